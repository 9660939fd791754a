// Escapes file contents quoted in error messages (see printable_text.h).
#include "core/printable_text.h"

namespace glint {

std::string printableText(std::string_view text, size_t maxLength) {
  static const char kHex[] = "0123456789ABCDEF";
  std::string out;
  size_t shown = text.size() <= maxLength ? text.size() : maxLength;
  out.reserve(shown + 3);
  for (size_t i = 0; i < shown; ++i) {
    unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7F) {
      out += char(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (shown < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

}  // namespace glint
