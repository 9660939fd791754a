// Tests of next-event estimation: environment importance sampling against its density
// (chi-square, normalisation, per-sample consistency), the equirectangular mapping,
// emissive-triangle densities checked by ray casting, unbiased irradiance estimates for
// each light kind, and spot-light falloff.
#include "synth/light_sampler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "common/chi_square.h"
#include "math/rng.h"
#include "math/sampling.h"
#include "synth/mesh_builder.h"
#include "synth/ray_caster.h"

namespace glint {
namespace {

constexpr double kSignificance = 0.01;  // of the one chi-square test in this file
constexpr float kRotation = 0.7f;  // environment rotation about +Y, radians
constexpr float kInfinity = std::numeric_limits<float>::infinity();

bool nearRelative(double a, double b, double tolerance) { return std::abs(a - b) <= tolerance * std::abs(b); }

// Mean and standard error of a Monte Carlo estimate, per colour channel.
class MeanEstimate {
 public:
  void add(const Vec3d& x) {
    sum_ += x;
    sumSquares_ += x * x;
    ++count_;
  }
  void addZero() { ++count_; }
  Vec3d mean() const { return sum_ / double(count_); }
  Vec3d standardError() const {
    Vec3d m = mean(), variance = sumSquares_ / double(count_) - m * m;
    return {std::sqrt(std::max(0.0, variance.x) / count_), std::sqrt(std::max(0.0, variance.y) / count_),
            std::sqrt(std::max(0.0, variance.z) / count_)};
  }

 private:
  Vec3d sum_, sumSquares_;
  int64_t count_ = 0;
};

// A 32 x 16 equirectangular map, nonzero everywhere: colour gradients in both directions
// and a bright blob well above the horizon, so the sampling density varies by 100x.
Image makeEnvironmentMap() {
  Image map(32, 16, 3);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      float blob = 20.0f * std::exp(-(float((x - 22) * (x - 22) + (y - 5) * (y - 5))) / (2 * 1.5f * 1.5f));
      Rgb gradient(0.05f + 0.3f * x / 31, 0.1f + 0.2f * y / 15, 0.2f);
      map.setRgb(x, y, gradient + Rgb(1.0f, 0.8f, 0.5f) * blob);
    }
  return map;
}

// A tiny sphere (the sampler needs bounds) under an environment map.
MeshScene environmentScene() {
  MeshScene scene;
  scene.materials.push_back(Material{});
  scene.spheres.push_back({{0, 0, 0}, 0.01f, 0});
  scene.environment.map = makeEnvironmentMap();
  scene.environment.rotationY = kRotation;
  scene.environment.intensity = 1.5f;
  return scene;
}

// Directions from the sampler for the square sample u; nothing when it gave no sample.
std::optional<Vec3f> sampledDirection(const LightSampler& lights, Vec2f u) {
  LightSample s = lights.sample({0, 0, 0}, 0.5f, u);
  if (s.pdf <= 0) return std::nullopt;
  return s.wi;
}

TEST(EnvironmentSampling, DirectionsFollowEnvironmentPdf) {
  MeshScene scene = environmentScene();
  LightSampler lights(scene);
  auto result = test::testDirectionSampler(
      test::DirectionGrid::sphere(), [&](Vec2f u) { return sampledDirection(lights, u); },
      [&](const Vec3f& w) { return double(lights.environmentPdf(w)); }, 200000, 41, kSignificance);
  EXPECT_TRUE(result.passed) << result.message;
}

TEST(EnvironmentSampling, PdfIntegratesToOne) {
  MeshScene scene = environmentScene();
  LightSampler lights(scene);
  double integral = test::DirectionGrid::sphere().integrate([&](const Vec3f& w) { return lights.environmentPdf(w); },
                                                            1e-4);
  EXPECT_NEAR(integral, 1.0, 1e-3);
}

// True when uv lies within a float rounding error of a pixel edge, where the sampled pixel
// and the pixel the direction maps back to may differ after the round trip through trigonometry.
bool onPixelEdge(Vec2f uv, const Image& map) {
  auto nearInteger = [](float x) { return std::abs(x - std::round(x)) < 1e-4f; };
  return nearInteger(uv.x * map.width) || nearInteger(uv.y * map.height);
}

TEST(EnvironmentSampling, SamplesAgreeWithPdfAndRadiance) {
  MeshScene scene = environmentScene();
  LightSampler lights(scene);
  Rng rng(42);
  constexpr int kSamples = 100000;
  int onEdges = 0;
  for (int k = 0; k < kSamples; ++k) {
    LightSample s = lights.sample({0.3f, -0.2f, 0.1f}, rng.uniform(), rng.uniform2());
    ASSERT_GT(s.pdf, 0.0f);
    ASSERT_NEAR(length(s.wi), 1.0f, 1e-5f);
    ASSERT_FALSE(s.isDelta);
    ASSERT_TRUE(std::isinf(s.distance));
    ASSERT_EQ(s.radiance, lights.environmentRadiance(s.wi)) << "sample " << k;
    float pdf = lights.environmentPdf(s.wi);
    if (nearRelative(s.pdf, pdf, 1e-3)) continue;
    Vec2f uv = directionToEquirect(s.wi, kRotation);
    ASSERT_TRUE(onPixelEdge(uv, scene.environment.map))
        << "sample " << k << ": pdf " << s.pdf << " but environmentPdf gives " << pdf << " at pixel coordinates ("
        << uv.x * scene.environment.map.width << ", " << uv.y * scene.environment.map.height << ")";
    ++onEdges;
  }
  EXPECT_LE(onEdges, kSamples / 10000) << "too many samples on pixel edges";
}

TEST(EnvironmentSampling, EstimatesTheEnvironmentsIntegralWithLowVariance) {
  MeshScene scene = environmentScene();
  LightSampler lights(scene);
  const Image& map = scene.environment.map;
  // Exact: each pixel is constant over its patch of solid angle 2 pi / W (cos theta0 - cos theta1).
  double exact = 0;
  for (int y = 0; y < map.height; ++y) {
    double solidAngle = 2 * kPi / map.width * (std::cos(kPi * y / map.height) - std::cos(kPi * (y + 1) / map.height));
    for (int x = 0; x < map.width; ++x) exact += luminance(map.rgb(x, y)) * scene.environment.intensity * solidAngle;
  }
  Rng rng(43);
  constexpr int kSamples = 100000;
  MeanEstimate estimate;
  for (int k = 0; k < kSamples; ++k) {
    LightSample s = lights.sample({0, 0, 0}, rng.uniform(), rng.uniform2());
    estimate.add(Vec3d(s.pdf > 0 ? luminance(s.radiance) / s.pdf : 0.0));
  }
  EXPECT_NEAR(estimate.mean().x, exact, 5 * estimate.standardError().x);
  // Importance sampling by luminance leaves only the sin(theta) variation within rows:
  // a sampler that ignored the map would show a relative deviation above 1 here.
  EXPECT_LT(estimate.standardError().x * std::sqrt(double(kSamples)) / exact, 0.1)
      << "relative standard deviation of one sample";
}

TEST(EnvironmentSampling, RadianceComesFromTheMapPixelInThatDirection) {
  MeshScene scene = environmentScene();
  LightSampler lights(scene);
  const Image& map = scene.environment.map;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x) {
      Vec2f center((x + 0.5f) / map.width, (y + 0.5f) / map.height);
      Vec3f dir = equirectToDirection(center, kRotation);
      EXPECT_EQ(lights.environmentRadiance(dir), map.rgb(x, y) * scene.environment.intensity) << x << ", " << y;
    }
  // The top row is up, the bottom row down (their azimuth is arbitrary at the pole itself).
  Vec2f top = directionToEquirect({0, 1, 0}, kRotation), bottom = directionToEquirect({0, -1, 0}, kRotation);
  EXPECT_EQ(top.y, 0.0f);
  EXPECT_GT(bottom.y, 1.0f - 1e-6f);
  EXPECT_EQ(lights.environmentRadiance({0, 1, 0}), map.rgb(int(top.x * map.width), 0) * scene.environment.intensity);
  EXPECT_EQ(lights.environmentRadiance({0, -1, 0}),
            map.rgb(int(bottom.x * map.width), map.height - 1) * scene.environment.intensity);
}

TEST(Equirect, MappingsAreInverse) {
  Rng rng(44);
  for (float rotation : {0.0f, kRotation, -2.5f, 9.0f}) {
    for (int k = 0; k < 20000; ++k) {
      // Away from the poles, where azimuth is undefined.
      Vec2f uv(rng.uniform(), 0.001f + 0.998f * rng.uniform());
      Vec3f dir = equirectToDirection(uv, rotation);
      ASSERT_NEAR(length(dir), 1.0f, 1e-5f);
      Vec2f back = directionToEquirect(dir, rotation);
      float du = std::abs(back.x - uv.x);
      EXPECT_LT(std::min(du, 1 - du), 1e-5f) << "u " << uv.x << " rotation " << rotation;  // u wraps around
      EXPECT_NEAR(back.y, uv.y, 1e-5f);
      // And from directions.
      Vec3f w = sampleUniformSphere(rng.uniform2());
      Vec2f p = directionToEquirect(w, rotation);
      ASSERT_GE(p.x, 0.0f);
      ASSERT_LT(p.x, 1.0f);
      ASSERT_GE(p.y, 0.0f);
      ASSERT_LT(p.y, 1.0f);
      Vec3f wBack = equirectToDirection(p, rotation);
      EXPECT_LT(length(wBack - w), 1e-4f);
    }
  }
}

TEST(Equirect, PolarAngleKeepsItsPrecisionNearThePoles) {
  // The solid-angle density divides by sin(theta), so theta needs relative precision there.
  for (float v : {1e-3f, 1e-4f, 1e-5f}) {
    for (float pole : {0.0f, 1.0f}) {
      float vv = pole == 0 ? v : 1 - v, fromPole = pole == 0 ? vv : 1 - vv;  // 1 - vv is exact
      Vec2f back = directionToEquirect(equirectToDirection({0.3f, vv}, kRotation), kRotation);
      EXPECT_NEAR(pole == 0 ? back.y : 1 - back.y, fromPole, 1e-3f * fromPole) << "v = " << vv;
    }
  }
}

TEST(Equirect, Conventions) {
  // v = 0 is straight up, v = 1/2 the horizon; u grows from +X towards +Z; rotation adds to azimuth.
  Vec3f up = equirectToDirection({0.3f, 0.0f}, 0.0f);
  EXPECT_NEAR(up.y, 1.0f, 1e-6f);
  Vec3f x = equirectToDirection({0.0f, 0.5f}, 0.0f), z = equirectToDirection({0.25f, 0.5f}, 0.0f);
  EXPECT_LT(length(x - Vec3f(1, 0, 0)), 1e-6f);
  EXPECT_LT(length(z - Vec3f(0, 0, 1)), 1e-6f);
  Vec3f rotated = equirectToDirection({0.0f, 0.5f}, kPi / 2);
  EXPECT_LT(length(rotated - Vec3f(0, 0, 1)), 1e-6f);
}

TEST(Equirect, StaysBelowOneJustUnderTheSeam) {
  // Azimuth a hair below the seam: u must still be in [0, 1), like v, so pixel lookups
  // never need to clamp.
  for (float rotation : {0.0f, kRotation}) {
    Vec3f dir = equirectToDirection({0.0f, 0.5f}, rotation);
    Vec3f justBelow = normalize(dir - Vec3f(-dir.z, 0, dir.x) * 1e-9f);
    Vec2f uv = directionToEquirect(justBelow, rotation);
    EXPECT_GE(uv.x, 0.0f);
    EXPECT_LT(uv.x, 1.0f);
  }
  Vec2f south = directionToEquirect({0, -1, 0}, 0.0f);
  EXPECT_LT(south.y, 1.0f);
}

TEST(ConstantEnvironment, UniformPdfAndConstantRadiance) {
  MeshScene scene;
  scene.materials.push_back(Material{});
  scene.spheres.push_back({{0, 0, 0}, 1.0f, 0});
  scene.environment.constant = Rgb(0.5f, 1.0f, 2.0f);
  scene.environment.intensity = 2.0f;
  LightSampler lights(scene);
  ASSERT_FALSE(lights.empty());
  Rng rng(45);
  for (int k = 0; k < 1000; ++k) {
    LightSample s = lights.sample({0.1f, 0.2f, 0.3f}, rng.uniform(), rng.uniform2());
    EXPECT_NEAR(s.pdf, kInv4Pi, 1e-6f);
    EXPECT_EQ(s.radiance, Rgb(1.0f, 2.0f, 4.0f));
    EXPECT_TRUE(std::isinf(s.distance));
    EXPECT_NEAR(length(s.wi), 1.0f, 1e-5f);
    Vec3f w = sampleUniformSphere(rng.uniform2());
    EXPECT_NEAR(lights.environmentPdf(w), kInv4Pi, 1e-6f);
    EXPECT_EQ(lights.environmentRadiance(w), Rgb(1.0f, 2.0f, 4.0f));
  }
}

TEST(LightSampler, NoLightsMeansEmpty) {
  MeshScene scene;
  scene.materials.push_back(Material{});
  scene.spheres.push_back({{0, 0, 0}, 1.0f, 0});
  scene.environment.constant = Rgb(1.0f);
  scene.environment.intensity = 0.0f;  // black after all
  LightSampler lights(scene);
  EXPECT_TRUE(lights.empty());
  EXPECT_EQ(lights.sample({0, 0, 0}, 0.5f, {0.5f, 0.5f}).pdf, 0.0f);
  EXPECT_EQ(lights.environmentPdf({0, 1, 0}), 0.0f);
}

// Two emissive parallelograms of different areas and colours above a dark floor.
struct QuadLight {
  Vec3f corner, u, v;
  Rgb emission;
};
const QuadLight kQuadLights[2] = {
    {{-0.5f, 1.5f, -0.75f}, {1.2f, 0, 0}, {0, 0.3f, 1.5f}, {4, 3, 2}},
    {{1.5f, -0.3f, -0.2f}, {0, 0.5f, 0.1f}, {0.1f, 0, 0.4f}, {1, 2, 6}},
};

// Mesh 0 is the floor; mesh i + 1 is kQuadLights[i].
MeshScene quadLightScene() {
  MeshScene scene;
  scene.materials.push_back(Material{});
  scene.meshes.push_back(makeQuad("floor", {-3, -1, -3}, {0, 0, 6}, {6, 0, 0}, 0));
  for (const QuadLight& q : kQuadLights) {
    Material light;
    light.emission = q.emission;
    scene.materials.push_back(light);
    scene.meshes.push_back(makeQuad("light", q.corner, q.u, q.v, int(scene.materials.size()) - 1));
  }
  return scene;
}

float quadArea(const QuadLight& q) { return length(cross(q.u, q.v)); }

// Expects two estimates (or an estimate and an exact value) to agree within 5 combined standard errors.
void expectAgree(const MeanEstimate& a, const Vec3d& b, const Vec3d& bError, const char* what) {
  Vec3d ma = a.mean(), ea = a.standardError();
  for (int c = 0; c < 3; ++c) {
    double tolerance = 5 * std::sqrt(ea[c] * ea[c] + bError[c] * bError[c]);
    EXPECT_NEAR(ma[c], b[c], tolerance) << what << ", channel " << c;
    EXPECT_GT(b[c], 10 * tolerance) << what << ": the comparison is too noisy to mean anything";
  }
}

// Irradiance at p (normal n) from both two-sided quads by uniform sampling of their areas,
// E = sum of A E[L cos(theta_p) cos(theta_q) / r^2]; independent of the light sampler.
MeanEstimate quadsIrradianceByArea(const Vec3f& p, const Vec3f& n, uint64_t seed) {
  Rng rng(seed);
  MeanEstimate e;
  for (int k = 0; k < 1000000; ++k) {
    Vec3d sum;
    for (const QuadLight& q : kQuadLights) {
      Vec3d u(q.u), v(q.v), areaNormal = cross(u, v);  // length = area, so A cos(theta_q) = |areaNormal . w|
      Vec3d d = Vec3d(q.corner) + u * rng.uniformDouble() + v * rng.uniformDouble() - Vec3d(p);
      double r2 = dot(d, d);
      Vec3d w = d / std::sqrt(r2);
      sum += Vec3d(q.emission) * (std::max(0.0, dot(Vec3d(n), w)) * std::abs(dot(areaNormal, w)) / r2);
    }
    e.add(sum);
  }
  return e;
}

TEST(EmitterSampling, PdfMatchesEmitterPdfWhereTheRayLands) {
  MeshScene scene = quadLightScene();
  RayCaster caster(scene);
  LightSampler lights(scene);
  const Vec3f p(0.1f, 0.2f, -0.1f);
  constexpr int kSamples = 20000;
  int perLight[2] = {0, 0}, misses = 0;
  Rng rng(46);
  for (int k = 0; k < kSamples; ++k) {
    LightSample s = lights.sample(p, rng.uniform(), rng.uniform2());
    ASSERT_GT(s.pdf, 0.0f);
    ASSERT_FALSE(s.isDelta);
    ASSERT_TRUE(std::isfinite(s.distance));
    SurfaceHit hit;
    if (!caster.intersect(p, s.wi, 0.0f, kInfinity, &hit)) {
      ++misses;  // a sample on the very edge of a quad, where the ray may slip past
      continue;
    }
    ASSERT_TRUE(hit.mesh == 1 || hit.mesh == 2) << "sample " << k << " landed on mesh " << hit.mesh;
    EXPECT_NEAR(hit.t, s.distance, 1e-4f * s.distance);
    EXPECT_EQ(s.radiance, kQuadLights[hit.mesh - 1].emission);
    float pdf = lights.emitterPdf(p, hit.position, hit.geometricNormal, hit.mesh, hit.triangle);
    EXPECT_TRUE(nearRelative(s.pdf, pdf, 1e-3)) << "sample " << k << ": pdf " << s.pdf << ", emitterPdf " << pdf;
    ++perLight[hit.mesh - 1];
  }
  EXPECT_LE(misses, kSamples / 10000);
  // Lights are chosen in proportion to their power, area x luminance.
  double power0 = quadArea(kQuadLights[0]) * luminance(kQuadLights[0].emission);
  double power1 = quadArea(kQuadLights[1]) * luminance(kQuadLights[1].emission);
  double expected1 = power1 / (power0 + power1);
  int hits = perLight[0] + perLight[1];
  EXPECT_NEAR(perLight[1], hits * expected1, 5 * std::sqrt(hits * expected1 * (1 - expected1)));
  // Surfaces that do not emit have no density.
  EXPECT_EQ(lights.emitterPdf(p, {0, -1, 0}, {0, 1, 0}, 0, 0), 0.0f);
  EXPECT_EQ(lights.emitterPdf(p, {0, -1, 0}, {0, 1, 0}, -1, -1), 0.0f);
}

TEST(EmitterSampling, IrradianceMatchesAreaSampling) {
  MeshScene scene = quadLightScene();
  LightSampler lights(scene);
  const Vec3f p(0.1f, 0.2f, -0.1f), n = normalize(Vec3f(0.3f, 1.0f, 0.1f));
  MeanEstimate sampled;
  Rng rng(47);
  for (int k = 0; k < 200000; ++k) {
    LightSample s = lights.sample(p, rng.uniform(), rng.uniform2());
    if (s.pdf > 0) sampled.add(Vec3d(s.radiance) * (std::max(0.0f, dot(n, s.wi)) / double(s.pdf)));
    else sampled.addZero();
  }
  MeanEstimate reference = quadsIrradianceByArea(p, n, 48);
  expectAgree(sampled, reference.mean(), reference.standardError(), "irradiance from two quads");
}

TEST(MixedLights, EveryKindIsChosenAsOftenAsItsDensitySaysAndUnbiased) {
  MeshScene scene = quadLightScene();
  PunctualLight point;
  point.position = {0.5f, 2.5f, 0.3f};
  point.intensity = {2.0f, 2.0f, 1.5f};
  scene.lights.push_back(point);
  scene.environment.constant = Rgb(0.3f, 0.35f, 0.4f);
  LightSampler lights(scene);
  const Vec3f p(0.1f, 0.2f, -0.1f), n = normalize(Vec3f(0.3f, 1.0f, 0.1f));

  // Contributions radiance x cos / pdf, kept apart by kind; each estimates that kind's irradiance.
  enum { kEmitter, kPoint, kEnvironment };
  MeanEstimate byKind[3];
  int counts[3] = {0, 0, 0};
  float pointPdf = 0, environmentPdf = 0;
  constexpr int kSamples = 400000;
  Rng rng(49);
  for (int k = 0; k < kSamples; ++k) {
    LightSample s = lights.sample(p, rng.uniform(), rng.uniform2());
    int kind = s.isDelta ? kPoint : (std::isinf(s.distance) ? kEnvironment : kEmitter);
    ++counts[kind];
    if (kind == kPoint) pointPdf = s.pdf;  // the choice probability itself
    if (kind == kEnvironment) environmentPdf = s.pdf;  // choice probability / (4 pi)
    for (int other = 0; other < 3; ++other) {
      if (other == kind && s.pdf > 0)
        byKind[other].add(Vec3d(s.radiance) * (std::max(0.0f, dot(n, s.wi)) / double(s.pdf)));
      else
        byKind[other].addZero();
    }
  }
  for (int kind = 0; kind < 3; ++kind) EXPECT_GT(counts[kind], kSamples / 50) << "kind " << kind;
  auto expectFrequency = [&](int count, double probability, const char* what) {
    EXPECT_NEAR(count, kSamples * probability, 5 * std::sqrt(kSamples * probability * (1 - probability))) << what;
  };
  expectFrequency(counts[kPoint], pointPdf, "point light");
  expectFrequency(counts[kEnvironment], environmentPdf * 4 * kPi, "environment");
  EXPECT_NEAR(lights.environmentPdf(n), environmentPdf, 1e-6f);

  // Exact irradiance from the point light (I cos / d^2) and from the constant environment
  // over the upper hemisphere (pi L); the quads by independent area sampling.
  Vec3f toLight = point.position - p;
  double d2 = dot(toLight, toLight), cosLight = dot(n, toLight) / std::sqrt(d2);
  expectAgree(byKind[kPoint], Vec3d(point.intensity) * (cosLight / d2), Vec3d(0.0), "point light");
  expectAgree(byKind[kEnvironment], Vec3d(scene.environment.constant) * double(kPi), Vec3d(0.0), "environment");
  MeanEstimate quads = quadsIrradianceByArea(p, n, 50);
  expectAgree(byKind[kEmitter], quads.mean(), quads.standardError(), "quads");
}

// Scene with one spot light above the origin, pointing down.
MeshScene spotScene(float innerAngle, float outerAngle) {
  MeshScene scene;
  scene.materials.push_back(Material{});
  scene.spheres.push_back({{0, -5, 0}, 0.1f, 0});
  PunctualLight spot;
  spot.type = PunctualLight::Type::Spot;
  spot.position = {0, 2, 0};
  spot.direction = {0, -3, 0};  // not unit: the sampler normalises it
  spot.intensity = {3, 2, 1};
  spot.innerConeAngle = innerAngle;
  spot.outerConeAngle = outerAngle;
  scene.lights.push_back(spot);
  return scene;
}

// The spot's angular falloff seen from the point at angle `angle` off its axis (distance 2
// below the light along the axis), recovered from the sampled irradiance I falloff / d^2.
float spotFalloff(const LightSampler& lights, float angle, float azimuth = 0.4f) {
  float r = 2 * std::tan(angle);
  Vec3f p(r * std::cos(azimuth), 0, r * std::sin(azimuth));
  LightSample s = lights.sample(p, 0.3f, {0.5f, 0.5f});
  Vec3f d = Vec3f(0, 2, 0) - p;
  EXPECT_TRUE(s.isDelta);
  EXPECT_EQ(s.pdf, 1.0f);
  EXPECT_NEAR(s.distance, length(d), 1e-5f);
  EXPECT_LT(length(s.wi - normalize(d)), 1e-6f);
  return s.radiance.x * dot(d, d) / 3;
}

TEST(SpotLight, ZeroOutsideFullInsideSmoothBetween) {
  constexpr float kInner = 0.2f, kOuter = 0.4f;
  MeshScene scene = spotScene(kInner, kOuter);
  LightSampler lights(scene);
  for (float angle : {0.0f, 0.05f, 0.15f, 0.199f}) EXPECT_NEAR(spotFalloff(lights, angle), 1.0f, 1e-5f) << angle;
  for (float angle : {0.401f, 0.5f, 1.0f, 1.5f}) EXPECT_EQ(spotFalloff(lights, angle), 0.0f) << angle;
  // Behind the light.
  LightSample behind = lights.sample({0.1f, 3, 0}, 0.3f, {0.5f, 0.5f});
  EXPECT_EQ(behind.radiance, Rgb(0.0f));
  // Between the cones: strictly inside (0, 1), decreasing, with no jumps.
  float previous = 1.0f;
  for (float angle = kInner + 0.001f; angle < kOuter - 0.0005f; angle += 0.001f) {
    float f = spotFalloff(lights, angle, angle * 7);  // azimuth varies too: the cone is round
    EXPECT_GT(f, 0.0f) << angle;
    EXPECT_LT(f, 1.0f) << angle;
    EXPECT_LE(f, previous + 1e-6f) << angle;
    EXPECT_LT(previous - f, 0.02f) << angle;
    previous = f;
  }
  EXPECT_LT(previous, 0.02f);  // and it fades out continuously at the outer cone
  // The colour follows the intensity.
  LightSample s = lights.sample({0, 0, 0}, 0.3f, {0.5f, 0.5f});
  EXPECT_NEAR(s.radiance.x, 3.0f / 4, 1e-5f);
  EXPECT_NEAR(s.radiance.y, 2.0f / 4, 1e-5f);
  EXPECT_NEAR(s.radiance.z, 1.0f / 4, 1e-5f);
}

TEST(SpotLight, EqualConesGiveAHardEdge) {
  MeshScene scene = spotScene(0.3f, 0.3f);
  LightSampler lights(scene);
  EXPECT_EQ(spotFalloff(lights, 0.29f), 1.0f);
  EXPECT_EQ(spotFalloff(lights, 0.31f), 0.0f);
}

TEST(DirectionalLight, ArrivesFromInfinityAgainstItsDirection) {
  MeshScene scene;
  scene.materials.push_back(Material{});
  scene.spheres.push_back({{0, 0, 0}, 1.0f, 0});
  PunctualLight sun;
  sun.type = PunctualLight::Type::Directional;
  sun.direction = {1, -2, 0.5f};
  sun.intensity = {5, 4, 3};
  scene.lights.push_back(sun);
  LightSampler lights(scene);
  LightSample s = lights.sample({0.3f, 0.1f, 0.2f}, 0.9f, {0.1f, 0.7f});
  EXPECT_TRUE(s.isDelta);
  EXPECT_TRUE(std::isinf(s.distance));
  EXPECT_EQ(s.pdf, 1.0f);
  EXPECT_EQ(s.radiance, sun.intensity);
  EXPECT_LT(length(s.wi + normalize(sun.direction)), 1e-6f);
}

}  // namespace
}  // namespace glint
