// Training configs: JSON round trip of every field, and clear errors for unknown keys,
// wrong types, out-of-range values and broken files.
#include "train/train_config.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/expect_error.h"
#include "core/atomic_file.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

TEST(TrainConfig, RoundTripsEveryField) {
  TrainConfig c;
  c.dataset = "/data/x";
  c.iters = 123;
  c.seed = 99;
  c.batchRays = 777;
  c.loss.normal = 0.5f;
  c.loss.roughnessFromSpecular = 0.25f;
  c.loss.f0FromSpecular = 2.0f;
  c.loss.depthConsistency = 0.03f;
  c.loss.depthConsistencyViews = 3;
  c.loss.normalHuber = 0.2f;
  c.loss.f0TintPrior = 0.3f;
  c.loss.photograph = 0.7f;
  c.initConsistentDepthOnly = true;
  c.cameras.every = 500;
  c.cameras.until = 4500;
  c.lr.f0 = 0.01f;
  c.lr.normalDecayStart = 4000;
  c.prune.start = 17;
  c.initSource = InitChoice::DepthBuffers;
  c.trace.kernelPower = 2.0f;
  c.trace.exactTail = true;
  c.farField.count = 1234;
  c.farField.boxes.push_back({Vec3f(-0.5f, 0.9f, 2.4f), Vec3f(0.5f, 1.75f, 2.8f), 5000});
  c.baseline = Baseline::None;
  TrainConfig back;
  applyJson(toJson(c), &back, "test");
  EXPECT_EQ(toJson(back), toJson(c));
  EXPECT_EQ(back.batchRays, 777);
  EXPECT_EQ(back.loss.roughnessFromSpecular, 0.25f);
  EXPECT_EQ(back.loss.f0FromSpecular, 2.0f);
  EXPECT_EQ(back.loss.depthConsistency, 0.03f);
  EXPECT_EQ(back.loss.depthConsistencyViews, 3);
  EXPECT_EQ(back.loss.normalHuber, 0.2f);
  EXPECT_EQ(back.loss.f0TintPrior, 0.3f);
  EXPECT_EQ(back.loss.photograph, 0.7f);
  EXPECT_TRUE(back.initConsistentDepthOnly);
  EXPECT_EQ(back.cameras.every, 500);
  EXPECT_EQ(back.cameras.until, 4500);
  EXPECT_EQ(back.lr.normalDecayStart, 4000);
  EXPECT_EQ(back.trace.exactTail, true);
  EXPECT_EQ(back.farField.count, 1234);
  ASSERT_EQ(back.farField.boxes.size(), 1u);
  EXPECT_EQ(back.farField.boxes[0].max, Vec3f(0.5f, 1.75f, 2.8f));
  EXPECT_EQ(back.farField.boxes[0].count, 5000);
}

TEST(TrainConfig, DefaultsAreThePapers) {
  TrainConfig c;
  EXPECT_EQ(c.loss.diffuse, 5.0f);
  EXPECT_EQ(c.loss.depth, 2.5f);
  EXPECT_EQ(c.loss.normal, 10.0f);  // Glint's choice, not the paper's 2.5 (train_config.h)
  EXPECT_EQ(c.farField.reflectionSeeds, 0);  // measured worse (far_field.h)
  EXPECT_EQ(c.lr.opacity, 2.5e-2f);
  EXPECT_EQ(c.adam.epsilon, 1e-15f);
  EXPECT_EQ(c.scaleDecay, 0.9999f);
  EXPECT_EQ(c.prune.every, 125);
  EXPECT_EQ(c.prune.start, 1250);
  EXPECT_FALSE(c.trace.exactTail);  // Glint's choice, see train_config.h
  EXPECT_EQ(c.bounces, 2);
  EXPECT_EQ(c.reflectionWarmup, 750);
  EXPECT_EQ(c.loss.specular, 3.0f);
  // The paper's detached throughputs: L_r reaches neither roughness nor F0.
  EXPECT_EQ(c.loss.roughnessFromSpecular, 0.0f);
  EXPECT_EQ(c.loss.f0FromSpecular, 0.0f);
  EXPECT_EQ(c.loss.normalHuber, 0.0f);  // the paper's L1 normal term
  EXPECT_EQ(c.loss.f0TintPrior, 0.1f);  // the tint option's pull toward grey (off with the option)
  EXPECT_EQ(c.loss.photograph, 0.0f);   // the photograph term, beyond the paper
  EXPECT_EQ(c.farField.count, 75000);
  EXPECT_EQ(c.farField.sigmaFactor, 4.0f);
  EXPECT_EQ(c.farField.truncation, 3.0f);
  EXPECT_EQ(c.farField.opacity, 0.1f);
  EXPECT_EQ(c.farField.diffuse, 0.2f);
  nlohmann::json j = toJson(c);
  EXPECT_EQ(j["trace"]["kernel_power"], 2.0);  // Glint's choice, not the paper code's 3 (trace_settings.h)
  EXPECT_EQ(j["batch_rays"], 16384);
  EXPECT_EQ(j["densify"]["fraction"], 0.1);  // Glint's: the paper does not densify (densify.h)
  // Floats are written as people write them, not as the doubles they widen to.
  EXPECT_EQ(j["densify"]["fraction"].dump(), "0.1");
  EXPECT_EQ(j["trace"]["alpha_min"].dump(), "0.005");
  EXPECT_EQ(j["render_bounces"], 4);
}

// Rendering a run follows render_bounces when the run trains reflections, never fewer than
// it trained, and none when it trains none (the RGB baseline included).
TEST(TrainConfig, RenderPathFollowsRenderBouncesOnlyForRunsWithReflections) {
  TrainConfig c;
  EXPECT_EQ(c.path().bounces, 2);
  EXPECT_EQ(c.renderPath().bounces, 4);
  c.bounces = 6;
  EXPECT_EQ(c.renderPath().bounces, 6);
  c.bounces = 0;
  EXPECT_EQ(c.renderPath().bounces, 0);
  c.bounces = 2;
  c.baseline = Baseline::Rgb;
  EXPECT_EQ(c.renderPath().bounces, 0);
  c.baseline = Baseline::None;
  c.renderBounces = 1;
  EXPECT_EQ(c.renderPath().bounces, 2);
  EXPECT_EQ(c.renderPath().invalidNormalLength, c.path().invalidNormalLength);
}

// A constant rate given only its initial value stays constant; given both, it decays; a
// decaying rate (position) keeps its own final value.
TEST(TrainConfig, AConstantRateGivenOnlyItsInitialValueStaysConstant) {
  TrainConfig c;
  applyJson(nlohmann::json::parse(R"({"lr": {"roughness": 0.001, "normal": 0.004, "position_init": 0.0002}})"), &c, "test");
  EXPECT_EQ(c.lr.roughnessFinal, 0.001f);
  EXPECT_EQ(c.lr.normalFinal, 0.004f);
  EXPECT_EQ(c.lr.positionFinal, TrainConfig().lr.positionFinal);
  TrainConfig d;
  applyJson(nlohmann::json::parse(R"({"lr": {"roughness": 0.001, "roughness_final": 0.0001}})"), &d, "test");
  EXPECT_EQ(d.lr.roughness, 0.001f);
  EXPECT_EQ(d.lr.roughnessFinal, 0.0001f);
  // Only the final value given: a decay from the default initial rate.
  TrainConfig e;
  applyJson(nlohmann::json::parse(R"({"lr": {"roughness_final": 0.0001}})"), &e, "test");
  EXPECT_EQ(e.lr.roughness, TrainConfig().lr.roughness);
  EXPECT_EQ(e.lr.roughnessFinal, 0.0001f);
}

// Writes `text` as a config file and expects readTrainConfig to refuse it, naming the file
// and saying `detail`.
void expectRejected(const std::string& text, const std::string& detail) {
  test::TempFolder temp;
  std::filesystem::path file = temp.path() / "config.json";
  writeTextAtomically(file, text);
  test::expectErrorNaming([&] { readTrainConfig(file); }, file, detail);
}

TEST(TrainConfig, RejectsBadSettingsNamingTheFile) {
  expectRejected("{\"iters\": 10,", "not valid JSON");
  expectRejected("[1, 2]", "not a JSON object");
  expectRejected("{\"itres\": 10}", "unknown setting \"itres\"");
  expectRejected("{\"lr\": {\"postion_init\": 1}}", "unknown setting \"lr.postion_init\"");
  expectRejected("{\"iters\": \"many\"}", "\"iters\" has the wrong type");
  expectRejected("{\"iters\": 1.5}", "\"iters\" has the wrong type");
  expectRejected("{\"lr\": 3}", "\"lr\" must be an object");
  expectRejected("{\"iters\": 0}", "iters must be in [1, 100000000]");
  expectRejected("{\"trace\": {\"alpha_min\": 0.7}}", "alpha_min");
  expectRejected("{\"init\": {\"source\": \"magic\"}}", "init.source");
  expectRejected("{\"adam\": {\"beta1\": 1.0}}", "beta1");
  expectRejected("{\"lr\": {\"position_final\": 1.0}}", "position_final");
  expectRejected("{\"lr\": {\"normal_final\": 1.0}}", "normal_final");
  expectRejected("{\"lr\": {\"normal_decay_steps\": 0}}", "normal_decay_steps");
  expectRejected("{\"lr\": {\"roughness_final\": 1.0}}", "roughness_final");
  expectRejected("{\"lr\": {\"roughness\": 0.001, \"roughness_final\": 0.002}}", "roughness_final");
  expectRejected("{\"lr\": {\"roughness_decay_steps\": 0}}", "roughness_decay_steps");
  expectRejected("{\"lr\": {\"normal_decay_start\": -1}}", "normal_decay_start");
  expectRejected("{\"far_field\": {\"count\": -5}}", "far_field.count");
  expectRejected("{\"far_field\": {\"boxes\": {\"count\": 5}}}", "\"far_field.boxes\" has the wrong type");
  expectRejected("{\"far_field\": {\"boxes\": [{\"min\": [0, 0], \"max\": [1, 1, 1], \"count\": 5}]}}",
                 "\"far_field.boxes\":");
  expectRejected("{\"far_field\": {\"boxes\": [{\"min\": [0, 0, 0], \"max\": [1, 1, 1]}]}}", "count");
  expectRejected("{\"far_field\": {\"boxes\": [{\"min\": [0, 0, 0], \"max\": [1, 1, 1], \"count\": 5, "
                 "\"colour\": 1}]}}",
                 "unknown key \"colour\"");
  expectRejected("{\"far_field\": {\"boxes\": [{\"min\": [0, 2, 0], \"max\": [1, 1, 1], \"count\": 5}]}}",
                 "min must be below max");
  expectRejected("{\"baseline\": \"rgbd\"}", "baseline");
  expectRejected("{\"baseline\": \"rgb\"}", "G-buffer");  // bounces and G-buffer weights left on
  expectRejected("{\"loss\": {\"roughness_from_specular\": -1}}", "roughness_from_specular");
  expectRejected("{\"loss\": {\"depth_consistency\": 1.5}}", "loss.depth_consistency must be in [0, 1)");
  expectRejected("{\"loss\": {\"depth_consistency_views\": 9}}", "loss.depth_consistency_views must be in [1, 8]");
  expectRejected("{\"loss\": {\"depth_consistency_views\": 0}}", "loss.depth_consistency_views");
  expectRejected("{\"loss\": {\"normal_huber\": -0.1}}", "loss.normal_huber must be in [0, 2]");
  // The initialisation's filter is the check's verdict: nothing to filter with the check off,
  // nor in a point cloud.
  expectRejected("{\"init\": {\"consistent_depth_only\": true}}", "needs loss.depth_consistency > 0");
  expectRejected("{\"init\": {\"consistent_depth_only\": true, \"source\": \"point-cloud\"}, "
                 "\"loss\": {\"depth_consistency\": 0.02}}",
                 "applies to the depth buffers");
  expectRejected("{\"cameras\": {\"refine_every\": -5}}", "cameras.refine_every must be in [0, ");
  expectRejected("{\"cameras\": {\"refine_until\": -1}}", "cameras.refine_until must be in [0, ");
  // Leaving F0's tint to L_r needs L_r's gradient into F0.
  expectRejected("{\"f0_tint_from_reflections\": true}", "loss.f0_from_specular > 0");
  expectRejected("{\"loss\": {\"f0_tint_prior\": 1.5}}", "loss.f0_tint_prior must be in [0, 1]");
  expectRejected("{\"loss\": {\"photograph\": -1}}", "loss weights must be in [0, 1e6]");
}

// The choices are enums in memory and keep their words in config.json, so runs written
// before they were enums load unchanged.
TEST(TrainConfig, ChoicesRoundTripThroughTheirJsonWords) {
  nlohmann::json written = R"({"baseline": "rgb", "bounces": 0,
      "loss": {"depth": 0, "normal": 0, "roughness": 0, "f0": 0, "specular": 0},
      "init": {"source": "point-cloud"}, "prune": {"camera_cull_region": "whole-sphere"}})"_json;
  TrainConfig c;
  applyJson(written, &c, "test");
  EXPECT_EQ(c.baseline, Baseline::Rgb);
  EXPECT_EQ(c.initSource, InitChoice::PointCloud);
  EXPECT_EQ(c.prune.cameraCullRegion, CullRegion::WholeSphere);
  nlohmann::json back = toJson(c);
  EXPECT_EQ(back["baseline"], "rgb");
  EXPECT_EQ(back["init"]["source"], "point-cloud");
  EXPECT_EQ(back["prune"]["camera_cull_region"], "whole-sphere");

  for (InitChoice choice : {InitChoice::Auto, InitChoice::DepthBuffers, InitChoice::PointCloud}) {
    TrainConfig one;
    one.initSource = choice;
    TrainConfig read;
    applyJson(toJson(one), &read, "test");
    EXPECT_EQ(read.initSource, choice) << choiceName(choice);
  }
  for (CullRegion region : {CullRegion::SphereInView, CullRegion::WholeSphere}) {
    TrainConfig one;
    one.prune.cameraCullRegion = region;
    TrainConfig read;
    applyJson(toJson(one), &read, "test");
    EXPECT_EQ(read.prune.cameraCullRegion, region) << choiceName(region);
  }
}

TEST(TrainConfig, AnUnknownChoiceNamesTheFileTheKeyAndTheWords) {
  expectRejected(R"({"baseline": "rgbd"})", R"("baseline" is "rgbd"; expected "none" or "rgb")");
  expectRejected(R"({"init": {"source": "magic"}})",
                 R"("init.source" is "magic"; expected "auto", "depth" or "point-cloud")");
  expectRejected(R"({"prune": {"camera_cull_region": "in view"}})",
                 R"("prune.camera_cull_region" is "in view"; expected "in-view" or "whole-sphere")");
  expectRejected(R"({"baseline": 1})", R"("baseline" has the wrong type)");
}

TEST(TrainConfig, RejectsWhatTheFlagsRejectAndNeverWrapsOrOverflows) {
  // 2^32 + 1 read into an int was 1; the flag's bound (2^24) was not checked either.
  expectRejected("{\"batch_rays\": 4294967297}", "\"batch_rays\" is 4294967297, out of the range of its type");
  expectRejected("{\"batch_rays\": 16777217}", "batch_rays must be in [1, 16777216]");
  expectRejected("{\"iters\": -4294967295}", "\"iters\" is -4294967295");
  expectRejected("{\"seed\": -1}", "\"seed\" is -1");
  expectRejected("{\"threads\": 1025}", "threads must be in [0, 1024]");
  expectRejected("{\"batch_views\": 1048577}", "batch_views must be in [1, 1048576]");
  expectRejected("{\"save_every\": 100000001}", "save_every must be in [1, 100000000]");
  // 1e39 is a finite double but an infinite float: it trained to NaN and wrote null.
  expectRejected("{\"loss\": {\"diffuse\": 1e39}}", "\"loss.diffuse\" is 1e+39, out of the range of its type");
  expectRejected("{\"loss\": {\"diffuse\": 1e30}}", "loss weights must be in [0, 1e6]");
  expectRejected("{\"adam\": {\"epsilon\": 1e30}}", "adam.epsilon");
  expectRejected("{\"far_field\": {\"count\": 2147483647}}", "far_field.count must be in [0, 10000000]");
  expectRejected("{\"far_field\": {\"boxes\": [{\"min\": [0, 0, 0], \"max\": [1, 1, 1e39], \"count\": 5}]}}",
                 "finite");
  expectRejected("{\"far_field\": {\"boxes\": [{\"min\": [0, 0, 0], \"max\": [1, 1, 1], \"count\": 4294967297}]}}",
                 "\"count\" must be an integer of at most 10000000");
  expectRejected("{\"init\": {\"max_pixel_samples\": 1000000000000}}", "init.max_pixel_samples");
  // A key quoted in a message cannot send control characters to the terminal.
  expectRejected("{\"\\u001b[2Jx\": 1}", "unknown setting \"\\x1B[2Jx\"");
}

TEST(TrainConfig, ValidateRefusesNonFiniteNumbersOfEveryField) {
  TrainConfig c;
  c.farField.sigmaFactor = NAN;
  EXPECT_THROW(c.validate("test"), Error);
  c = TrainConfig();
  c.trace.kernelPower = INFINITY;
  EXPECT_THROW(c.validate("test"), Error);
  c = TrainConfig();
  c.lr.scale = NAN;  // "r >= 0 && r < 10" alone lets no NaN through either; the finite check names it first
  try {
    c.validate("test");
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lr.scale must be a finite number"), std::string::npos) << e.what();
  }
}

// The real-capture setting exists twice, in code (applied to predicted captures) and as
// scripts/real-capture-train.json (for --config and other tools): they must not drift.
TEST(TrainConfig, PredictedBufferSettingIsTheScriptsFile) {
  TrainConfig inCode;
  usePredictedBufferSetting(&inCode);
  const TrainConfig fromFile = readTrainConfig(std::string(GLINT_TEST_DATA) + "/../../scripts/real-capture-train.json");
  EXPECT_EQ(toJson(fromFile), toJson(inCode));
}

}  // namespace
}  // namespace glint
