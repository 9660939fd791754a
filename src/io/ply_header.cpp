// PLY header parsing: the magic line, format, comments, elements and typed properties.
#include "io/ply_header.h"

#include <algorithm>
#include <charconv>
#include <sstream>
#include <utility>

#include "core/error.h"
#include "core/printable_text.h"

namespace glint {

namespace {

bool parsePlyType(const std::string& word, PlyType& type) {
  static const std::pair<const char*, PlyType> kNames[] = {
      {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& [name, value] : kNames) {
    if (word == name) {
      type = value;
      return true;
    }
  }
  return false;
}

// The text of a comment line after "comment" and the one blank that separates it.
std::string commentText(const std::string& line) {
  size_t start = std::string("comment").size();
  if (start < line.size() && (line[start] == ' ' || line[start] == '\t')) ++start;
  return line.substr(std::min(start, line.size()));
}

}  // namespace

bool PlyElement::hasLists() const {
  return std::any_of(properties.begin(), properties.end(), [](const PlyProperty& p) { return p.isList; });
}

size_t PlyElement::rowSize() const {
  size_t size = 0;
  for (const PlyProperty& p : properties) size += plyTypeSize(p.type);
  return size;
}

PlyHeader parsePlyHeader(std::istream& in, const std::string& path) {
  auto fail = [&](const std::string& problem) -> Error { return Error(path, problem); };
  std::string line;
  if (!std::getline(in, line) || (line != "ply" && line != "ply\r")) throw fail("not a PLY file (no 'ply' magic line)");
  PlyHeader header;
  bool sawFormat = false;
  for (int lineNumber = 2;; ++lineNumber) {
    if (!std::getline(in, line)) throw fail("PLY header has no end_header line");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    // Quoted escaped: the "header" of a binary file that is not PLY is arbitrary bytes.
    std::string where = " (header line " + std::to_string(lineNumber) + ": '" + printableText(line) + "')";
    if (keyword == "end_header") break;
    if (keyword == "comment") {
      header.comments.push_back(commentText(line));
      continue;
    }
    if (keyword.empty() || keyword == "obj_info") continue;
    if (keyword == "format") {
      std::string format, version;
      words >> format >> version;
      if (format == "binary_little_endian") header.format = PlyFormat::BinaryLittleEndian;
      else if (format == "binary_big_endian") header.format = PlyFormat::BinaryBigEndian;
      else if (format == "ascii") header.format = PlyFormat::Ascii;
      else throw fail("unsupported PLY format" + where);
      if (version != "1.0") throw fail("unsupported PLY format version" + where);
      sawFormat = true;
    } else if (keyword == "element") {
      PlyElement element;
      std::string count;
      words >> element.name >> count;
      auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), element.count);
      if (element.name.empty() || ec != std::errc() || end != count.data() + count.size()) {
        throw fail("malformed element line" + where);
      }
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) throw fail("property before any element" + where);
      PlyProperty property;
      std::string type;
      words >> type;
      if (type == "list") {
        std::string countType, itemType;
        words >> countType >> itemType;
        property.isList = true;
        if (!parsePlyType(countType, property.countType) || !parsePlyType(itemType, property.type)) {
          throw fail("unknown PLY list type" + where);
        }
        if (property.countType == PlyType::Float32 || property.countType == PlyType::Float64) {
          throw fail("PLY list count must be an integer type" + where);
        }
      } else if (!parsePlyType(type, property.type)) {
        throw fail("unknown PLY property type '" + printableText(type) + "'" + where);
      }
      words >> property.name;
      if (property.name.empty()) throw fail("property without a name" + where);
      for (const PlyProperty& other : header.elements.back().properties) {
        if (other.name == property.name)
          throw fail("duplicate property '" + printableText(property.name) + "'" + where);
      }
      header.elements.back().properties.push_back(std::move(property));
    } else {
      throw fail("unknown PLY header keyword '" + printableText(keyword) + "'" + where);
    }
  }
  if (!sawFormat) throw fail("PLY header has no format line");
  return header;
}

}  // namespace glint
