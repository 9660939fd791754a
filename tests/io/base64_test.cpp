// Base64 encoding against the test vectors of RFC 4648 and an independent decoder.
#include "io/base64.h"

#include <gtest/gtest.h>

#include <string>

#include "common/base64_decode.h"

namespace glint {
namespace {

TEST(Base64Test, MatchesTheRfc4648Vectors) {
  EXPECT_EQ(encodeBase64(""), "");
  EXPECT_EQ(encodeBase64("f"), "Zg==");
  EXPECT_EQ(encodeBase64("fo"), "Zm8=");
  EXPECT_EQ(encodeBase64("foo"), "Zm9v");
  EXPECT_EQ(encodeBase64("foob"), "Zm9vYg==");
  EXPECT_EQ(encodeBase64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(encodeBase64("foobar"), "Zm9vYmFy");
}

TEST(Base64Test, EveryByteValueRoundTrips) {
  // All 256 byte values, at each of the three positions of a group (lengths 256..258).
  for (int extra = 0; extra < 3; ++extra) {
    std::string bytes;
    for (int i = 0; i < 256 + extra; ++i) bytes += char((i * 7 + extra) & 255);
    std::string text = encodeBase64(bytes);
    EXPECT_EQ(text.size(), (bytes.size() + 2) / 3 * 4);
    EXPECT_EQ(text.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/="),
              std::string::npos);
    EXPECT_EQ(test::decodeBase64(text), bytes) << extra;
  }
  EXPECT_EQ(encodeBase64(std::string("\xff\xfe\xfd", 3)), "//79");  // the last two letters of the alphabet
}

}  // namespace
}  // namespace glint
