// The parameter table: each entry names its own array, the scene's bookkeeping walks every
// entry, and the PLY names and rates are those the file formats and the config use.
#include "scene/gaussian_parameters.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace glint {
namespace {

// Gaussian i of a scene of n, every float distinct across parameters and Gaussians.
GaussianScene numberedScene(size_t n) {
  GaussianScene scene;
  scene.resize(n);
  float next = 1.0f;
  forEachParameter([&](const auto& p) {
    for (auto& value : scene.*p.values)
      for (int k = 0; k < p.components; ++k) component(value, k) = next++;
  });
  return scene;
}

TEST(GaussianParameters, EntriesNameTheirOwnArrays) {
  EXPECT_EQ(kGaussianParameterCount, 8u);
  EXPECT_EQ(parameterOf(&GaussianScene::position).index, 0u);
  EXPECT_EQ(parameterOf(&GaussianScene::rotation).components, 4);
  EXPECT_STREQ(parameterOf(&GaussianScene::logScale).name, "logScale");
  EXPECT_STREQ(parameterOf(&GaussianScene::opacityLogit).label, "opacity");
  EXPECT_STREQ(parameterOf(&GaussianScene::diffuse).label, "diffuse colour");
  EXPECT_EQ(parameterOf(&GaussianScene::f0).index, 7u);
  std::set<std::string> names;
  forEachParameter([&](const auto& p) { names.insert(p.name); });
  EXPECT_EQ(names.size(), kGaussianParameterCount);
}

TEST(GaussianParameters, ResizeGivesTheNeutralValues) {
  GaussianScene scene;
  scene.resize(2);
  ASSERT_TRUE(scene.consistent());
  EXPECT_EQ(scene.position[1], Vec3f(0.0f));
  EXPECT_EQ(scene.rotation[1].w, 1.0f);
  EXPECT_EQ(scene.rotation[1].x + scene.rotation[1].y + scene.rotation[1].z, 0.0f);
  EXPECT_EQ(scene.logScale[1], Vec3f(0.0f));
  EXPECT_EQ(scene.opacity(1), 0.5f);
  EXPECT_EQ(scene.diffuse[1], Rgb(0.0f));
  EXPECT_EQ(scene.normal[1], Vec3f(0.0f));
  EXPECT_EQ(scene.roughness[1], 0.0f);
  EXPECT_EQ(scene.f0[1], Rgb(0.04f));
}

TEST(GaussianParameters, AppendAndFilterMoveEveryParameter) {
  const GaussianScene source = numberedScene(4);
  GaussianScene scene;
  scene.append(source, 2);
  scene.append(source, 0);
  scene.append(source, 3);
  scene.filter({true, false, true});
  ASSERT_TRUE(scene.consistent());
  ASSERT_EQ(scene.size(), 2u);
  forEachParameter([&](const auto& p) {
    for (int k = 0; k < p.components; ++k) {
      EXPECT_EQ(component((scene.*p.values)[0], k), component((source.*p.values)[2], k)) << p.name;
      EXPECT_EQ(component((scene.*p.values)[1], k), component((source.*p.values)[3], k)) << p.name;
    }
  });
  scene.rotation.pop_back();
  EXPECT_FALSE(scene.consistent());
}

TEST(GaussianParameters, PlyNamesInOrderAreThePapersColumns) {
  std::vector<std::string> names;
  forEachParameterInPlyOrder([&](const auto& p) {
    for (const char* name : p.plyNames) names.push_back(name);
  });
  std::vector<std::string> expected = {"x",       "y",       "z",       "f_dc_0",   "f_dc_1",   "f_dc_2",
                                       "opacity", "scale_0", "scale_1", "scale_2",  "rot_0",    "rot_1",
                                       "rot_2",   "rot_3",   "normal_0", "normal_1", "normal_2", "roughness",
                                       "f0_0",    "f0_1",    "f0_2"};
  EXPECT_EQ(names, expected);
}

TEST(GaussianParameters, RatesNameTheirLearningRates) {
  LearningRates lr;
  EXPECT_EQ(&(lr.*parameterOf(&GaussianScene::position).rate.initial), &lr.positionInit);
  EXPECT_EQ(&(lr.*parameterOf(&GaussianScene::logScale).rate.initial), &lr.scale);
  EXPECT_EQ(&(lr.*parameterOf(&GaussianScene::normal).rate.final), &lr.normalFinal);
  EXPECT_EQ(&(lr.*parameterOf(&GaussianScene::roughness).rate.final), &lr.roughnessFinal);
  EXPECT_EQ(parameterOf(&GaussianScene::f0).rate.final, nullptr);
  std::set<std::string> keys;
  forEachParameter([&](const auto& p) { keys.insert(p.rate.key); });
  EXPECT_EQ(keys.size(), kGaussianParameterCount);
}

}  // namespace
}  // namespace glint
