// Tests of reading JSON files: one error naming the file, and nesting bounded before the
// recursive parser sees it (a file of 100,000 brackets overflowed the stack, issue 39); and
// of writing floats as their shortest decimal.
#include "io/json_file.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "common/expect_error.h"
#include "core/atomic_file.h"
#include "io/temp_folder.h"
#include "math/rng.h"

namespace glint {
namespace {

using test::expectErrorNaming;

TEST(JsonFile, DeepNestingIsRefusedBeforeParsing) {
  test::TempFolder folder;
  const auto deep = folder / "capture.json";
  writeTextAtomically(deep, "{\"photo_transfer\": " + std::string(100000, '[') + std::string(100000, ']') + "}");
  expectErrorNaming([&] { readJsonFile(deep); }, deep, {"nest deeper than 256 levels", "at byte 274"});
}

TEST(JsonFile, NestingCountsBracketsOutsideStringsOnly) {
  EXPECT_NO_THROW(checkJsonNesting(std::string(kMaxJsonNesting, '[') + std::string(kMaxJsonNesting, ']'), "f"));
  EXPECT_THROW(checkJsonNesting(std::string(kMaxJsonNesting + 1, '['), "f"), Error);
  // Brackets inside strings, escaped quotes included, are text.
  EXPECT_NO_THROW(checkJsonNesting("{\"a\": \"" + std::string(1000, '[') + "\\\"" + std::string(1000, '{') + "\"}", "f"));
  test::TempFolder folder;
  const auto text = folder / "ok.json";
  writeTextAtomically(text, "{\"name\": \"[[[[\", \"list\": [[1], [2]]}");
  EXPECT_EQ(readJsonFile(text)["list"][1][0], 2);
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

TEST(JsonFile, FloatsAreWrittenAsTheirShortestDecimalAndReadBackExactly) {
  EXPECT_EQ(nlohmann::json(jsonNumber(0.9f)).dump(), "0.9");
  EXPECT_EQ(nlohmann::json(jsonNumber(1e-3f)).dump(), "0.001");
  EXPECT_EQ(nlohmann::json(jsonNumber(0.005f)).dump(), "0.005");
  // Every float comes back as itself through the JSON text, whatever its magnitude.
  Rng rng(7);
  for (int i = 0; i < 200000; ++i) {
    const uint32_t bits = rng.nextUint();
    float value;
    std::memcpy(&value, &bits, sizeof value);
    if (!std::isfinite(value)) continue;
    const nlohmann::json parsed = nlohmann::json::parse(nlohmann::json(jsonNumber(value)).dump());
    ASSERT_EQ(parsed.get<float>(), value) << nlohmann::json(jsonNumber(value)).dump();
  }
}

}  // namespace
}  // namespace glint
