// Checkpoints: a bit-exact round trip of the whole training state, and clear errors for
// missing, foreign, truncated and corrupted files.
#include "train/checkpoint.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <span>

#include "common/expect_error.h"
#include "io/temp_folder.h"
#include "math/rng.h"
#include "scene/gaussian_ply.h"

namespace glint {
namespace {

TrainingState randomState() {
  Rng rng(77);
  TrainingState s;
  s.step = 4321;
  s.sceneExtent = 3.25f;
  s.configJson = "{\"iters\": 9}";
  s.scene.resize(37);
  auto r = [&] { return float(rng.uniformDouble() * 2 - 1); };
  for (size_t i = 0; i < s.scene.size(); ++i) {
    s.scene.position[i] = Vec3f(r(), r(), r());
    s.scene.rotation[i] = Quatf{r(), r(), r(), r()};
    s.scene.logScale[i] = Vec3f(r(), r(), r());
    s.scene.opacityLogit[i] = r();
    s.scene.diffuse[i] = Rgb(r(), r(), r());
    s.scene.normal[i] = Vec3f(r(), r(), r());
    s.scene.roughness[i] = r();
    s.scene.f0[i] = Rgb(r(), r(), r());
  }
  s.adam.reset(s.scene.size());
  for (float& m : s.adam.firstMoment().of(&GaussianScene::position)) m = r();
  for (float& v : s.adam.secondMoment().of(&GaussianScene::f0)) v = r();
  s.adam.setStepCount(4000);
  s.pruneWeight.resize(s.scene.size());
  for (float& w : s.pruneWeight) w = r();
  s.densifyScore.resize(s.scene.size());
  for (float& w : s.densifyScore) w = r();
  s.roughnessShift = 0.0731f;
  for (int v = 0; v < 3; ++v) {
    Mat4 pose = Mat4::lookAt(Vec3d(r(), r(), 2.0 + r()), Vec3d(0, 0, 0), Vec3d(0, 0, 1));
    s.cameraPoses.push_back(pose);
  }
  return s;
}

template <typename V>
bool sameBytes(const std::vector<V>& a, const std::vector<V>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(V)) == 0;
}

TEST(Checkpoint, RoundTripIsBitExact) {
  test::TempFolder temp;
  TrainingState s = randomState();
  std::filesystem::path file = temp.path() / "checkpoint" / "state.bin";
  writeCheckpoint(file, s);
  TrainingState back = readCheckpoint(file);
  EXPECT_EQ(back.step, s.step);
  EXPECT_EQ(back.sceneExtent, s.sceneExtent);
  EXPECT_EQ(back.configJson, s.configJson);
  EXPECT_EQ(back.adam.stepCount(), 4000);
  EXPECT_TRUE(sameBytes(back.scene.position, s.scene.position));
  EXPECT_TRUE(sameBytes(back.scene.rotation, s.scene.rotation));
  EXPECT_TRUE(sameBytes(back.scene.logScale, s.scene.logScale));
  EXPECT_TRUE(sameBytes(back.scene.opacityLogit, s.scene.opacityLogit));
  EXPECT_TRUE(sameBytes(back.scene.diffuse, s.scene.diffuse));
  EXPECT_TRUE(sameBytes(back.scene.normal, s.scene.normal));
  EXPECT_TRUE(sameBytes(back.scene.roughness, s.scene.roughness));
  EXPECT_TRUE(sameBytes(back.scene.f0, s.scene.f0));
  for (size_t p = 0; p < kGaussianParameterCount; ++p) {
    EXPECT_TRUE(sameBytes(back.adam.firstMoment().values[p], s.adam.firstMoment().values[p])) << p;
    EXPECT_TRUE(sameBytes(back.adam.secondMoment().values[p], s.adam.secondMoment().values[p])) << p;
  }
  EXPECT_TRUE(sameBytes(back.pruneWeight, s.pruneWeight));
  EXPECT_TRUE(sameBytes(back.densifyScore, s.densifyScore));
  EXPECT_EQ(back.roughnessShift, s.roughnessShift);
  ASSERT_EQ(back.cameraPoses.size(), 3u);
  for (size_t v = 0; v < 3; ++v) EXPECT_EQ(back.cameraPoses[v].m, s.cameraPoses[v].m) << v;
}

// A checkpoint written before the parameter table (scene/gaussian_parameters.h) chose its
// arrays (tests/data/README.md) loads with every array in its place and a zero
// densification score (version 1 had none), roughness shift and no camera poses; written again
// as version 4 it differs from the old file only in the version and the appended score, shift
// and pose count.
TEST(Checkpoint, VersionOneFileLoadsAndRewritesWithOnlyTheScoreAndShiftAdded) {
  const std::filesystem::path folder = std::filesystem::path(GLINT_TEST_DATA) / "version1_run";
  TrainingState state = readCheckpoint(folder / "state.bin");
  EXPECT_EQ(state.step, 12);
  EXPECT_EQ(state.adam.stepCount(), 12);
  // The scene is the one the run wrote as scene.ply at the same step.
  GaussianScene ply = readGaussianPly(folder / "scene.ply");
  EXPECT_TRUE(sameBytes(state.scene.position, ply.position));
  EXPECT_TRUE(sameBytes(state.scene.rotation, ply.rotation));
  EXPECT_TRUE(sameBytes(state.scene.logScale, ply.logScale));
  EXPECT_TRUE(sameBytes(state.scene.opacityLogit, ply.opacityLogit));
  EXPECT_TRUE(sameBytes(state.scene.diffuse, ply.diffuse));
  EXPECT_TRUE(sameBytes(state.scene.normal, ply.normal));
  EXPECT_TRUE(sameBytes(state.scene.roughness, ply.roughness));
  EXPECT_TRUE(sameBytes(state.scene.f0, ply.f0));
  // Moments as the file stores them: Gaussian 0's first moments of position and rotation.
  std::span<const float> position = state.adam.firstMoment().of(&GaussianScene::position);
  EXPECT_EQ(position[0], 0.02609849162399769f);
  EXPECT_EQ(position[1], -0.07272546738386154f);
  EXPECT_EQ(position[2], 0.023812226951122284f);
  EXPECT_EQ(state.adam.firstMoment().of(&GaussianScene::rotation)[3], -0.00017370961722917855f);

  EXPECT_EQ(state.densifyScore, std::vector<float>(state.scene.size(), 0.0f));
  EXPECT_EQ(state.roughnessShift, 0.0f);
  EXPECT_TRUE(state.cameraPoses.empty());

  test::TempFolder temp;
  writeCheckpoint(temp.path() / "state.bin", state);
  const auto written = test::readBytes(temp.path() / "state.bin");
  auto old = test::readBytes(folder / "state.bin");
  // Version 4: the version word becomes 4, and before the checksum come the score's count,
  // its zero floats, the zero shift and a pose count of 0.
  const size_t checksum = sizeof(uint64_t), scoreBytes = sizeof(uint64_t) + state.scene.size() * sizeof(float);
  ASSERT_EQ(written.size(), old.size() + scoreBytes + sizeof(float) + sizeof(uint64_t));
  old[8] = 4;
  const auto body = [](const auto& bytes, size_t end) { return std::vector<char>(bytes.begin(), bytes.begin() + end); };
  EXPECT_EQ(body(written, old.size() - checksum), body(old, old.size() - checksum));
}

TEST(Checkpoint, RejectsBadFiles) {
  test::TempFolder temp;
  std::filesystem::path file = temp.path() / "state.bin";
  test::expectErrorNaming([&] { readCheckpoint(file); }, file, "not found (no checkpoint to resume from)");
  writeCheckpoint(file, randomState());
  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    bytes.assign((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  }
  auto writeBytes = [&](const std::string& b) { std::ofstream(file, std::ios::binary) << b; };
  writeBytes(bytes.substr(0, bytes.size() / 2));
  test::expectErrorNaming([&] { readCheckpoint(file); }, file, "corrupt or truncated");
  std::string flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x10;
  writeBytes(flipped);
  test::expectErrorNaming([&] { readCheckpoint(file); }, file, "checksum");
  writeBytes("ply\nformat binary_little_endian 1.0\n");
  test::expectErrorNaming([&] { readCheckpoint(file); }, file, "not a Glint checkpoint");
}

}  // namespace
}  // namespace glint
