// Gradient buffers: each output of the backward pass lands in its parameter's floats, and
// sizing, clearing, filtering and the per-range reduction touch every parameter.
#include "raytrace/gaussian_gradients.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

// A hit gradient whose every number differs: field f's component k is 10 f + k + 1.
HitGradient<double> distinctGradient() {
  HitGradient<double> g;
  g.v_position = {1, 2, 3};
  g.v_rotation = {11, 12, 13, 14};
  g.v_logScale = {21, 22, 23};
  g.v_opacityLogit = 31;
  g.v_diffuse = {41, 42, 43};
  g.v_normal = {51, 52, 53};
  g.v_roughness = 61;
  g.v_f0 = {71, 72, 73};
  g.weight = 0.5;
  return g;
}

TEST(GaussianGradients, AddRoutesEachFieldToItsParameter) {
  GaussianGradients g;
  g.reset(3);
  g.add(1, distinctGradient());
  g.add(1, distinctGradient());
  // Field f (in table order) holds 2 (10 f + k + 1) at Gaussian 1, zero elsewhere.
  forEachParameter([&](const auto& p) {
    std::span<const float> values = g.values[p.index];
    ASSERT_EQ(values.size(), 3u * p.components) << p.name;
    for (int k = 0; k < p.components; ++k) {
      EXPECT_EQ(values[size_t(p.components + k)], 2.0f * float(10 * p.index + k + 1)) << p.name << " " << k;
      EXPECT_EQ(values[size_t(k)], 0.0f) << p.name;
      EXPECT_EQ(values[size_t(2 * p.components + k)], 0.0f) << p.name;
    }
  });
  EXPECT_EQ(g.weight[1], 1.0f);
  EXPECT_EQ(g.of(&GaussianScene::opacityLogit)[1], 62.0f);
}

TEST(GaussianGradients, RangesAddZeroGrowAndFilterEveryParameter) {
  GaussianGradients a, b;
  a.reset(4);
  b.reset(4);
  for (size_t i = 0; i < 4; ++i) {
    a.add(i, distinctGradient());
    b.add(i, distinctGradient());
  }
  a.addRange(b, 1, 3);  // Gaussians 1 and 2 now hold twice the gradient
  a.zero(2, 3);         // and Gaussian 2 none
  a.grow(5);            // Gaussian 4 is new: zero
  a.filter({false, true, true, true, true});
  ASSERT_EQ(a.size(), 4u);
  const float expected[] = {2, 0, 1, 0};  // multiples of the gradient, Gaussians 1 to 4
  forEachParameter([&](const auto& p) {
    ASSERT_EQ(a.values[p.index].size(), 4u * p.components) << p.name;
    for (size_t i = 0; i < 4; ++i)
      for (int k = 0; k < p.components; ++k)
        EXPECT_EQ(a.values[p.index][i * p.components + k], expected[i] * float(10 * p.index + k + 1))
            << p.name << " Gaussian " << i;
  });
  EXPECT_EQ(a.weight, (std::vector<float>{1.0f, 0.0f, 0.5f, 0.0f}));
}

}  // namespace
}  // namespace glint
