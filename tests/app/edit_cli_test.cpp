// `glint edit` and `--edits` end to end: the baked scene loads with the expected count and
// positions; render and eval apply edits and report refit / rebuild costs; bad edit files
// and existing outputs are refused with a message naming them and a non-zero exit.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/run_glint.h"
#include "io/temp_folder.h"
#include "render/gaussian_layers.h"
#include "scene/gaussian_ply.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::Outcome;
using test::runGlint;

// 40 Gaussians near the origin of builtin:spheres' cameras: 20 at x < 0 and 20 at x > 0.
GaussianScene twoClusters() {
  GaussianScene scene;
  scene.resize(40);
  for (size_t i = 0; i < scene.size(); ++i) {
    float side = i < 20 ? -0.4f : 0.4f;
    scene.position[i] = {side + 0.05f * float(i % 4), 0.5f + 0.05f * float(i % 5), 0.04f * float(i % 3)};
    scene.logScale[i] = Vec3f(std::log(0.1f));
    scene.opacityLogit[i] = 1.0f;
    scene.diffuse[i] = {0.5f, 0.4f, 0.3f};
    scene.normal[i] = {0, 1, 0};
    scene.roughness[i] = i < 20 ? 0.05f : 0.6f;
    scene.f0[i] = Rgb(0.9f);
  }
  return scene;
}

// Duplicates the left cluster 1 m up, then makes everything but the left cluster rough:
// the right cluster and, since selections see the scene as it stands, the copies.
const char* kEdits = R"({
  "glint_edits": 1,
  "selections": {
    "left": {"box": {"min": [-1, 0, -0.5], "max": [0, 1.5, 0.5]}},
    "right": {"difference": ["all", "left"]},
    "all": "everything",
    "nothing": {"sphere": {"center": [9, 9, 9], "radius": 0.1}}
  },
  "operations": [
    {"op": "duplicate", "selection": "left", "offset": [0, 0, 1]},
    {"op": "roughness", "selection": "right", "set": 0.9},
    {"op": "delete", "selection": "nothing"}
  ]
})";

// Moves everything without changing the count, so render can refit.
const char* kMoveEdits = R"({"glint_edits": 1, "selections": {"all": "everything"},
  "operations": [{"op": "translate", "selection": "all", "offset": [0.1, 0, 0]}]})";

class EditCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    writeGaussianPly(folder_ / "scene.ply", twoClusters());
    std::ofstream(folder_ / "edits.json") << kEdits;
    std::ofstream(folder_ / "move.json") << kMoveEdits;
  }
  std::string path(const std::string& name) const { return (folder_ / name).string(); }
  test::TempFolder folder_;
};

TEST_F(EditCliTest, EditBakesTheEditsIntoANewScene) {
  Outcome edit = runGlint("edit " + path("scene.ply") + " " + path("edits.json") + " -o " + path("out.ply"));
  ASSERT_EQ(edit.status, 0) << edit.output;
  // Per-operation counts and the warning for the empty selection.
  EXPECT_NE(edit.output.find("operations[0] duplicate \"left\": 20 Gaussians"), std::string::npos) << edit.output;
  EXPECT_NE(edit.output.find("operations[1] roughness \"right\": 40 Gaussians"), std::string::npos) << edit.output;
  EXPECT_NE(edit.output.find("warning: operations[2] delete \"nothing\""), std::string::npos) << edit.output;
  EXPECT_NE(edit.output.find("40 -> 60"), std::string::npos) << edit.output;

  GaussianScene original = twoClusters();
  GaussianScene edited = readGaussianPly(path("out.ply"));
  ASSERT_EQ(edited.size(), 60u);
  for (size_t i = 0; i < 20; ++i) {
    EXPECT_EQ(edited.position[40 + i], original.position[i] + Vec3f(0, 0, 1));
    EXPECT_EQ(edited.roughness[i], 0.05f);      // the left cluster
    EXPECT_EQ(edited.roughness[20 + i], 0.9f);  // the right cluster
    EXPECT_EQ(edited.roughness[40 + i], 0.9f);  // the copies of the left one
  }

  // The output exists now: refused without --force, replaced with it.
  Outcome again = runGlint("edit " + path("scene.ply") + " " + path("move.json") + " -o " + path("out.ply"));
  EXPECT_NE(again.status, 0);
  EXPECT_NE(again.output.find("out.ply"), std::string::npos) << again.output;
  EXPECT_NE(again.output.find("--force"), std::string::npos) << again.output;
  EXPECT_EQ(readGaussianPly(path("out.ply")).size(), 60u);
  Outcome forced =
      runGlint("edit " + path("scene.ply") + " " + path("move.json") + " -o " + path("out.ply") + " --force");
  ASSERT_EQ(forced.status, 0) << forced.output;
  EXPECT_EQ(readGaussianPly(path("out.ply")).size(), 40u);
}

// Issue 19: 40 duplications of everything (2.7 kB) asked for 40 x 2^40 Gaussians and ended
// in std::bad_alloc; the file is refused, naming it and the limit, and nothing is written.
TEST_F(EditCliTest, FortyDuplicationsAreRefusedNamingTheFileAndTheLimit) {
  std::string operations;
  for (int i = 0; i < 40; ++i)
    operations += std::string(i ? ", " : "") + R"({"op": "duplicate", "selection": "all", "offset": [0, 0, 0.01]})";
  std::ofstream(folder_ / "forty.json") << R"({"glint_edits": 1, "selections": {"all": "everything"}, "operations": [)"
                                        << operations << "]}";
  Outcome edit = runGlint("edit " + path("scene.ply") + " " + path("forty.json") + " -o " + path("o.ply") +
                          " --max-gaussians 5000");
  EXPECT_NE(edit.status, 0) << edit.output;
  // 40 Gaussians double at each operation: the 7th would make 5120.
  for (const char* part : {"forty.json", "operations[6] duplicate", "5120", "limit of 5000", "--max-gaussians"})
    EXPECT_NE(edit.output.find(part), std::string::npos) << part << " in " << edit.output;
  EXPECT_FALSE(fs::exists(folder_ / "o.ply"));
}

TEST_F(EditCliTest, BadEditFilesAreNamedWithANonZeroExit) {
  std::ofstream(folder_ / "typo.json") << R"({"glint_edits": 1, "selections": {"all": "everything"},
    "operations": [{"op": "rotat", "selection": "all", "axis": [0, 1, 0], "angle_degrees": 5, "pivot": [0, 0, 0]}]})";
  std::ofstream(folder_ / "broken.json") << "{\"glint_edits\": 1,";
  Outcome synth = runGlint("synth builtin:spheres -o " + path("D") + " --train 1 --test 1 --res 16x12 --spp 1");
  ASSERT_EQ(synth.status, 0) << synth.output;
  struct Case {
    std::string args, file, problem;  // the message names the file and the problem
  };
  std::string render = "render " + path("scene.ply") + " --dataset " + path("D") + " -o " + path("R");
  std::string eval = "eval " + path("scene.ply") + " --dataset " + path("D") + " -o " + path("m.json");
  std::string edit = "edit " + path("scene.ply") + " ";
  for (const Case& c : std::vector<Case>{
           {edit + path("typo.json") + " -o " + path("o.ply"), "typo.json", "operations[0]: unknown operation \"rotat\""},
           {edit + path("broken.json") + " -o " + path("o.ply"), "broken.json", "not valid JSON"},
           {edit + path("absent.json") + " -o " + path("o.ply"), "absent.json", "absent.json"},
           {render + " --edits " + path("typo.json"), "typo.json", "unknown operation \"rotat\""},
           {eval + " --edits " + path("typo.json"), "typo.json", "unknown operation \"rotat\""},
       }) {
    Outcome bad = runGlint(c.args);
    EXPECT_NE(bad.status, 0) << c.args;
    EXPECT_NE(bad.output.find(c.file), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find(c.problem), std::string::npos) << bad.output;
  }
  EXPECT_FALSE(fs::exists(folder_ / "o.ply"));
}

TEST_F(EditCliTest, RenderAndEvalApplyEditsAndReportRefitAndRebuildCosts) {
  Outcome synth = runGlint("synth builtin:spheres -o " + path("D") + " --train 1 --test 2 --res 24x18 --spp 1");
  ASSERT_EQ(synth.status, 0) << synth.output;
  // Same count: both costs are measured and one structure is kept.
  Outcome moved = runGlint("render " + path("scene.ply") + " --dataset " + path("D") + " -o " + path("R") +
                           " --edits " + path("move.json") + " --bounces 1");
  ASSERT_EQ(moved.status, 0) << moved.output;
  EXPECT_NE(moved.output.find("refit"), std::string::npos) << moved.output;
  EXPECT_NE(moved.output.find("rebuild"), std::string::npos) << moved.output;
  EXPECT_NE(moved.output.find("kept the"), std::string::npos) << moved.output;
  EXPECT_TRUE(fs::exists(folder_ / "R" / "render" / "render_0001.exr"));
  // A changed count can only be rebuilt; eval records the edit file.
  Outcome duplicated = runGlint("eval " + path("scene.ply") + " --dataset " + path("D") + " -o " + path("m.json") +
                                " --edits " + path("edits.json") + " --spp 1");
  ASSERT_EQ(duplicated.status, 0) << duplicated.output;
  EXPECT_NE(duplicated.output.find("no refit"), std::string::npos) << duplicated.output;
  EXPECT_NE(duplicated.output.find("60 Gaussians"), std::string::npos) << duplicated.output;
  std::ifstream in(folder_ / "m.json");
  nlohmann::json metrics = nlohmann::json::parse(in);
  EXPECT_EQ(metrics["edits"], path("edits.json"));
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

// Relighting on `glint edit` (the default): deleting a plate that shades the floor brightens
// the floor under it, moving it by zero changes no colour at all, and --no-relight keeps
// every colour.
TEST(EditRelightCli, DeletedPlateBrightensTheFloorAndANullMoveChangesNothing) {
  test::TempFolder folder;
  auto path = [&](const std::string& name) { return (folder / name).string(); };
  const test::PlateRoom room = test::plateRoom();
  const GaussianScene& scene = room.scene;
  writeGaussianPly(folder / "scene.ply", scene);
  const char* selection = R"("selections": {"plate": {"box": {"min": [-0.2, -0.2, 0.3], "max": [0.2, 0.2, 0.5]}}})";
  std::ofstream(folder / "delete.json") << "{\"glint_edits\": 1, " << selection
                                        << R"(, "operations": [{"op": "delete", "selection": "plate"}]})";
  std::ofstream(folder / "still.json")
      << "{\"glint_edits\": 1, " << selection
      << R"(, "operations": [{"op": "translate", "selection": "plate", "offset": [0, 0, 0]}]})";

  // Relighting is on by default.
  Outcome deleted = runGlint("edit " + path("scene.ply") + " " + path("delete.json") + " -o " + path("deleted.ply"));
  ASSERT_EQ(deleted.status, 0) << deleted.output;
  EXPECT_NE(deleted.output.find("glint edit: relit "), std::string::npos) << deleted.output;
  GaussianScene relit = readGaussianPly(path("deleted.ply"));
  ASSERT_EQ(relit.size(), room.floorEnd);
  // The floor Gaussian nearest the centre, under the plate, gains light; one in a far corner
  // barely changes.
  const size_t centre = room.centre;
  size_t corner = room.floorBegin;
  for (size_t i = room.floorBegin; i < room.floorEnd; ++i)
    if (length(scene.position[i]) > length(scene.position[corner])) corner = i;
  EXPECT_GT(relit.diffuse[centre].x, 1.15f * scene.diffuse[centre].x);
  EXPECT_NEAR(relit.diffuse[corner].x, scene.diffuse[corner].x, 0.05f * scene.diffuse[corner].x);
  // The ceiling faces away from the plate's region: it keeps its colour exactly.
  EXPECT_EQ(relit.diffuse[0], scene.diffuse[0]);

  Outcome still = runGlint("edit " + path("scene.ply") + " " + path("still.json") + " -o " + path("still.ply") +
                           " --relight");
  ASSERT_EQ(still.status, 0) << still.output;
  EXPECT_NE(still.output.find("relit 0 of the"), std::string::npos) << still.output;
  GaussianScene same = readGaussianPly(path("still.ply"));
  ASSERT_EQ(same.size(), scene.size());
  for (size_t i = 0; i < scene.size(); ++i) EXPECT_EQ(same.diffuse[i], scene.diffuse[i]) << i;

  // --no-relight keeps every trained colour, also under a deletion.
  Outcome kept = runGlint("edit " + path("scene.ply") + " " + path("delete.json") + " -o " + path("kept.ply") +
                          " --no-relight");
  ASSERT_EQ(kept.status, 0) << kept.output;
  EXPECT_EQ(kept.output.find("relit"), std::string::npos) << kept.output;
  GaussianScene unrelit = readGaussianPly(path("kept.ply"));
  ASSERT_EQ(unrelit.size(), room.floorEnd);
  for (size_t i = 0; i < unrelit.size(); ++i) EXPECT_EQ(unrelit.diffuse[i], scene.diffuse[i]) << i;
}

}  // namespace
}  // namespace glint
