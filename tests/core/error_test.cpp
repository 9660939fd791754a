// Tests of glint::Error: the message names the file, and the file is kept separately.
#include "core/error.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace glint {
namespace {

TEST(Error, FileAndProblem) {
  Error e("scene/transforms.json", "frame 3 has no file_path");
  EXPECT_STREQ(e.what(), "scene/transforms.json: frame 3 has no file_path");
  EXPECT_EQ(e.file(), "scene/transforms.json");
}

TEST(Error, MessageOnlyHasNoFile) {
  Error e("cannot create an Embree device");
  EXPECT_STREQ(e.what(), "cannot create an Embree device");
  EXPECT_EQ(e.file(), "");
}

TEST(Error, CaughtAsRuntimeError) {
  try {
    throw Error("a.png", "truncated");
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "a.png: truncated");
  }
}

TEST(Check, PassingCheckDoesNothing) {
  GLINT_CHECK(1 + 1 == 2, "arithmetic");
  GLINT_CHECK(true);
  SUCCEED();
}

TEST(CheckDeathTest, FailingCheckAbortsWithTheCondition) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(GLINT_CHECK(2 < 1, "ordering broken"), "internal check failed.*2 < 1: ordering broken");
}

}  // namespace
}  // namespace glint
