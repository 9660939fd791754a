// Tests of the escaping of file contents quoted in error messages.
#include "core/printable_text.h"

#include <gtest/gtest.h>

#include <string>

namespace glint {
namespace {

TEST(PrintableText, PrintableAsciiIsKept) {
  EXPECT_EQ(printableText("format binary_little_endian 1.0"), "format binary_little_endian 1.0");
  EXPECT_EQ(printableText(""), "");
}

TEST(PrintableText, ControlAndHighBytesAreEscaped) {
  EXPECT_EQ(printableText(std::string("a\x1b[31mb\n\x7f\xff\0z", 12)), "a\\x1B[31mb\\x0A\\x7F\\xFF\\x00z");
}

TEST(PrintableText, LongTextIsCut) {
  EXPECT_EQ(printableText(std::string(100, 'a'), 4), "aaaa... (100 bytes)");
  EXPECT_EQ(printableText("abcd", 4), "abcd");
  EXPECT_EQ(printableText(std::string(100, 'a'), std::string::npos), std::string(100, 'a'));
}

}  // namespace
}  // namespace glint
