// A plain Base64 decoder for tests, written independently of io/base64.cpp so that it can
// check it: turns data: URIs back into the bytes they embed.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace glint::test {

// Decodes padded standard Base64; nullopt for a character outside the alphabet or a
// length that is not a multiple of four.
inline std::optional<std::string> decodeBase64(std::string_view text) {
  if (text.size() % 4 != 0) return std::nullopt;
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    return -1;
  };
  std::string bytes;
  for (size_t i = 0; i < text.size(); i += 4) {
    int padding = (text[i + 3] == '=') + (text[i + 2] == '=');
    if (padding > 0 && i + 4 != text.size()) return std::nullopt;
    unsigned bits = 0;
    for (int k = 0; k < 4; ++k) {
      int v = k >= 4 - padding ? 0 : value(text[i + k]);
      if (v < 0) return std::nullopt;
      bits = bits * 64 + unsigned(v);
    }
    bytes += char(bits >> 16);
    if (padding < 2) bytes += char((bits >> 8) & 255);
    if (padding < 1) bytes += char(bits & 255);
  }
  return bytes;
}

}  // namespace glint::test
