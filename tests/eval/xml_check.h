// A small well-formedness check of XML-like markup for tests of generated SVG and HTML:
// tags nest and close, attribute values are quoted, and text holds no raw < or stray &.
#pragma once

#include <cctype>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace glint::test {

// Empty when well formed, else a description of the first problem. HTML's void elements
// (meta, img, br, ...) may stay unclosed when html is set; <!DOCTYPE> is skipped.
inline std::string markupProblem(const std::string& text, bool html = false) {
  static const std::set<std::string> kVoid = {"meta", "img", "br", "hr", "link", "input"};
  static const std::regex kEntity("^&(amp|lt|gt|quot|#39|middot|deg|#[0-9]+);");
  std::vector<std::string> open;
  size_t i = 0;
  while (i < text.size()) {
    char c = text[i];
    if (c == '&') {
      std::smatch m;
      std::string rest = text.substr(i, 12);
      if (!std::regex_search(rest, m, kEntity)) return "stray & at " + std::to_string(i);
      i += size_t(m.length(0));
      continue;
    }
    if (c == '>') return "raw > in text at " + std::to_string(i);
    if (c != '<') {
      ++i;
      continue;
    }
    if (text.compare(i, 9, "<!DOCTYPE") == 0) {
      i = text.find('>', i) + 1;
      continue;
    }
    bool closing = i + 1 < text.size() && text[i + 1] == '/';
    size_t j = i + (closing ? 2 : 1);
    size_t nameStart = j;
    while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '-')) ++j;
    std::string name = text.substr(nameStart, j - nameStart);
    if (name.empty()) return "raw < in text at " + std::to_string(i);
    // Attributes: name="value" pairs with no < or " inside the value.
    bool selfClosing = false;
    while (true) {
      while (j < text.size() && std::isspace(static_cast<unsigned char>(text[j]))) ++j;
      if (j >= text.size()) return "unterminated tag <" + name;
      if (text[j] == '>') break;
      if (text.compare(j, 2, "/>") == 0) {
        selfClosing = true;
        ++j;
        break;
      }
      if (closing) return "attributes in closing tag </" + name;
      size_t attrStart = j;
      while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '-' || text[j] == ':'))
        ++j;
      if (j == attrStart || text.compare(j, 2, "=\"") != 0) return "unquoted attribute in <" + name;
      size_t end = text.find('"', j + 2);
      if (end == std::string::npos) return "unterminated attribute in <" + name;
      std::string value = text.substr(j + 2, end - j - 2);
      if (value.find('<') != std::string::npos) return "raw < in an attribute of <" + name;
      j = end + 1;
    }
    i = j + 1;
    if (closing) {
      if (open.empty() || open.back() != name)
        return "</" + name + "> closes " + (open.empty() ? std::string("nothing") : "<" + open.back() + ">");
      open.pop_back();
    } else if (!selfClosing && !(html && kVoid.count(name))) {
      open.push_back(name);
      if (name == "style") {  // CSS is not markup: skip to its end tag
        size_t end = text.find("</style>", i);
        if (end == std::string::npos) return "unterminated <style>";
        i = end;
      }
    }
  }
  if (!open.empty()) return "<" + open.back() + "> is never closed";
  return "";
}

}  // namespace glint::test
