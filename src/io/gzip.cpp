// gzip compression with zlib's streaming API.
#include "io/gzip.h"

#include <zlib.h>

#include "core/error.h"

namespace glint {

namespace {

// windowBits 15 + 16: zlib's switch for a gzip header and trailer instead of zlib's own.
constexpr int kGzipWindowBits = 15 + 16;
constexpr size_t kChunkBytes = 1 << 16;

}  // namespace

std::string gzipCompress(std::string_view bytes) {
  z_stream stream{};
  GLINT_CHECK(deflateInit2(&stream, Z_DEFAULT_COMPRESSION, Z_DEFLATED, kGzipWindowBits, 8, Z_DEFAULT_STRATEGY) == Z_OK,
              "zlib deflateInit2 failed");
  std::string out;
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  stream.avail_in = uInt(bytes.size());
  GLINT_CHECK(bytes.size() == stream.avail_in, "gzipCompress: more than 4 GB in one stream");
  int status = Z_OK;
  while (status != Z_STREAM_END) {
    size_t used = out.size();
    out.resize(used + kChunkBytes);
    stream.next_out = reinterpret_cast<Bytef*>(out.data() + used);
    stream.avail_out = uInt(kChunkBytes);
    status = deflate(&stream, Z_FINISH);
    out.resize(used + kChunkBytes - stream.avail_out);
    GLINT_CHECK(status == Z_OK || status == Z_STREAM_END || status == Z_BUF_ERROR, "zlib deflate failed");
  }
  deflateEnd(&stream);
  return out;
}

}  // namespace glint
