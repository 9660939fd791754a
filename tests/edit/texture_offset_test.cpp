// The texture offset: on a checker floor with a hole, the offset found maps every point of the
// hole onto a square of the same colour; on a uniform floor there is none to find.
#include "edit/texture_offset.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "math/rng.h"

namespace glint {
namespace {

constexpr float kTextureSpacing = 0.05f, kSquare = 0.2f, kTextureHoleRadius = 0.17f;
const Rgb kLight(0.8f, 0.8f, 0.75f), kDark(0.12f, 0.12f, 0.14f);

bool lightSquare(float x, float z) {
  return (int64_t(std::floor(x / kSquare)) + int64_t(std::floor(z / kSquare))) % 2 == 0;
}

// The floor y = 0 over [-1.5, 1.5]^2 every 5 cm (jittered, as training leaves it), coloured by
// `colour`, none within the hole around (0.05, 0, 0.05) (off the checker's corners).
template <typename Colour>
GaussianScene floor(Colour colour) {
  GaussianScene s;
  Rng rng(7);
  for (int x = -30; x <= 30; ++x)
    for (int z = -30; z <= 30; ++z) {
      const Vec3f p(float(x) * kTextureSpacing + 0.01f * (rng.uniform() - 0.5f), 0,
                    float(z) * kTextureSpacing + 0.01f * (rng.uniform() - 0.5f));
      if (length(p - Vec3f(0.05f, 0, 0.05f)) < kTextureHoleRadius) continue;
      const size_t i = s.size();
      s.resize(i + 1);
      s.position[i] = p;
      s.normal[i] = {0, 1, 0};
      s.diffuse[i] = colour(p.x, p.z);
      s.logScale[i] = Vec3f(std::log(0.04f), std::log(0.004f), std::log(0.04f));
      s.opacityLogit[i] = logit(0.9f);
    }
  return s;
}

std::vector<Vec3f> holePoints() {
  std::vector<Vec3f> hole;
  for (int x = -4; x <= 4; ++x)
    for (int z = -4; z <= 4; ++z) {
      const Vec3f p(0.05f + float(x) * kTextureSpacing, 0, 0.05f + float(z) * kTextureSpacing);
      if (length(p - Vec3f(0.05f, 0, 0.05f)) < kTextureHoleRadius) hole.push_back(p);
    }
  return hole;
}

std::vector<uint32_t> all(const GaussianScene& s) {
  std::vector<uint32_t> indices(s.size());
  for (size_t i = 0; i < s.size(); ++i) indices[i] = uint32_t(i);
  return indices;
}

TEST(TextureOffset, ContinuesACheckerWithASquareOfTheSameColour) {
  const GaussianScene s = floor([](float x, float z) { return lightSquare(x, z) ? kLight : kDark; });
  const std::vector<Vec3f> hole = holePoints();
  const auto found = findTextureOffset(s, all(s), hole, {0, 1, 0}, kTextureSpacing, 2 * kTextureSpacing);
  ASSERT_TRUE(found.has_value());
  EXPECT_GT(found->correlation, 0.8f);
  EXPECT_NEAR(found->offset.y, 0.0f, 1e-5f);
  // Every hole point shifted lands on a square of its own colour, not only on average (the
  // offset's error, under one spacing, is allowed at the squares' edges).
  int same = 0;
  for (const Vec3f& p : hole) {
    const Vec3f q = p + found->offset;
    same += lightSquare(p.x, p.z) == lightSquare(q.x, q.z);
  }
  EXPECT_GE(same, int(0.9 * double(hole.size()))) << found->offset.x << " " << found->offset.z;
  EXPECT_GE(length(found->offset), 2 * kTextureHoleRadius);  // off the hole itself
}

TEST(TextureOffset, GivesUpOnASearchBeyondItsBudget) {
  const GaussianScene s = floor([](float x, float z) { return lightSquare(x, z) ? kLight : kDark; });
  TextureOffsetSettings settings;
  settings.maxWork = 1e5;  // the checker's search visits about 8e5 cells
  EXPECT_FALSE(findTextureOffset(s, all(s), holePoints(), {0, 1, 0}, kTextureSpacing, 2 * kTextureSpacing, settings).has_value());
  settings.maxWork = 1e8;
  EXPECT_TRUE(findTextureOffset(s, all(s), holePoints(), {0, 1, 0}, kTextureSpacing, 2 * kTextureSpacing, settings).has_value());
}

TEST(TextureOffset, SearchesNoOffsetShorterThanAsked) {
  const GaussianScene s = floor([](float x, float z) { return lightSquare(x, z) ? kLight : kDark; });
  TextureOffsetSettings settings;
  settings.minOffsetWidths = 3;  // the checker's period is under 3 hole widths
  const auto found = findTextureOffset(s, all(s), holePoints(), {0, 1, 0}, kTextureSpacing, 2 * kTextureSpacing, settings);
  if (found) {
    EXPECT_GE(length(found->offset), 3 * 7 * kTextureSpacing - 1e-4f);  // the hole is 7 cells wide
  }
  settings.minOffsetWidths = 10;  // beyond the search (2 widths): nothing to find
  EXPECT_FALSE(findTextureOffset(s, all(s), holePoints(), {0, 1, 0}, kTextureSpacing, 2 * kTextureSpacing, settings).has_value());
}

TEST(TextureOffset, FindsNoneOnAUniformOrNoisySurface) {
  Rng rng(3);
  const GaussianScene noisy =
      floor([&](float, float) { return Rgb(0.5f) * (1.0f + 0.05f * (rng.uniform() - 0.5f)); });
  // The best pair of opposite offsets correlates at 0.26 on this noise (the checker: 0.86).
  EXPECT_FALSE(findTextureOffset(noisy, all(noisy), holePoints(), {0, 1, 0}, kTextureSpacing, 2 * kTextureSpacing).has_value());
  const GaussianScene uniform = floor([](float, float) { return Rgb(0.5f); });
  EXPECT_FALSE(findTextureOffset(uniform, all(uniform), holePoints(), {0, 1, 0}, kTextureSpacing, 2 * kTextureSpacing).has_value());
}

TEST(TextureOffset, IgnoresGaussiansOffThePlaneOrFacingAway) {
  // The checker's colours on Gaussians that do not lie on the plane (or face along it) are no
  // texture of it: with only those, the floor is unknown and no offset is found.
  GaussianScene s = floor([](float x, float z) { return lightSquare(x, z) ? kLight : kDark; });
  GaussianScene lifted = s, turned = s;
  for (size_t i = 0; i < s.size(); ++i) lifted.position[i].y += 0.5f, turned.normal[i] = {1, 0, 0};
  EXPECT_FALSE(findTextureOffset(lifted, all(lifted), holePoints(), {0, 1, 0}, kTextureSpacing, 2 * kTextureSpacing).has_value());
  EXPECT_FALSE(findTextureOffset(turned, all(turned), holePoints(), {0, 1, 0}, kTextureSpacing, 2 * kTextureSpacing).has_value());
}

}  // namespace
}  // namespace glint
