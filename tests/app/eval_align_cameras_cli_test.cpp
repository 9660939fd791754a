// `glint eval --align-cameras`: test views whose cameras are a degree off their images score
// as they are without it, and close to their true cameras' score with it, the scene held fixed.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "app/run_glint.h"
#include "common/corner_scene.h"
#include "io/temp_folder.h"
#include "raytrace/gaussian_tracer.h"
#include "scene/dataset.h"
#include "scene/gaussian_ply.h"
#include "train/train_config.h"
#include "train/training_eval.h"

namespace glint {
namespace {

namespace fs = std::filesystem;

nlohmann::json readMetrics(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// The corner scene as a .ply, and a dataset of it whose test views were rendered from the
// true cameras but whose transforms hold `degrees` / `distance` disturbed ones (or the true
// ones at 0).
void writeCornerFiles(const fs::path& root, const std::string& name, double degrees, double distance) {
  const GaussianScene scene = test::cornerScene();
  writeGaussianPly(root / "corner.ply", scene);
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer("fast");
  tracer->build(scene, TrainConfig{}.trace);
  for (const char* splitName : {"train", "test"}) {
    DatasetSplit split;
    split.name = splitName;
    split.width = test::kCornerWidth;
    split.height = test::kCornerHeight;
    for (int v = 0; v < 2; ++v) {
      const Camera truth = test::cornerCamera(2 * v + 1);
      const std::string file = std::string(splitName) + "/render/render_000" + std::to_string(v);
      split.views.push_back({file, degrees > 0 ? test::disturbed(truth, degrees, distance, v) : truth, {}});
      writeViewBuffers(root / name, split.views.back(),
                       renderScoredView(*tracer, truth, scoringSettings(16, PathSettings{}), uint64_t(v)),
                       ImageFormat::Exr);
    }
    writeTransforms(root / name, split);
  }
}

TEST(EvalAlignCameras, ScoresTestViewsAtTheCamerasTheirImagesWereSeenFrom) {
  test::TempFolder folder;
  const fs::path root = folder.path();
  writeCornerFiles(root, "true", 0.0, 0.0);
  writeCornerFiles(root, "disturbed", 1.2, 0.05);
  const std::string scene = (root / "corner.ply").string();

  auto eval = [&](const std::string& dataset, const std::string& flags, const std::string& out) {
    test::Outcome o = test::runGlint("eval " + scene + " --dataset " + (root / dataset).string() + " --spp 16 --seed 7 " +
                                     flags + " -o " + (root / out).string());
    EXPECT_EQ(o.status, 0) << o.output;
    return std::pair{readMetrics(root / out), o.output};
  };
  const auto [truth, truthOutput] = eval("true", "", "true.json");
  const auto [off, offOutput] = eval("disturbed", "", "off.json");
  const auto [aligned, alignedOutput] = eval("disturbed", "--align-cameras", "aligned.json");

  const auto diffuse = [](const nlohmann::json& m) { return m["mean"]["diffuse"]["psnr"].get<double>(); };
  std::fprintf(stderr, "diffuse PSNR: true cameras %.2f dB, disturbed %.2f, disturbed and aligned %.2f\n",
               diffuse(truth), diffuse(off), diffuse(aligned));
  EXPECT_GT(diffuse(truth), diffuse(off) + 6.0);      // a degree costs decibels
  EXPECT_GT(diffuse(aligned), diffuse(off) + 5.0);    // most of which the alignment wins back
  EXPECT_FALSE(off.contains("camera_alignment"));
  ASSERT_TRUE(aligned.contains("camera_alignment"));
  EXPECT_EQ(aligned["camera_alignment"]["views_moved"], 2);
  EXPECT_GT(aligned["camera_alignment"]["degrees_median"].get<double>(), 0.5);
  EXPECT_NE(alignedOutput.find("--align-cameras moved 2 of 2 cameras"), std::string::npos) << alignedOutput;
}

}  // namespace
}  // namespace glint
