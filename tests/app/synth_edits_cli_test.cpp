// `glint synth --edits`: the edited ground truth keeps the unedited dataset's cameras (also
// when the edit changes the scene's bounds), differs in its images, prints the edit report,
// and rejects a bad edit file by name.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "app/run_glint.h"
#include "io/image.h"
#include "synth/gltf_test_files.h"

namespace {

namespace fs = std::filesystem;

using glint::test::Outcome;
using glint::test::runGlint;

class SynthEditsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("glint_synth_edits_test_" + std::to_string(getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(root_ / name) << text; }
  std::string read(const std::string& name) const {
    std::ifstream in(root_ / name);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
  // Synthesises one tiny dataset of `scene` into folder `out`, with extra arguments.
  Outcome synth(const std::string& scene, const std::string& out, const std::string& extra = "",
                int trainViews = 1) const {
    return runGlint("synth " + scene + " -o " + path(out) + " --train " + std::to_string(trainViews) +
                    " --test 1 --res 64x48 --spp 4 " + extra);
  }
  // Sum of absolute differences of the two datasets' first test render.
  double testRenderDifference(const std::string& a, const std::string& b) const {
    glint::Image first = glint::readImage(root_ / a / "test/render/render_0000.exr");
    glint::Image second = glint::readImage(root_ / b / "test/render/render_0000.exr");
    EXPECT_EQ(first.pixels.size(), second.pixels.size());
    double sum = 0;
    for (size_t i = 0; i < std::min(first.pixels.size(), second.pixels.size()); ++i)
      sum += std::abs(first.pixels[i] - second.pixels[i]);
    return sum;
  }
  void expectSameCameras(const std::string& a, const std::string& b) const {
    for (const char* split : {"transforms_train.json", "transforms_test.json"}) {
      std::string first = read(a + "/" + split);
      EXPECT_FALSE(first.empty()) << split;
      EXPECT_EQ(first, read(b + "/" + split)) << split;
    }
  }
  fs::path root_;
};

TEST_F(SynthEditsTest, MovingASphereKeepsTheCamerasAndChangesTheImages) {
  // The red chrome sphere of builtin:spheres sits at (-1.3, 0.6, 0.3).
  write("move.json", R"({"glint_edits": 1,
    "selections": {"red": {"box": {"center": [-1.3, 0.6, 0.3], "half_extent": [0.1, 0.1, 0.1]}}},
    "operations": [{"op": "translate", "selection": "red", "offset": [0, 0.5, 0.6]}]})");
  Outcome plain = synth("builtin:spheres", "plain");
  ASSERT_EQ(plain.status, 0) << plain.output;
  Outcome edited = synth("builtin:spheres", "edited", "--edits " + path("move.json"));
  ASSERT_EQ(edited.status, 0) << edited.output;
  EXPECT_NE(edited.output.find("operations[0] translate \"red\": 1 node"), std::string::npos) << edited.output;
  expectSameCameras("plain", "edited");
  EXPECT_GT(testRenderDifference("plain", "edited"), 1.0);

  // An empty edit changes nothing: the same seed renders the same images.
  write("none.json", R"({"glint_edits": 1, "selections": {"far": {"sphere": {"center": [50, 0, 0], "radius": 1}}},
    "operations": [{"op": "delete", "selection": "far"}]})");
  Outcome unchanged = synth("builtin:spheres", "unchanged", "--edits " + path("none.json"));
  ASSERT_EQ(unchanged.status, 0) << unchanged.output;
  EXPECT_NE(unchanged.output.find("warning:"), std::string::npos) << unchanged.output;
  EXPECT_EQ(testRenderDifference("plain", "unchanged"), 0.0);

  // The test split does not depend on the number of training views, so `--train 1` renders
  // a comparison set quickly: the same test cameras and images as a full dataset.
  Outcome more = synth("builtin:spheres", "more", "", 3);
  ASSERT_EQ(more.status, 0) << more.output;
  EXPECT_EQ(read("plain/transforms_test.json"), read("more/transforms_test.json"));
  EXPECT_EQ(testRenderDifference("plain", "more"), 0.0);
}

TEST_F(SynthEditsTest, CamerasComeFromTheUneditedBoundsWhenTheSceneHasNoRig) {
  // Two quads (x in [0, 1] and [3, 4]) and no camera rig: cameras derive from the bounds,
  // which the edit stretches to x = 7 by moving the second quad.
  glint::test::GltfBuilder b;
  int mesh = glint::test::addQuadMesh(b);
  int left = b.add("nodes", {{"mesh", mesh}});
  int right = b.add("nodes", {{"mesh", mesh}, {"translation", {3, 0, 0}}});
  b.doc["scenes"] = {{{"nodes", {left, right}}}};
  b.doc["scene"] = 0;
  b.writeGlb(root_ / "quads.glb");
  write("stretch.json", R"({"glint_edits": 1,
    "selections": {"right": {"box": {"min": [3.3, 0.3, -0.2], "max": [3.7, 0.7, 0.2]}}},
    "operations": [{"op": "translate", "selection": "right", "offset": [3, 0, 0]}]})");
  Outcome plain = synth(path("quads.glb"), "plain");
  ASSERT_EQ(plain.status, 0) << plain.output;
  Outcome edited = synth(path("quads.glb"), "edited", "--edits " + path("stretch.json"));
  ASSERT_EQ(edited.status, 0) << edited.output;
  EXPECT_NE(edited.output.find("\"right\": 1 node"), std::string::npos) << edited.output;
  expectSameCameras("plain", "edited");
  EXPECT_GT(testRenderDifference("plain", "edited"), 1.0);
}

TEST_F(SynthEditsTest, ABadEditFileIsRejectedByName) {
  struct BadEdit {
    std::string file, operations, expected;  // expected: a fragment of the message
  };
  const BadEdit cases[] = {
      {"typo.json", R"([{"op": "rotat", "selection": "all"}])", "rotat"},
      // Deleting every node leaves nothing to render.
      {"empty.json", R"([{"op": "delete", "selection": "all"}])", "no geometry"},
      {"missing.json", "", "missing.json"},  // not written
  };
  for (const BadEdit& c : cases) {
    if (!c.operations.empty())
      write(c.file, R"({"glint_edits": 1, "selections": {"all": "everything"}, "operations": )" + c.operations + "}");
    Outcome bad = synth("builtin:spheres", "out", "--edits " + path(c.file));
    EXPECT_NE(bad.status, 0) << c.file;
    EXPECT_NE(bad.output.find(c.file), std::string::npos) << bad.output;
    EXPECT_NE(bad.output.find(c.expected), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(root_ / "out" / "transforms_test.json"));
  }
}

}  // namespace
