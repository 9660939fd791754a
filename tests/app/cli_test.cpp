// End-to-end tests of the `glint` program: the issue's synth/info scenario, render and eval
// of scenes and training runs, and clear errors with non-zero exits for bad input.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "app/run_glint.h"
#include "app/small_cloud.h"
#include "io/image.h"
#include "scene/gaussian_ply.h"
#include "synth/gltf_test_files.h"

namespace {

namespace fs = std::filesystem;

using glint::test::Outcome;
using glint::test::runGlint;
using glint::test::writeSmallCloud;

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() /
            ("glint_cli_test_" + std::to_string(getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string path(const std::string& name) const { return (root_ / name).string(); }
  fs::path root_;
};

TEST_F(CliTest, SynthOfTheSmallSpheresDatasetIsFastAndReportedClean) {
  auto start = std::chrono::steady_clock::now();
  Outcome synth = runGlint("synth builtin:spheres -o " + path("D") + " --train 4 --test 2 --res 64x48 --spp 64");
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(synth.status, 0) << synth.output;
  EXPECT_LT(seconds, 60.0);
  Outcome info = runGlint("info " + path("D"));
  EXPECT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("problems: none"), std::string::npos) << info.output;
  EXPECT_NE(info.output.find("64x48"), std::string::npos) << info.output;

  Outcome sheet = runGlint("sheet " + path("D") + " -o " + path("sheet.png") + " --rows 2");
  EXPECT_EQ(sheet.status, 0) << sheet.output;
  EXPECT_TRUE(fs::exists(path("sheet.png")));

  // A second synth into the same folder refuses without --force: nothing is overwritten.
  Outcome again = runGlint("synth builtin:spheres -o " + path("D") + " --train 1 --test 1 --res 8x8 --spp 1");
  EXPECT_NE(again.status, 0);
  EXPECT_NE(again.output.find("--force"), std::string::npos) << again.output;

  // Damage one buffer: info reports it and exits non-zero.
  fs::remove(root_ / "D" / "train" / "roughness" / "roughness_0002.exr");
  Outcome damaged = runGlint("info " + path("D"));
  EXPECT_NE(damaged.status, 0);
  EXPECT_NE(damaged.output.find("roughness_0002"), std::string::npos) << damaged.output;
}

struct BadInvocation {
  std::string args;
  std::string expected;  // a fragment the error message must contain
};

// Each invocation must fail with a non-zero exit and a message containing its fragment.
void expectEachRejected(std::span<const BadInvocation> cases) {
  for (const BadInvocation& c : cases) {
    Outcome bad = runGlint(c.args);
    EXPECT_NE(bad.status, 0) << c.args;
    EXPECT_NE(bad.output.find(c.expected), std::string::npos) << c.args << "\n" << bad.output;
  }
}

TEST_F(CliTest, BadInputGetsOneClearErrorAndANonZeroExit) {
  std::ofstream(path("not_a_scene.obj")) << "v 0 0 0\n";
  fs::create_directories(root_ / "precious");
  std::ofstream(root_ / "precious" / "notes.txt") << "mine\n";
  std::ofstream(path("broken.gltf")) << "{ this is not json";
  const BadInvocation cases[] = {
      {"synth builtin:nope -o " + path("x"), "builtin:spheres"},
      {"synth " + path("missing.gltf") + " -o " + path("x"), "missing.gltf"},
      {"synth " + path("not_a_scene.obj") + " -o " + path("x"), "not_a_scene.obj"},
      {"synth " + path("broken.gltf") + " -o " + path("x"), "broken.gltf"},
      {"synth builtin:spheres -o " + path("x") + " --res 0x10", "--res"},
      {"synth builtin:spheres -o " + path("x") + " --res 64by48", "--res"},
      {"synth builtin:spheres -o " + path("x") + " --spp 0", "--spp"},
      {"synth builtin:spheres -o " + path("x") + " --bounces 1000", "--bounces"},
      {"synth builtin:spheres -o " + path("x") + " --format jpg", "--format"},
      {"synth builtin:spheres -o " + path("x") + " --exposure -1", "--exposure"},
      {"synth builtin:spheres -o " + path("x") + " --env 1,2", "--env"},
      {"synth builtin:spheres -o " + path("precious"), "not empty"},
      {"info " + path("nowhere"), "nowhere"},
      {"sheet " + path("nowhere") + " -o " + path("s.png"), "nowhere"},
      {"frobnicate", "frobnicate"},
  };
  expectEachRejected(cases);
  // The user's folder is untouched.
  EXPECT_TRUE(fs::exists(root_ / "precious" / "notes.txt"));
  EXPECT_FALSE(fs::exists(root_ / "precious" / "transforms_train.json"));
}

TEST_F(CliTest, SynthTurnsAGltfFileIntoAValidDataset) {
  // A unit quad seen from the front, lit by a point light (glTF's lights shine along -Z).
  glint::test::GltfBuilder b;
  int material = b.add("materials", {{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.4, 0.2, 1.0}},
                                                              {"metallicFactor", 0.0},
                                                              {"roughnessFactor", 0.4}}}});
  int mesh = glint::test::addQuadMesh(b, material);
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 5.0}}};
  int quad = b.add("nodes", {{"mesh", mesh}});
  int light = b.add("nodes", {{"translation", {0.5, 0.5, 1.5}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  b.doc["scenes"] = {{{"nodes", {quad, light}}}};
  b.doc["scene"] = 0;
  b.writeGlb(root_ / "quad.glb");

  Outcome synth = runGlint("synth " + path("quad.glb") + " -o " + path("D") + " --train 3 --test 2 --res 24x18 --spp 4");
  ASSERT_EQ(synth.status, 0) << synth.output;
  Outcome info = runGlint("info " + path("D"));
  EXPECT_EQ(info.status, 0) << info.output;
  EXPECT_NE(info.output.find("problems: none"), std::string::npos) << info.output;
}

TEST_F(CliTest, HelpExplainsEveryCommand) {
  Outcome help = runGlint("--help");
  EXPECT_EQ(help.status, 0);
  for (const char* command : {"synth", "info", "sheet", "render", "eval"}) EXPECT_NE(help.output.find(command), std::string::npos);
  Outcome synthHelp = runGlint("synth --help");
  for (const char* flag : {"--train", "--test", "--res", "--spp", "--bounces", "--seed", "--format", "--exposure", "--env"})
    EXPECT_NE(synthHelp.output.find(flag), std::string::npos) << flag;
}

TEST_F(CliTest, ExportWritesA3dgsSceneThatLoadsBackAndNamesBadInputs) {
  glint::GaussianScene scene;
  scene.resize(5);
  for (size_t i = 0; i < scene.size(); ++i) {
    float t = float(i);
    scene.position[i] = {t, -2.0f * t, 0.5f + t};
    scene.rotation[i] = {1.0f, 0.1f * t, 0.0f, -0.2f};
    scene.logScale[i] = {-2.0f, -3.0f + 0.1f * t, -4.0f};
    scene.opacityLogit[i] = 0.3f * t - 1.0f;
    scene.diffuse[i] = {0.1f * t, 0.9f - 0.1f * t, 0.5f};
    scene.normal[i] = {0.0f, 0.0f, 1.0f};
    scene.roughness[i] = 0.2f;
  }
  glint::writeGaussianPly(path("scene.ply"), scene);

  Outcome run = runGlint("export " + path("scene.ply") + " --format 3dgs -o " + path("splat.ply"));
  ASSERT_EQ(run.status, 0) << run.output;
  glint::GaussianPlyImport import;
  glint::GaussianScene splat = glint::readGaussianPly(path("splat.ply"), glint::PlyLayout::Auto, &import);
  EXPECT_EQ(import.layout, glint::PlyLayout::ThreeDgs);
  ASSERT_EQ(splat.size(), scene.size());
  for (size_t i = 0; i < scene.size(); ++i) {
    EXPECT_EQ(splat.position[i], scene.position[i]);
    EXPECT_EQ(splat.logScale[i], scene.logScale[i]);
    EXPECT_EQ(splat.opacityLogit[i], scene.opacityLogit[i]);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(splat.diffuse[i][k], scene.diffuse[i][k], 1e-4);  // via the tonemap
  }

  // A run folder is read through its scene.ply; the Glint layout round-trips exactly.
  fs::create_directories(root_ / "run");
  fs::copy_file(root_ / "scene.ply", root_ / "run" / "scene.ply");
  run = runGlint("export " + path("run") + " --format glint -o " + path("again.ply"));
  ASSERT_EQ(run.status, 0) << run.output;
  glint::GaussianScene again = glint::readGaussianPly(path("again.ply"));
  EXPECT_EQ(again.diffuse, scene.diffuse);
  EXPECT_EQ(again.roughness, scene.roughness);

  fs::create_directories(root_ / "empty_run");
  const BadInvocation cases[] = {
      {"export " + path("missing.ply") + " --format 3dgs -o " + path("out.ply"), "missing.ply"},
      {"export " + path("empty_run") + " -o " + path("out.ply"), "scene.ply"},
      {"export " + path("scene.ply") + " --format splat -o " + path("out.ply"), "--format"},
  };
  expectEachRejected(cases);
  EXPECT_FALSE(fs::exists(root_ / "out.ply"));
  EXPECT_NE(runGlint("export --help").output.find("--format"), std::string::npos);
}

}  // namespace

namespace {

TEST_F(CliTest, RenderWritesTheBuffersOfEverySplitViewWithTheDatasetsNames) {
  Outcome synth = runGlint("synth builtin:spheres -o " + path("D") + " --train 2 --test 3 --res 16x12 --spp 1");
  ASSERT_EQ(synth.status, 0) << synth.output;
  // A small cloud of Gaussians around the origin.
  glint::GaussianScene scene;
  scene.resize(50);
  for (size_t i = 0; i < scene.size(); ++i) {
    scene.position[i] = {0.05f * float(i % 7) - 0.15f, 0.6f + 0.03f * float(i % 5), 0.04f * float(i % 3)};
    scene.logScale[i] = glint::Vec3f(std::log(0.2f));
    scene.opacityLogit[i] = 1.0f;
    scene.diffuse[i] = {0.8f, 0.3f, 0.1f};
    scene.normal[i] = {0, 1, 0};
  }
  glint::writeGaussianPly(path("scene.ply"), scene);
  Outcome render = runGlint("render " + path("scene.ply") + " --dataset " + path("D") + " -o " + path("R") +
                            " --tracer reference --spp 2");
  ASSERT_EQ(render.status, 0) << render.output;
  for (const char* buffer : {"render", "diffuse", "specular", "depth", "normal", "roughness", "f0"})
    for (int v = 0; v < 3; ++v) {
      char name[64];
      std::snprintf(name, sizeof name, "%s/%s_%04d.exr", buffer, buffer, v);
      EXPECT_TRUE(fs::exists(root_ / "R" / name)) << name;
    }
  // Bad input: unknown tracer, missing dataset, non-empty unrelated output folder.
  Outcome badTracer = runGlint("render " + path("scene.ply") + " --dataset " + path("D") + " -o " + path("R2") +
                               " --tracer warp-drive");
  EXPECT_NE(badTracer.status, 0);
  EXPECT_NE(badTracer.output.find("warp-drive"), std::string::npos) << badTracer.output;
  Outcome noDataset = runGlint("render " + path("scene.ply") + " --dataset " + path("nowhere") + " -o " + path("R3"));
  EXPECT_NE(noDataset.status, 0);
  EXPECT_NE(noDataset.output.find("nowhere"), std::string::npos) << noDataset.output;
}

}  // namespace

namespace {

nlohmann::json readJson(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// Every metric of one metrics.json entry is a finite number.
void expectFiniteMetrics(const nlohmann::json& m) {
  for (const char* pass : {"diffuse", "specular", "final"})
    for (const char* key : {"psnr", "ssim", "psnr_tonemapped", "ssim_tonemapped"})
      EXPECT_TRUE(m[pass][key].is_number()) << pass << " " << key << ": " << m.dump();
  EXPECT_TRUE(m["depth_rmse"].is_number()) << m.dump();
  EXPECT_TRUE(m["normal_angle_deg"].is_number()) << m.dump();
  double ssim = m["final"]["ssim"].get<double>();
  EXPECT_GT(ssim, -1.0);
  EXPECT_LT(ssim, 1.0);
}

TEST_F(CliTest, EvalWritesMetricsForAPlyAndForATrainingRun) {
  Outcome synth = runGlint("synth builtin:spheres -o " + path("D") + " --train 1 --test 2 --res 24x18 --spp 2");
  ASSERT_EQ(synth.status, 0) << synth.output;
  writeSmallCloud(root_ / "cloud.ply");

  // A bare .ply has no run folder to write into: -o is required.
  Outcome noOutput = runGlint("eval " + path("cloud.ply") + " --dataset " + path("D"));
  EXPECT_NE(noOutput.status, 0);
  EXPECT_NE(noOutput.output.find("-o"), std::string::npos) << noOutput.output;

  Outcome ply = runGlint("eval " + path("cloud.ply") + " --dataset " + path("D") + " -o " + path("m.json"));
  ASSERT_EQ(ply.status, 0) << ply.output;
  EXPECT_NE(ply.output.find("mean"), std::string::npos) << ply.output;
  nlohmann::json metrics = readJson(root_ / "m.json");
  EXPECT_EQ(metrics["split"], "test");
  EXPECT_EQ(metrics["views"], 2);
  EXPECT_EQ(metrics["tracer"], "fast");
  expectFiniteMetrics(metrics["mean"]);
  ASSERT_EQ(metrics["per_view"].size(), 2u);
  EXPECT_EQ(metrics["per_view"][1]["view"], "test/render/render_0001");
  for (const nlohmann::json& view : metrics["per_view"]) expectFiniteMetrics(view);

  // A run folder names its dataset and trace settings; flags override the settings.
  fs::create_directories(root_ / "run");
  fs::copy_file(root_ / "cloud.ply", root_ / "run" / "scene.ply");
  nlohmann::json config = {{"dataset", path("D")}, {"trace", {{"kernel_power", 1.0}, {"alpha_min", 0.01}}}};
  std::ofstream(root_ / "run" / "config.json") << config.dump(2);
  Outcome run = runGlint("eval " + path("run") + " --save-images --alpha-min 0.02");
  ASSERT_EQ(run.status, 0) << run.output;
  metrics = readJson(root_ / "run" / "eval" / "metrics.json");
  EXPECT_EQ(metrics["trace"]["kernel_power"], 1.0);
  EXPECT_NEAR(metrics["trace"]["alpha_min"].get<double>(), 0.02, 1e-7);
  expectFiniteMetrics(metrics["mean"]);
  for (const char* buffer : {"render", "diffuse", "depth", "normal"})
    EXPECT_TRUE(fs::exists(root_ / "run" / "eval" / "test" / buffer / (std::string(buffer) + "_0001.exr"))) << buffer;

  // --denoise specular scores the filtered specular pass, and the render it scores is the
  // unfiltered diffuse plus it.
  Outcome denoised = runGlint("eval " + path("run") + " --spp 4 --denoise specular --save-images -o " + path("dn.json"));
  ASSERT_EQ(denoised.status, 0) << denoised.output;
  EXPECT_EQ(readJson(root_ / "dn.json")["denoise"], "specular");
  fs::path images = root_ / "test";
  glint::Image final = glint::readImage(images / "render" / "render_0001.exr");
  glint::Image diffuse = glint::readImage(images / "diffuse" / "diffuse_0001.exr");
  glint::Image specular = glint::readImage(images / "specular" / "specular_0001.exr");
  ASSERT_EQ(final.pixels.size(), diffuse.pixels.size());
  ASSERT_EQ(final.pixels.size(), specular.pixels.size());
  for (size_t i = 0; i < final.pixels.size(); ++i)
    ASSERT_NEAR(final.pixels[i], diffuse.pixels[i] + specular.pixels[i], 1e-5f * (1.0f + final.pixels[i])) << i;
  // The filter changed the specular pass: the same render without it differs.
  Outcome raw = runGlint("eval " + path("run") + " --spp 4 --save-images -o " + path("raw/m.json"));
  ASSERT_EQ(raw.status, 0) << raw.output;
  glint::Image rawSpecular = glint::readImage(root_ / "raw" / "test" / "specular" / "specular_0001.exr");
  double change = 0.0;
  for (size_t i = 0; i < specular.pixels.size(); ++i) change += std::abs(specular.pixels[i] - rawSpecular.pixels[i]);
  EXPECT_GT(change, 1e-3);
  Outcome badDenoise = runGlint("eval " + path("run") + " --denoise everything -o " + path("dn2.json"));
  EXPECT_NE(badDenoise.status, 0);
  EXPECT_NE(badDenoise.output.find("--denoise"), std::string::npos) << badDenoise.output;

  // glint render takes the same run folder, without --dataset.
  Outcome render = runGlint("render " + path("run") + " -o " + path("R"));
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_NE(render.output.find("p = 1"), std::string::npos) << render.output;
  EXPECT_TRUE(fs::exists(root_ / "R" / "render" / "render_0001.exr"));
  Outcome train = runGlint("render " + path("run") + " --split train --kernel-power 2 --denoise -o " + path("R2"));
  ASSERT_EQ(train.status, 0) << train.output;
  EXPECT_NE(train.output.find("p = 2"), std::string::npos) << train.output;
  EXPECT_TRUE(fs::exists(root_ / "R2" / "render" / "render_0000.exr"));
  // --denoise adds the denoised final image beside the raw buffers.
  EXPECT_TRUE(fs::exists(root_ / "R2" / "render_denoised" / "render_0000.exr"));
  EXPECT_FALSE(fs::exists(root_ / "R" / "render_denoised"));
}

TEST_F(CliTest, RunFoldersWithoutASceneOrWithABadConfigAreRejected) {
  fs::create_directories(root_ / "empty_run");
  fs::create_directories(root_ / "bad_run");
  writeSmallCloud(root_ / "bad_run" / "scene.ply");
  std::ofstream(root_ / "bad_run" / "config.json") << "{ \"dataset\": ";
  fs::create_directories(root_ / "lost_run");
  writeSmallCloud(root_ / "lost_run" / "scene.ply");
  const BadInvocation cases[] = {
      {"eval " + path("empty_run"), "no scene.ply"},
      {"render " + path("empty_run") + " -o " + path("R"), "no scene.ply"},
      {"eval " + path("bad_run"), "config.json"},
      {"render " + path("bad_run") + " -o " + path("R"), "config.json"},
      {"eval " + path("lost_run"), "--dataset"},
      {"render " + path("lost_run") + " -o " + path("R"), "--dataset"},
      {"eval " + path("lost_run") + " --dataset " + path("nowhere"), "nowhere"},
      {"eval " + path("lost_run") + " --region 1,2,3", "--region expects six numbers"},
      {"eval " + path("lost_run") + " --region 0,0,0,1,1,nan", "--region expects six numbers"},
  };
  expectEachRejected(cases);
  EXPECT_FALSE(fs::exists(root_ / "R"));
  EXPECT_FALSE(fs::exists(root_ / "lost_run" / "eval"));
}

}  // namespace
