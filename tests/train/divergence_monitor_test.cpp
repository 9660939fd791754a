// Tests of the divergence monitor: non-finite numbers at once, sustained collapse (no hits,
// a loss grown a thousandfold) after kSustainedSteps, healthy noise never.
#include "train/divergence_monitor.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

constexpr float kExtent = 3.0f;

GaussianScene sceneOf(size_t n) {
  GaussianScene scene;
  for (size_t i = 0; i < n; ++i) {
    scene.position.push_back(Vec3f(float(i), 0, 0));
    scene.rotation.push_back(Quatf());
    scene.logScale.push_back(Vec3f(-3.0f));
    scene.opacityLogit.push_back(0.0f);
    scene.diffuse.push_back(Rgb(0.5f));
    scene.normal.push_back(Vec3f(0, 0, 1));
    scene.roughness.push_back(0.1f);
    scene.f0.push_back(Rgb(0.04f));
  }
  return scene;
}

StepReport report(int64_t step, double loss, int64_t hits = 1000) {
  StepReport r;
  r.step = step;
  r.loss = loss;
  r.rays = 100;
  r.hits = hits;
  return r;
}

TEST(DivergenceMonitor, AHealthyNoisyRunPasses) {
  DivergenceMonitor monitor(kExtent);
  GaussianScene scene = sceneOf(10);
  for (int64_t s = 1; s <= 500; ++s) {
    double loss = 1.0 / double(s) * (s % 7 == 0 ? 30.0 : 1.0);  // falling, with spikes
    int64_t hits = s % 13 == 0 ? 0 : 1000;                      // a batch through a gap now and then
    EXPECT_FALSE(monitor.check(report(s, loss, hits), scene)) << "step " << s;
  }
  EXPECT_TRUE(monitor.clean());
}

TEST(DivergenceMonitor, NonFiniteLossStopsAtOnce) {
  DivergenceMonitor monitor(kExtent);
  GaussianScene scene = sceneOf(4);
  EXPECT_FALSE(monitor.check(report(1, 0.5), scene));
  std::optional<std::string> problem = monitor.check(report(2, NAN), scene);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("at step 2: the loss is nan"), std::string::npos) << *problem;
}

TEST(DivergenceMonitor, NonFiniteParameterNamesTheGaussianAndAttribute) {
  DivergenceMonitor monitor(kExtent);
  GaussianScene scene = sceneOf(40000);  // several chunks: the lowest index must win
  scene.logScale[30001].y = INFINITY;
  scene.diffuse[20002].x = NAN;
  std::optional<std::string> problem = monitor.check(report(7, 0.5), scene);
  ASSERT_TRUE(problem);
  EXPECT_EQ(*problem, "at step 7: Gaussian 20002 has a non-finite diffuse colour");
}

TEST(DivergenceMonitor, ExplodedScalesStopAtOnceButAFarFieldDoesNot) {
  DivergenceMonitor monitor(kExtent);
  GaussianScene scene = sceneOf(1000);
  // Most Gaussians far-field sized (a third of the radius), the rest tiny: healthy.
  for (size_t i = 0; i < 900; ++i) scene.logScale[i] = Vec3f(std::log(kExtent / 3.0f));
  EXPECT_FALSE(monitor.check(report(1, 0.5), scene));
  for (size_t i = 0; i < 600; ++i) scene.logScale[i] = Vec3f(-3.0f, 5.0f, -3.0f);  // e^5 = 148 along one axis
  std::optional<std::string> problem = monitor.check(report(2, 0.5), scene);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("at step 2: the scales have exploded: half the Gaussians are larger than 148.4"),
            std::string::npos)
      << *problem;
}

TEST(DivergenceMonitor, MedianLargestScaleSamplesEvenly) {
  GaussianScene scene = sceneOf(100001);
  for (size_t i = 0; i < scene.size(); ++i) scene.logScale[i] = Vec3f(-9.0f, std::log(float(i + 1)), -9.0f);
  EXPECT_NEAR(medianLargestScale(scene), 50000.0f, 50.0f);  // 8334 samples 12 apart: their median is the middle
  EXPECT_EQ(medianLargestScale(GaussianScene()), 0.0f);
}

TEST(DivergenceMonitor, RaysHittingNothingForTwentyStepsIsCollapse) {
  DivergenceMonitor monitor(kExtent);
  GaussianScene scene = sceneOf(4);
  EXPECT_FALSE(monitor.check(report(15, 0.5), scene));
  for (int64_t s = 16; s < 16 + DivergenceMonitor::kSustainedSteps - 1; ++s) {
    EXPECT_FALSE(monitor.check(report(s, 0.5, 0), scene));
    EXPECT_FALSE(monitor.clean());  // checkpoints wait meanwhile
  }
  std::optional<std::string> problem = monitor.check(report(35, 0.5, 0), scene);
  ASSERT_TRUE(problem);
  EXPECT_EQ(*problem, "from step 16 to 35, no ray hit any Gaussian (the Gaussians have collapsed, vanished or flown off)");
}

TEST(DivergenceMonitor, LossGrownAThousandfoldForTwentyStepsIsCollapse) {
  DivergenceMonitor monitor(kExtent);
  GaussianScene scene = sceneOf(4);
  for (int64_t s = 1; s <= 10; ++s) EXPECT_FALSE(monitor.check(report(s, 0.01), scene));
  std::optional<std::string> problem;
  for (int64_t s = 11; s <= 40 && !problem; ++s) problem = monitor.check(report(s, 50.0), scene);
  ASSERT_TRUE(problem);
  EXPECT_NE(problem->find("from step 11 to 30, the loss stayed above 1000 times its lowest (0.01; now 50)"),
            std::string::npos)
      << *problem;
}

TEST(DivergenceMonitor, ARecoveryResetsTheCount) {
  DivergenceMonitor monitor(kExtent);
  GaussianScene scene = sceneOf(4);
  for (int round = 0; round < 5; ++round) {
    for (int k = 0; k < DivergenceMonitor::kSustainedSteps - 1; ++k)
      EXPECT_FALSE(monitor.check(report(round * 100 + k, 0.5, 0), scene));
    EXPECT_FALSE(monitor.check(report(round * 100 + 50, 0.5), scene));
    EXPECT_TRUE(monitor.clean());
  }
}

}  // namespace
}  // namespace glint
