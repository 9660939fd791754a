// Training configs: JSON round trip of every field, and clear errors for unknown keys,
// wrong types, out-of-range values and broken files.
#include "train/train_config.h"

#include <gtest/gtest.h>

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
  c.lr.f0 = 0.01f;
  c.prune.start = 17;
  c.initSource = "depth";
  c.trace.kernelPower = 2.0f;
  c.trace.exactTail = true;
  c.farField.count = 1234;
  c.farField.boxes.push_back({Vec3f(-0.5f, 0.9f, 2.4f), Vec3f(0.5f, 1.75f, 2.8f), 5000});
  c.baseline = "none";
  TrainConfig back;
  applyJson(toJson(c), &back, "test");
  EXPECT_EQ(toJson(back), toJson(c));
  EXPECT_EQ(back.batchRays, 777);
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
  EXPECT_EQ(c.lr.opacity, 2.5e-2f);
  EXPECT_EQ(c.adam.epsilon, 1e-15f);
  EXPECT_EQ(c.scaleDecay, 0.9999f);
  EXPECT_EQ(c.prune.every, 125);
  EXPECT_EQ(c.prune.start, 1250);
  EXPECT_FALSE(c.trace.exactTail);  // Glint's choice, see train_config.h
  EXPECT_EQ(c.bounces, 2);
  EXPECT_EQ(c.reflectionWarmup, 750);
  EXPECT_EQ(c.loss.specular, 3.0f);
  EXPECT_EQ(c.farField.count, 75000);
  EXPECT_EQ(c.farField.sigmaFactor, 4.0f);
  EXPECT_EQ(c.farField.truncation, 3.0f);
  EXPECT_EQ(c.farField.opacity, 0.1f);
  EXPECT_EQ(c.farField.diffuse, 0.2f);
  nlohmann::json j = toJson(c);
  EXPECT_EQ(j["trace"]["kernel_power"], 3.0);
  EXPECT_EQ(j["batch_rays"], 16384);
}

TEST(TrainConfig, RejectsBadSettingsNamingTheFile) {
  test::TempFolder temp;
  auto expectRejected = [&](const std::string& text, const std::string& detail) {
    std::filesystem::path file = temp.path() / "config.json";
    writeTextAtomically(file, text);
    test::expectErrorNaming([&] { readTrainConfig(file); }, file, detail);
  };
  expectRejected("{\"iters\": 10,", "not valid JSON");
  expectRejected("[1, 2]", "not a JSON object");
  expectRejected("{\"itres\": 10}", "unknown setting \"itres\"");
  expectRejected("{\"lr\": {\"postion_init\": 1}}", "unknown setting \"lr.postion_init\"");
  expectRejected("{\"iters\": \"many\"}", "\"iters\" has the wrong type");
  expectRejected("{\"iters\": 1.5}", "\"iters\" has the wrong type");
  expectRejected("{\"lr\": 3}", "\"lr\" must be an object");
  expectRejected("{\"iters\": 0}", "iters must be positive");
  expectRejected("{\"trace\": {\"alpha_min\": 0.7}}", "alpha_min");
  expectRejected("{\"init\": {\"source\": \"magic\"}}", "init.source");
  expectRejected("{\"adam\": {\"beta1\": 1.0}}", "beta1");
  expectRejected("{\"lr\": {\"position_final\": 1.0}}", "position_final");
  expectRejected("{\"lr\": {\"normal_final\": 1.0}}", "normal_final");
  expectRejected("{\"lr\": {\"normal_decay_steps\": 0}}", "normal_decay_steps");
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
}

}  // namespace
}  // namespace glint
