// gzip compression (RFC 1952) in memory, through zlib: the outer layer of .spz files.
#pragma once

#include <string>
#include <string_view>

namespace glint {

// The gzip stream of `bytes` (deflate at zlib's default level, a gzip header and trailer).
std::string gzipCompress(std::string_view bytes);

}  // namespace glint
