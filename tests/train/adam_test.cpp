// Adam against a double-precision transcription of the algorithm (Kingma and Ba 2015,
// PyTorch's bias correction), the position learning-rate schedule, and moment filtering.
#include "train/adam.h"

#include <gtest/gtest.h>

#include <cmath>

#include "math/rng.h"

namespace glint {
namespace {

TEST(Adam, MatchesTheAlgorithmStepByStep) {
  GaussianScene scene;
  scene.resize(3);
  const float untouched = scene.opacityLogit[0];
  AdamSettings settings;
  settings.epsilon = 1e-8f;
  AdamOptimizer adam(settings);
  adam.reset(scene.size());
  StepLearningRates rates{{0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f}};  // table order
  Rng rng(3);
  double p = scene.opacityLogit[1], m = 0, v = 0;  // one parameter followed in double
  double q = scene.diffuse[2].y, mq = 0, vq = 0;
  for (int t = 1; t <= 20; ++t) {
    GaussianGradients g;
    g.reset(scene.size());
    float gp = float(rng.uniformDouble() * 2 - 1), gq = float(rng.uniformDouble() * 2 - 1);
    g.of(&GaussianScene::opacityLogit)[1] = gp;
    g.of(&GaussianScene::diffuse)[2 * 3 + 1] = gq;  // Gaussian 2's green
    adam.step(&scene, g, rates);
    auto reference = [&](double& x, double& mm, double& vv, double grad, double lr) {
      mm = 0.9 * mm + 0.1 * grad;
      vv = 0.999 * vv + 0.001 * grad * grad;
      double mhat = mm / (1 - std::pow(0.9, t)), vhat = vv / (1 - std::pow(0.999, t));
      x -= lr * mhat / (std::sqrt(vhat) + 1e-8);
    };
    reference(p, m, v, gp, 0.4);
    reference(q, mq, vq, gq, 0.5);
    EXPECT_NEAR(scene.opacityLogit[1], p, 1e-5) << "step " << t;
    EXPECT_NEAR(scene.diffuse[2].y, q, 1e-5) << "step " << t;
  }
  // Parameters without gradient stay where they were (their moments stay zero).
  EXPECT_EQ(scene.opacityLogit[0], untouched);
  EXPECT_EQ(adam.stepCount(), 20);
}

TEST(Adam, PositionNormalAndRoughnessRatesDecayLogLinearlyFromTheirStart) {
  LearningRates lr;
  float extent = 2.5f;
  EXPECT_NEAR(learningRatesAt(lr, extent, 0).of(&GaussianScene::position), 1.6e-4 * 2.5, 1e-9);
  EXPECT_NEAR(learningRatesAt(lr, extent, 16000).of(&GaussianScene::position), std::sqrt(1.6e-4 * 1.6e-6) * 2.5, 1e-9);
  EXPECT_NEAR(learningRatesAt(lr, extent, 32000).of(&GaussianScene::position), 1.6e-6 * 2.5, 1e-10);
  EXPECT_NEAR(learningRatesAt(lr, extent, 90000).of(&GaussianScene::position), 1.6e-6 * 2.5, 1e-10);
  EXPECT_EQ(learningRatesAt(lr, extent, 123).of(&GaussianScene::diffuse), lr.diffuse);
  EXPECT_EQ(learningRatesAt(lr, extent, 123).of(&GaussianScene::opacityLogit), lr.opacity);
  // The normal rate is constant by default, and decays like the position rate when asked.
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 5000).of(&GaussianScene::normal), lr.normal);
  lr.normalFinal = lr.normal / 100;
  lr.normalDecaySteps = 4000;
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 0).of(&GaussianScene::normal), lr.normal);
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 2000).of(&GaussianScene::normal), lr.normal / 10);
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 9000).of(&GaussianScene::normal), lr.normal / 100);
  // The roughness rate too, on its own schedule.
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 5000).of(&GaussianScene::roughness), lr.roughness);
  lr.roughnessFinal = lr.roughness / 10;
  lr.roughnessDecaySteps = 2000;
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 1000).of(&GaussianScene::roughness), lr.roughness / std::sqrt(10.0f));
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 2000).of(&GaussianScene::roughness), lr.roughness / 10);
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 2000).of(&GaussianScene::normal), lr.normal / 10);
  // A decay that starts late holds the initial rate until its start.
  lr.roughnessDecayStart = 3000;
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 2999).of(&GaussianScene::roughness), lr.roughness);
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 4000).of(&GaussianScene::roughness), lr.roughness / std::sqrt(10.0f));
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 5000).of(&GaussianScene::roughness), lr.roughness / 10);
  EXPECT_FLOAT_EQ(learningRatesAt(lr, extent, 9000).of(&GaussianScene::roughness), lr.roughness / 10);
}

TEST(Adam, FilterKeepsTheMomentsOfKeptGaussians) {
  GaussianScene scene;
  scene.resize(4);
  AdamOptimizer adam;
  adam.reset(4);
  GaussianGradients g;
  g.reset(4);
  for (int i = 0; i < 4; ++i) g.of(&GaussianScene::roughness)[i] = float(i + 1);
  adam.step(&scene, g, StepLearningRates{{1, 1, 1, 1, 1, 1, 1, 1}});
  adam.filter({true, false, false, true});
  ASSERT_EQ(adam.firstMoment().size(), 2u);
  EXPECT_FLOAT_EQ(adam.firstMoment().of(&GaussianScene::roughness)[0], 0.1f * 1);
  EXPECT_FLOAT_EQ(adam.firstMoment().of(&GaussianScene::roughness)[1], 0.1f * 4);
  EXPECT_NEAR(adam.secondMoment().of(&GaussianScene::roughness)[1], 0.001 * 16, 1e-6);
}

}  // namespace
}  // namespace glint
