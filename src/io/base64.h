// Base64 (RFC 4648, standard alphabet, padded): how binary files are embedded in text,
// e.g. PNG images in data: URIs of a self-contained HTML page.
#pragma once

#include <string>
#include <string_view>

namespace glint {

// "Man" -> "TWFu", "M" -> "TQ==". No line breaks.
std::string encodeBase64(std::string_view bytes);

}  // namespace glint
