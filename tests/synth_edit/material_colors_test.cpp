// Re-expressing materials for a requested diffuse and F0: every kind of material (dielectric,
// partial metal, pure metal, tinted specular) ends with exactly the requested factors.
#include "synth_edit/material_colors.h"

#include <gtest/gtest.h>

#include "math/rng.h"

namespace glint {
namespace {

void expectColor(const Vec3f& a, const Vec3f& b, float tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

Rgb randomColor(Rng& rng, float scale) { return Rgb(rng.uniform(), rng.uniform(), rng.uniform()) * scale; }

TEST(MaterialColors, AnyRequestedDiffuseAndF0IsReachedExactly) {
  Rng rng(6);
  for (int trial = 0; trial < 400; ++trial) {
    Material m;
    m.baseColor = randomColor(rng, 1.0f);
    m.metallic = trial % 4 == 0 ? 1.0f : (trial % 4 == 1 ? 0.0f : rng.uniform());
    m.specularLevel = rng.uniform();
    m.specularTint = randomColor(rng, 1.0f);
    m.roughness = rng.uniform();
    Rgb diffuse = trial % 3 == 0 ? Rgb(0.0f) : randomColor(rng, 1.5f);
    Rgb F0 = randomColor(rng, 1.0f);
    float roughness = m.roughness;
    setDiffuseAndF0(m, diffuse, F0);
    SurfaceMaterial result = materialFactors(m);
    expectColor(result.diffuse, diffuse, 1e-5f);
    expectColor(result.F0, F0, 1e-5f);
    EXPECT_EQ(result.roughness, roughness);
    EXPECT_LE(maxComponent(m.specularTint), 1.0f);
  }
}

TEST(MaterialColors, TheMappingKeepsWhatItCan) {
  // A dielectric keeps metallic 0, and its default specular for F0 = 0.04.
  Material paint;
  setDiffuseAndF0(paint, {0.1f, 0.2f, 0.3f}, Rgb(0.04f));
  EXPECT_EQ(paint.metallic, 0.0f);
  EXPECT_NEAR(paint.specularLevel, 0.5f, 1e-6f);
  EXPECT_EQ(paint.specularTint, Rgb(1.0f));
  EXPECT_EQ(paint.baseColor, Rgb(0.1f, 0.2f, 0.3f));

  // A pure metal without diffuse stays a metal whose base colour is its F0.
  Material chrome;
  chrome.metallic = 1.0f;
  setDiffuseAndF0(chrome, Rgb(0.0f), {0.9f, 0.5f, 0.2f});
  EXPECT_EQ(chrome.metallic, 1.0f);
  EXPECT_EQ(chrome.baseColor, Rgb(0.9f, 0.5f, 0.2f));

  // A half metal keeps its metallic while its metal part reflects less than F0...
  Material half;
  half.metallic = 0.5f;
  setDiffuseAndF0(half, Rgb(0.2f), Rgb(0.5f));  // baseColor 0.4, metal part 0.2, rest 0.3
  EXPECT_EQ(half.metallic, 0.5f);
  expectColor(half.baseColor, Rgb(0.4f), 1e-6f);
  EXPECT_NEAR(half.specularLevel, 0.3f / 0.5f / 0.08f, 1e-5f);
  // ...and becomes a dielectric when its metal part alone would exceed F0.
  setDiffuseAndF0(half, Rgb(0.4f), Rgb(0.1f));  // baseColor 0.8 -> metal part 0.4 > 0.1
  EXPECT_EQ(half.metallic, 0.0f);
  expectColor(half.baseColor, Rgb(0.4f), 1e-6f);
}

}  // namespace
}  // namespace glint
