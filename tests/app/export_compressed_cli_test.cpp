// `glint export --format spz|compressed-ply` and `--bake-reflections` end to end: the files
// they write, the SH degree of a baked 3DGS export, and the flag combinations refused.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "app/run_glint.h"
#include "common/random_gaussians.h"
#include "io/ply.h"
#include "io/temp_folder.h"
#include "scene/gaussian_ply.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::runGlint;

class ExportCompressedCli : public ::testing::Test {
 protected:
  void SetUp() override { writeGaussianPly(scene(), randomScene(40, 9)); }
  std::string scene() const { return (folder_ / "scene.ply").string(); }
  std::string out(const std::string& name) const { return (folder_ / name).string(); }

  test::TempFolder folder_;
};

TEST_F(ExportCompressedCli, WritesSpzAndCompressedPly) {
  test::Outcome spz = runGlint("export " + scene() + " --format spz -o " + out("a.spz"));
  ASSERT_EQ(spz.status, 0) << spz.output;
  const std::string bytes = test::readBytes(out("a.spz"));
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(uint8_t(bytes[0]), 0x1f);  // gzip
  EXPECT_EQ(uint8_t(bytes[1]), 0x8b);
  test::Outcome ply = runGlint("export " + scene() + " --format compressed-ply -o " + out("a.compressed.ply"));
  ASSERT_EQ(ply.status, 0) << ply.output;
  EXPECT_EQ(readPly(out("a.compressed.ply"), "chunk").count, 1u);
}

TEST_F(ExportCompressedCli, BakedThreeDgsExportHasTheAskedShDegree) {
  // A bare .ply has no dataset: directions over the sphere, with a note.
  test::Outcome run = runGlint("export " + scene() + " --format 3dgs --bake-reflections --sh-degree 1 "
                               "--bake-directions 8 -o " + out("baked.ply"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("samples every direction"), std::string::npos) << run.output;
  PlyTable table = readPly(out("baked.ply"));
  EXPECT_TRUE(table.has("f_rest_8"));
  EXPECT_FALSE(table.has("f_rest_9"));
}

TEST_F(ExportCompressedCli, RefusesBakingFlagsThatCannotApply) {
  struct Case {
    std::string args, expected;
  } cases[] = {
      {"--format spz --bake-ridge 0.1", "--bake-ridge"},          // without --bake-reflections
      {"--format spz --colour linear", "--colour linear"},        // spz is display-referred
      {"--format glint --bake-reflections", "--bake-reflections"},  // Glint's layout has no SH
      {"--format spz --bake-reflections --sh-degree 4", "--sh-degree"},
  };
  for (const Case& c : cases) {
    test::Outcome run = runGlint("export " + scene() + " " + c.args + " -o " + out("x.spz"));
    EXPECT_NE(run.status, 0) << c.args;
    EXPECT_NE(run.output.find(c.expected), std::string::npos) << c.args << ": " << run.output;
  }
  EXPECT_FALSE(fs::exists(out("x.spz")));
}

}  // namespace
}  // namespace glint
