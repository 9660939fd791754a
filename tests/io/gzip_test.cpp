// gzipCompress output is a gzip stream zlib's own reader turns back into the input.
#include "io/gzip.h"

#include <zlib.h>

#include <string>

#include <gtest/gtest.h>

#include "math/rng.h"

namespace glint {
namespace {

std::string gunzip(const std::string& compressed, size_t size) {
  std::string out(size + 16, '\0');
  z_stream stream{};
  EXPECT_EQ(inflateInit2(&stream, 15 + 16), Z_OK);
  stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  stream.avail_in = uInt(compressed.size());
  stream.next_out = reinterpret_cast<Bytef*>(out.data());
  stream.avail_out = uInt(out.size());
  EXPECT_EQ(inflate(&stream, Z_FINISH), Z_STREAM_END);
  out.resize(stream.total_out);
  inflateEnd(&stream);
  return out;
}

TEST(Gzip, RoundTripsThroughZlib) {
  Rng rng(3);
  std::string data;
  for (int i = 0; i < 300000; ++i) data.push_back(char(rng.nextUint() % 7));  // more than one output chunk
  std::string compressed = gzipCompress(data);
  ASSERT_GE(compressed.size(), 18u);
  EXPECT_EQ(uint8_t(compressed[0]), 0x1f);  // the gzip magic (RFC 1952)
  EXPECT_EQ(uint8_t(compressed[1]), 0x8b);
  EXPECT_LT(compressed.size(), data.size() / 2);
  EXPECT_EQ(gunzip(compressed, data.size()), data);
}

TEST(Gzip, EmptyInputGivesAValidStream) { EXPECT_EQ(gunzip(gzipCompress(""), 0), ""); }

}  // namespace
}  // namespace glint
