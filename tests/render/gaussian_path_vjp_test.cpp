// Finite-difference tests of tracePath_vjp (render/gaussian_path.h) on a recorded three-segment
// path (fixed keys, hence fixed random numbers): a mirror reflects the camera ray onto a
// second reflective layer, which reflects it into a cluster of overlapping p = 3
// Gaussians. With the segment rays and throughputs held as recorded (the paper's detached
// gradient), L_r is differentiated through each reflected segment's blended diffuse by a
// double-precision compositor, and compared with tracePath_vjp.
#include "render/gaussian_path.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "common/double_compositor.h"
#include "common/finite_difference.h"
#include "common/ggx_reference.h"
#include "math/frame.h"
#include "math/rng.h"

namespace glint {
namespace {

using test::kParams;

// The path's keys (seed, view, pixel, sample): they fix its random numbers.
constexpr uint64_t kSeed = 3, kView = 1, kPixel = 42, kSample = 7;
constexpr double kMirrorRoughness = 0.2, kLayerRoughness = 0.35;

struct GaussianSpec {
  Vec3d mean;
  Quatd rotation;
  Vec3d scale;
  double opacity;
  Vec3d diffuse, normal;
  double roughness;
  Vec3d f0;
};

void addGaussian(std::vector<double>* x, const GaussianSpec& g) {
  double p[kParams] = {g.mean.x, g.mean.y, g.mean.z, g.rotation.w, g.rotation.x, g.rotation.y, g.rotation.z,
                       std::log(g.scale.x), std::log(g.scale.y), std::log(g.scale.z),
                       std::log(g.opacity / (1 - g.opacity)), g.diffuse.x, g.diffuse.y, g.diffuse.z,
                       g.normal.x, g.normal.y, g.normal.z, g.roughness, g.f0.x, g.f0.y, g.f0.z};
  x->insert(x->end(), p, p + kParams);
}

// The rotation taking the local z axis (a flat Gaussian's thin axis) to the unit vector n.
Quatd rotationFromZ(const Vec3d& n) {
  Vec3d axis = cross(Vec3d(0, 0, 1), n);
  double s = length(axis);
  if (s < 1e-12) return Quatd{};
  double angle = std::atan2(s, n.z);
  axis = axis / s;
  return {std::cos(angle / 2), std::sin(angle / 2) * axis.x, std::sin(angle / 2) * axis.y,
          std::sin(angle / 2) * axis.z};
}

double uniformIn(Rng& rng, double lo, double hi) { return lo + (hi - lo) * rng.uniformDouble(); }
Vec3d uniformRgb(Rng& rng, double lo, double hi) {
  return {uniformIn(rng, lo, hi), uniformIn(rng, lo, hi), uniformIn(rng, lo, hi)};
}

// A square reflective layer of flat, overlapping, fairly opaque Gaussians around `centre`
// facing `normal`, jittered slightly in orientation and offset along the normal on seven
// levels that differ between neighbours (so the hits of one ray have distinct keys).
void addReflectiveLayer(std::vector<double>* x, Rng& rng, const Vec3d& centre, const Vec3d& normal, int half,
                        double roughness) {
  Framed frame = Framed::fromNormal(normal);
  Quatd q = rotationFromZ(normal);
  for (int i = -half; i <= half; ++i)
    for (int j = -half; j <= half; ++j) {
      GaussianSpec g;
      g.mean = centre + frame.s * (0.1 * i) + frame.t * (0.1 * j) + normal * (0.008 * ((3 * i + 5 * j + 21) % 7 - 3));
      g.rotation = {q.w + uniformIn(rng, -0.03, 0.03), q.x + uniformIn(rng, -0.03, 0.03),
                    q.y + uniformIn(rng, -0.03, 0.03), q.z + uniformIn(rng, -0.03, 0.03)};
      g.scale = {0.06, 0.06, 0.01};
      g.opacity = uniformIn(rng, 0.55, 0.75);
      g.diffuse = uniformRgb(rng, 0.1, 0.9);
      g.normal = normal;
      g.roughness = roughness;
      g.f0 = Vec3d(0.6);
      addGaussian(x, g);
    }
}

// Overlapping Gaussians of partial opacity and random shapes along the ray o + t d.
void addCluster(std::vector<double>* x, Rng& rng, const Vec3d& o, const Vec3d& d) {
  Framed frame = Framed::fromNormal(d);
  for (double t : {0.5, 0.62, 0.74, 0.86, 0.98}) {
    GaussianSpec g;
    g.mean = o + d * t + frame.s * uniformIn(rng, -0.05, 0.05) + frame.t * uniformIn(rng, -0.05, 0.05);
    g.rotation = {uniformIn(rng, 0.5, 1.5), uniformIn(rng, -1, 1), uniformIn(rng, -1, 1), uniformIn(rng, -1, 1)};
    g.scale = {uniformIn(rng, 0.08, 0.2), uniformIn(rng, 0.08, 0.2), uniformIn(rng, 0.08, 0.2)};
    g.opacity = uniformIn(rng, 0.25, 0.6);
    g.diffuse = uniformRgb(rng, 0.1, 0.9);
    g.normal = normalize(Vec3d(uniformIn(rng, -1, 1), uniformIn(rng, -1, 1), uniformIn(rng, -1, 1)));
    g.roughness = uniformIn(rng, 0, 1);
    g.f0 = uniformRgb(rng, 0, 1);
    addGaussian(x, g);
  }
}

// One recorded path through the scene, with everything needed to replay it.
struct PathCase {
  std::vector<double> x;
  GaussianScene scene;
  std::unique_ptr<GaussianTracer> tracer;
  TraceSettings trace = [] {
    TraceSettings t;
    t.kernelPower = 3.0f;  // the case was laid out for power 3 (its segments' hit counts differ)
    return t;
  }();
  PathSettings settings;
  TraceRay primary;
  PathResult path;
  std::vector<PathSegment> segments;

  void retrace() {
    scene = test::toScene(x);
    tracer = makeGaussianTracer("fast");
    tracer->build(scene, trace);
    path = tracePath(*tracer, primary, settings, kSeed, kView, kPixel, kSample, &segments);
    segments.resize(size_t(path.segments));
  }
};

// The mirror at z = 0 reflects the camera ray onto a layer tilted to send it along +x
// (both rough, so the directions are GGX samples); the cluster sits on the last segment's
// ray as first traced (it is hit by no earlier segment, so that ray does not move).
PathCase makePathCase(size_t hitListCapacity = 512) {
  PathCase c;
  c.trace.exactTail = true;  // as in training
  c.settings.bounces = 2;
  c.settings.hitListCapacity = hitListCapacity;
  c.primary = {Vec3f(0, -1, 1), normalize(Vec3f(0, 1, -1)), 0.0f};
  Rng rng(2024);
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j) {
      GaussianSpec g{Vec3d(0.1 * i, 0.1 * j, 0), Quatd{}, Vec3d(0.08, 0.08, 0.004), 0.98, Vec3d(0.2),
                     Vec3d(0, 0, 1), kMirrorRoughness, Vec3d(0.6)};
      addGaussian(&c.x, g);
    }
  Vec3d toLayer = normalize(Vec3d(0, 1, 1));
  addReflectiveLayer(&c.x, rng, Vec3d(0, 1, 1), normalize(Vec3d(1, 0, 0) - toLayer), 3, kLayerRoughness);
  test::roundToFloat(&c.x);
  c.retrace();
  EXPECT_EQ(c.path.segments, 3) << "the layers must reflect the path twice";
  if (c.path.segments != 3) return c;
  TraceRay last = c.segments[2].ray;
  addCluster(&c.x, rng, Vec3d(last.origin), Vec3d(last.direction));
  test::roundToFloat(&c.x);
  c.retrace();
  EXPECT_EQ(c.path.segments, 3);
  EXPECT_EQ(c.segments[2].ray.origin, last.origin);
  EXPECT_EQ(c.segments[2].ray.direction, last.direction);
  return c;
}

std::set<uint32_t> hitIds(const PathSegment& segment) {
  std::set<uint32_t> ids;
  for (const HitRecord& h : segment.hits.hits) ids.insert(h.id);
  return ids;
}

// The loss of the test: a fixed linear function of the path's specular sum, L = g . specular
// (the L1 loss of training is linear near any point away from its kink).
struct LossSetup {
  Rgb g{0.7f, -0.5f, 0.9f};  // dL/d specular

  explicit LossSetup(const Rgb&) {}
  double loss(const Vec3d& specular) const { return dot(Vec3d(g), specular); }
};

// The whole-scene gradient tracePath_vjp<T> hands out for dL/d specular = g (and dL/d the
// first segment's result = vFirst), and the Gaussians it reached.
template <typename T>
std::vector<double> reflectionGradient(const PathCase& c, const Rgb& g, std::set<uint32_t>* reached = nullptr,
                                       int* overflowed = nullptr, const RayResultAdjoint& vFirst = {}) {
  std::vector<double> gradient(c.x.size(), 0.0);
  RayBackwardScratch<T> scratch;
  int skipped = tracePath_vjp<T>(c.scene, c.trace, c.segments, vFirst, g, PathGradientSettings{}, scratch,
                                      [&](uint32_t id, const HitGradient<T>& hg) {
                                        test::accumulate(&gradient, id, hg);
                                        if (reached) reached->insert(id);
                                      });
  if (overflowed) *overflowed = skipped;
  return gradient;
}

TEST(TracePathVjp, MatchesFiniteDifferencesThroughTheReflectedSegments) {
  PathCase c = makePathCase();
  ASSERT_EQ(c.segments.size(), 3u);
  // The Gaussians each reflected segment composites, and the double forward of its ray:
  // the same hits in the same order, the same blended diffuse, no truncation and no
  // discontinuity within reach of a finite-difference step.
  std::vector<std::set<uint32_t>> hits;
  std::vector<test::Forward> forwards;
  for (const PathSegment& s : c.segments) {
    hits.push_back(hitIds(s));
    forwards.push_back(test::traceDouble(c.x, s.ray, c.trace));
  }
  EXPECT_GE(hits[1].size(), 2u);
  EXPECT_GE(hits[2].size(), 3u);
  std::vector<uint32_t> varied;  // the Gaussians L_r is differentiated against
  std::vector<int> segmentOf;
  for (size_t k = 1; k < 3; ++k) {
    const PathSegment& s = c.segments[k];
    const test::Forward& f = forwards[k];
    ASSERT_FALSE(s.result.truncated || s.hits.overflowed) << "segment " << k;
    ASSERT_EQ(f.composited.size(), s.hits.hits.size()) << "segment " << k;
    for (size_t i = 0; i < f.composited.size(); ++i) EXPECT_EQ(f.composited[i].id, s.hits.hits[i].id);
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(f.out[ch], s.result.diffuse[ch], 1e-5) << "segment " << k;
    EXPECT_GT(f.minKeyGap, 1e-3) << "segment " << k;
    EXPECT_GT(f.finalT, 1.2 * c.trace.minTransmittance) << "segment " << k;
    for (uint32_t id : hits[k]) {
      // Disjoint hit sets: each varied Gaussian's gradient comes from one segment.
      for (size_t other = 0; other < 3; ++other) ASSERT_TRUE(other == k || !hits[other].count(id)) << id;
      varied.push_back(id);
      segmentOf.push_back(int(k));
    }
  }
  // A step of 1e-6 moves r^2 / R^2 of the thinnest Gaussians (scale 0.01) by about 1e-4.
  for (uint32_t id : varied)
    for (size_t k = 1; k < 3; ++k) EXPECT_GT(forwards[k].margin[id], 1e-3) << "Gaussian " << id << ", segment " << k;

  LossSetup loss(c.path.specular);
  std::vector<double> analytic = reflectionGradient<double>(c, loss.g);
  // L_r with the rays and throughputs held as recorded, as a function of the varied
  // Gaussians' parameters.
  std::vector<double> theta;
  for (uint32_t id : varied) theta.insert(theta.end(), c.x.begin() + id * kParams, c.x.begin() + (id + 1) * kParams);
  auto lossOf = [&](const std::vector<double>& t) {
    std::vector<double> x = c.x;
    for (size_t v = 0; v < varied.size(); ++v)
      std::copy(t.begin() + v * kParams, t.begin() + (v + 1) * kParams, x.begin() + varied[v] * kParams);
    Vec3d specular(0.0);
    for (size_t k = 1; k < 3; ++k) {
      test::Outputs out = test::traceDouble(x, c.segments[k].ray, c.trace).out;
      specular += Vec3d(c.segments[k].throughput) * Vec3d(out[0], out[1], out[2]);
    }
    return loss.loss(specular);
  };
  ASSERT_NEAR(lossOf(theta), loss.loss(Vec3d(c.path.specular)), 1e-5);
  std::vector<double> numeric = test::centralGradient(lossOf, theta);
  // Segment k's gradient is scaled by (1 - rho_{k-1})^3, rho the blended roughness of the
  // surface it leaves: here about 0.2 for the mirror and 0.35 for the layer.
  std::vector<double> expected(numeric.size()), reported(numeric.size());
  for (size_t v = 0; v < varied.size(); ++v) {
    double rho = std::clamp(double(c.segments[segmentOf[v] - 1].result.roughness), 0.0, 1.0);
    double weight = std::pow(1 - rho, 3);
    for (int p = 0; p < kParams; ++p) {
      expected[v * kParams + p] = weight * numeric[v * kParams + p];
      reported[v * kParams + p] = analytic[varied[v] * kParams + p];
    }
  }
  test::expectGradientNear(reported, expected, 2e-5, "reflected segments' Gaussians");
  // The check has teeth: every varied Gaussian's diffuse and opacity move the loss.
  for (size_t v = 0; v < varied.size(); ++v) {
    EXPECT_GT(std::abs(numeric[v * kParams + test::kDiffuseParam]), 1e-6) << varied[v];
    EXPECT_GT(std::abs(numeric[v * kParams + test::kOpacityParam]), 1e-6) << varied[v];
  }
}

// Nothing flows into normals, roughness or F0, nor into the Gaussians only the first
// segment hits; exactly the reflected segments' hits receive gradients.
TEST(TracePathVjp, GradientsReachOnlyTheReflectedSegmentsBlendedDiffuse) {
  PathCase c = makePathCase();
  ASSERT_EQ(c.segments.size(), 3u);
  LossSetup loss(c.path.specular);
  std::set<uint32_t> reached;
  std::vector<double> gradient = reflectionGradient<double>(c, loss.g, &reached);
  std::set<uint32_t> reflectedHits = hitIds(c.segments[1]);
  for (uint32_t id : hitIds(c.segments[2])) reflectedHits.insert(id);
  EXPECT_EQ(reached, reflectedHits);
  EXPECT_FALSE(hitIds(c.segments[0]).empty());
  size_t nonzero = 0;
  for (size_t i = 0; i < c.scene.size(); ++i)
    for (int p = 0; p < kParams; ++p) {
      double v = gradient[i * kParams + p];
      if (p >= test::kNormalParam || !reflectedHits.count(uint32_t(i)))
        EXPECT_EQ(v, 0.0) << "Gaussian " << i << ", parameter " << p;
      else
        nonzero += v != 0.0;
    }
  EXPECT_EQ(nonzero, reflectedHits.size() * test::kNormalParam);
}

TEST(TracePathVjp, SpecularAndWeightsFollowTheRecordedSegments) {
  PathCase c = makePathCase();
  ASSERT_EQ(c.segments.size(), 3u);
  Rgb specular = pathSpecular(c.segments);
  for (int ch = 0; ch < 3; ++ch) EXPECT_FLOAT_EQ(specular[ch], c.path.specular[ch]);
  EXPECT_GT(c.path.specular.x, 0.05f);
  for (size_t k = 1; k < 3; ++k) {
    double rho = c.segments[k - 1].result.roughness;
    EXPECT_NEAR(reflectionGradientWeight(c.segments, k), std::pow(1 - rho, 3), 1e-6) << k;
  }
  // Each surface's Gaussians share one roughness, which blends to rho (1 - T): the weights
  // above are about 0.51 for the mirror and 0.32 for the layer.
  EXPECT_NEAR(c.segments[0].result.roughness, kMirrorRoughness * (1 - c.segments[0].result.transmittance), 1e-5);
  EXPECT_NEAR(c.segments[1].result.roughness, kLayerRoughness * (1 - c.segments[1].result.transmittance), 1e-5);
  EXPECT_GT(reflectionGradientWeight(c.segments, 1) - reflectionGradientWeight(c.segments, 2), 0.1f);
  // Roughness is clamped to [0, 1] before weighting.
  std::vector<PathSegment> fabricated(2);
  fabricated[0].result.roughness = 1.4f;
  EXPECT_EQ(reflectionGradientWeight(fabricated, 1), 0.0f);
  fabricated[0].result.roughness = -0.3f;
  EXPECT_EQ(reflectionGradientWeight(fabricated, 1), 1.0f);
}

// Training runs the float pass on the tracer's records: it agrees with the double one.
TEST(TracePathVjp, FloatAgreesWithDouble) {
  PathCase c = makePathCase();
  ASSERT_EQ(c.segments.size(), 3u);
  LossSetup loss(c.path.specular);
  std::vector<double> reference = reflectionGradient<double>(c, loss.g);
  std::vector<double> single = reflectionGradient<float>(c, loss.g);
  test::expectGradientNear(single, reference, 1e-4, "float reflection gradient");
}

// D15: with L_r's gradient into roughness and F0 on, each step's weight w_j is a function
// of the blended roughness and F0 of the surface it leaves, at its recorded directions and
// density: w_j(theta) = w_j(theta_0) f_theta / f_theta_0, f = D G2 F. The whole gradient
// (diffuse unweighted, so every term is the true derivative) matches central differences
// of g . s with the rays held as recorded and the throughputs rescaled so.
double lobeValue(const Vec3d& wo, const Vec3d& wi, double roughness, double minRoughness, double f0) {
  double rho = std::max(std::clamp(roughness, 0.0, 1.0), minRoughness);
  double alpha = std::max(rho * rho, double(kMinGgxAlpha));
  double F = f0 + (1 - f0) * std::pow(1 - dot(wo, normalize(wo + wi)), 5);
  return test::ggxLobeReference(wo, wi, alpha) * F;
}

TEST(TracePathVjp, MaterialGradientsMatchFiniteDifferencesOfTheDetachedWeights) {
  PathCase c = makePathCase();
  ASSERT_EQ(c.segments.size(), 3u);
  PathGradientSettings settings;
  settings.weightReflections = false;
  settings.roughnessFromSpecular = 1;
  settings.f0FromSpecular = 1;
  settings.materialsMoveGeometry = true;  // the whole derivative
  settings.path = c.settings;
  // The local directions of steps 1 and 2, in the frame continuePath used.
  std::vector<Vec3d> wo(3), wi(3);
  for (size_t j = 1; j < 3; ++j) {
    const PathSegment& from = c.segments[j - 1];
    Vec3f n;
    ASSERT_TRUE(reflectionNormal(from.ray, from.result, c.settings, &n));
    Framef frame = Framef::fromNormal(n);
    wo[j] = Vec3d(frame.toLocal(-from.ray.direction));
    wi[j] = Vec3d(frame.toLocal(c.segments[j].ray.direction));
  }
  std::vector<uint32_t> varied;
  std::vector<std::set<uint32_t>> hits;
  std::vector<test::Forward> base;
  for (const PathSegment& s : c.segments) {
    hits.push_back(hitIds(s));
    base.push_back(test::traceDouble(c.x, s.ray, c.trace));
  }
  for (size_t k = 0; k < 3; ++k)
    for (uint32_t id : hits[k]) {
      for (size_t other = 0; other < 3; ++other) ASSERT_TRUE(other == k || !hits[other].count(id)) << id;
      for (size_t j = 0; j < 3; ++j) ASSERT_GT(base[j].margin[id], 1e-3) << "Gaussian " << id << ", segment " << j;
      varied.push_back(id);
    }
  // A truncated segment (the mirror is nearly opaque) holds its tail's colour ratio and
  // T_f / tau_n as recorded, as backwardRay does (D12).
  std::vector<std::optional<test::DetachedTail>> tails(3);
  for (size_t k = 0; k < 3; ++k) {
    if (!base[k].truncated) continue;
    test::DetachedTail& tail = tails[k].emplace();
    for (const test::Hit& h : base[k].composited) tail.order.push_back(h.id);
    test::Outputs front = test::traceDouble(c.x, c.segments[k].ray, c.trace, &tail).out;
    double ratio = base[k].finalT / base[k].tauN;
    for (int i = 0; i < 11; ++i) tail.background[i] = (1 - ratio) * front[i] / (1 - base[k].tauN);
  }
  constexpr int kRoughness = 7, kF0 = 8;  // in test::Outputs
  LossSetup loss(c.path.specular);
  auto lossOf = [&](const std::vector<double>& t) {
    std::vector<double> x = c.x;
    for (size_t v = 0; v < varied.size(); ++v)
      std::copy(t.begin() + v * kParams, t.begin() + (v + 1) * kParams, x.begin() + varied[v] * kParams);
    std::vector<test::Outputs> out;
    for (size_t k = 0; k < 3; ++k)
      out.push_back(test::traceDouble(x, c.segments[k].ray, c.trace, tails[k] ? &*tails[k] : nullptr).out);
    Vec3d specular(0.0), scale(1.0);
    for (size_t k = 1; k < 3; ++k) {
      for (int ch = 0; ch < 3; ++ch) {
        double minRoughness = c.settings.minRoughness;
        scale[ch] *= lobeValue(wo[k], wi[k], out[k - 1][kRoughness], minRoughness, out[k - 1][kF0 + ch]) /
                     lobeValue(wo[k], wi[k], base[k - 1].out[kRoughness], minRoughness, base[k - 1].out[kF0 + ch]);
      }
      for (int ch = 0; ch < 3; ++ch) specular[ch] += c.segments[k].throughput[ch] * scale[ch] * out[k][ch];
    }
    return loss.loss(specular);
  };
  std::vector<double> theta;
  for (uint32_t id : varied) theta.insert(theta.end(), c.x.begin() + id * kParams, c.x.begin() + (id + 1) * kParams);
  ASSERT_NEAR(lossOf(theta), loss.loss(Vec3d(c.path.specular)), 1e-5);
  std::vector<double> numeric = test::centralGradient(lossOf, theta);
  std::vector<double> gradient(c.x.size(), 0.0);
  RayBackwardScratch<double> scratch;
  tracePath_vjp<double>(c.scene, c.trace, c.segments, RayResultAdjoint{}, loss.g, settings, scratch,
                        [&](uint32_t id, const HitGradient<double>& hg) { test::accumulate(&gradient, id, hg); });
  std::vector<double> reported;
  for (uint32_t id : varied)
    reported.insert(reported.end(), gradient.begin() + id * kParams, gradient.begin() + (id + 1) * kParams);
  test::expectGradientNear(reported, numeric, 1e-4, "material gradients of the path");
  // The check has teeth: the mirror's and the layer's roughness and F0 move the loss, and
  // the mirror's Gaussians (hit by the first segment alone) get nothing without the option.
  double roughness[2] = {0, 0}, f0[2] = {0, 0};
  for (size_t v = 0; v < varied.size(); ++v)
    for (size_t k = 0; k < 2; ++k)
      if (hits[k].count(varied[v])) {
        roughness[k] += std::abs(numeric[v * kParams + test::kNormalParam + 3]);
        f0[k] += std::abs(numeric[v * kParams + test::kNormalParam + 4]);
      }
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_GT(roughness[k], 1e-4) << "segment " << k;
    EXPECT_GT(f0[k], 1e-4) << "segment " << k;
  }
  std::set<uint32_t> reached;
  reflectionGradient<double>(c, loss.g, &reached);
  for (uint32_t id : hits[0]) EXPECT_FALSE(reached.count(id)) << id;
}

// By default L_r's material gradients hold the compositing weights: each Gaussian's own
// roughness and F0 get what the whole derivative gives them, and its opacity, position,
// shape, diffuse and normal get exactly what they get with the material gradients off.
TEST(TracePathVjp, MaterialGradientsWithHeldWeightsReachOnlyRoughnessAndF0) {
  PathCase c = makePathCase();
  ASSERT_EQ(c.segments.size(), 3u);
  LossSetup loss(c.path.specular);
  PathGradientSettings off;
  off.path = c.settings;
  PathGradientSettings held = off;
  held.roughnessFromSpecular = 1;
  held.f0FromSpecular = 1;
  PathGradientSettings whole = held;
  whole.materialsMoveGeometry = true;
  auto gradientOf = [&](const PathGradientSettings& settings) {
    std::vector<double> gradient(c.x.size(), 0.0);
    RayBackwardScratch<double> scratch;
    tracePath_vjp<double>(c.scene, c.trace, c.segments, RayResultAdjoint{}, loss.g, settings, scratch,
                          [&](uint32_t id, const HitGradient<double>& hg) { test::accumulate(&gradient, id, hg); });
    return gradient;
  };
  const std::vector<double> gOff = gradientOf(off), gHeld = gradientOf(held), gWhole = gradientOf(whole);
  constexpr int kRoughnessParam = test::kNormalParam + 3, kF0Param = test::kNormalParam + 4;
  double geometryMoved = 0, materials = 0;
  for (size_t i = 0; i < c.scene.size(); ++i)
    for (int p = 0; p < kParams; ++p) {
      const size_t at = i * kParams + p;
      const bool material = p >= kRoughnessParam && p < kF0Param + 3;
      if (material) {
        EXPECT_NEAR(gHeld[at], gWhole[at], 1e-12) << "Gaussian " << i << ", parameter " << p;
        materials += std::abs(gHeld[at]);
      } else {
        EXPECT_NEAR(gHeld[at], gOff[at], 1e-12) << "Gaussian " << i << ", parameter " << p;
        geometryMoved += std::abs(gWhole[at] - gOff[at]);
      }
    }
  // The check has teeth: the materials get a gradient, and the whole derivative does move
  // the geometry.
  EXPECT_GT(materials, 1e-4);
  EXPECT_GT(geometryMoved, 1e-4);
}

// A segment whose hit list overflowed gives no gradient and is counted.
TEST(TracePathVjp, OverflowedSegmentsAreSkippedAndCounted) {
  PathCase full = makePathCase();
  ASSERT_EQ(full.segments.size(), 3u);
  size_t fewest = std::min(full.segments[1].hits.hits.size(), full.segments[2].hits.hits.size());
  size_t most = std::max(full.segments[1].hits.hits.size(), full.segments[2].hits.hits.size());
  ASSERT_LT(fewest, most) << "the scene should give the reflected segments different hit counts";
  PathCase c = makePathCase(fewest);
  ASSERT_EQ(c.segments.size(), 3u);
  LossSetup loss(c.path.specular);
  std::set<uint32_t> reached;
  int overflowed = -1;
  reflectionGradient<double>(c, loss.g, &reached, &overflowed);
  EXPECT_EQ(overflowed, 1);
  size_t kept = c.segments[1].hits.overflowed ? 2 : 1;
  EXPECT_FALSE(c.segments[kept].hits.overflowed);
  EXPECT_EQ(reached, hitIds(c.segments[kept]));
}

// With f0FromSpecularMetalsOnly, L_r's F0 gradient reaches the surface a step leaves only
// where its blended F0 is a metal's (greyF0IsMetal); the roughness gradient is unchanged.
TEST(TracePathVjp, F0FromSpecularMetalsOnlyLeavesDielectricsToTheirPrior) {
  PathCase c = makePathCase();
  ASSERT_EQ(c.segments.size(), 3u);
  PathGradientSettings all;
  all.roughnessFromSpecular = 1;
  all.f0FromSpecular = 1;
  all.path = c.settings;
  PathGradientSettings metals = all;
  metals.f0FromSpecularMetalsOnly = true;
  const Rgb g(0.3f, -0.2f, 0.5f);
  std::vector<PathSegment> segments = c.segments;
  for (const Rgb& f0 : {Rgb(0.04f), Rgb(0.9f, 0.6f, 0.5f)}) {
    segments[0].result.f0 = f0;  // the surface the first reflection leaves
    const RayResultAdjoint a = segmentAdjoint(segments, 0, RayResultAdjoint{}, g, all);
    const RayResultAdjoint m = segmentAdjoint(segments, 0, RayResultAdjoint{}, g, metals);
    ASSERT_FALSE(a.v_f0WeightsHeld == Rgb(0.0f));
    EXPECT_EQ(m.v_f0WeightsHeld, greyF0IsMetal(f0) ? a.v_f0WeightsHeld : Rgb(0.0f));
    EXPECT_EQ(m.v_roughnessWeightsHeld, a.v_roughnessWeightsHeld);
  }
}

// The first segment's adjoint flows through its own hits exactly as backwardRay hands it
// out, added to the reflected segments' gradient.
TEST(TracePathVjp, FirstSegmentAdjointAddsTheFirstSegmentsBackwardRay) {
  PathCase c = makePathCase();
  ASSERT_EQ(c.segments.size(), 3u);
  LossSetup loss(c.path.specular);
  RayResultAdjoint vFirst;
  vFirst.v_diffuse = Rgb(0.3f, -0.2f, 0.1f);
  vFirst.v_depth = 0.05f;
  vFirst.v_normal = Vec3f(0.1f, 0.2f, -0.3f);
  vFirst.v_roughness = -0.4f;
  vFirst.v_f0 = Rgb(0.2f, 0.1f, -0.1f);
  std::vector<double> both = reflectionGradient<double>(c, loss.g, nullptr, nullptr, vFirst);
  std::vector<double> expected = reflectionGradient<double>(c, loss.g);
  RayBackwardScratch<double> scratch;
  backwardRay<double>(c.scene, c.trace, c.segments[0].ray, c.segments[0].hits, c.segments[0].result, vFirst, scratch,
                      [&](uint32_t id, const HitGradient<double>& hg) { test::accumulate(&expected, id, hg); });
  test::expectGradientNear(both, expected, 1e-12, "path gradient with a first-segment adjoint");
  // The first segment's Gaussians receive gradients in every attribute, normals included.
  double normalGradient = 0;
  for (uint32_t id : hitIds(c.segments[0])) normalGradient += std::abs(both[id * kParams + test::kNormalParam]);
  EXPECT_GT(normalGradient, 0.0);
}

// The wavefront records the same segments, hits and results as the path traced alone.
TEST(TracePathVjp, WavefrontRecordsWhatTracePathRecords) {
  PathCase c = makePathCase();
  ASSERT_EQ(c.segments.size(), 3u);
  PathBatch batch;
  std::vector<TraceRay> primaries{c.primary, c.primary};
  std::vector<PathKey> keys{{kView, kPixel, kSample}, {kView, kPixel + 1, kSample}};
  std::vector<PathResult> results(2);
  batch.trace(*c.tracer, primaries, keys, kSeed, c.settings, results, /*record=*/true);
  std::span<const PathSegment> path = batch.path(0);
  ASSERT_EQ(path.size(), c.segments.size());
  EXPECT_EQ(results[0].segments, c.path.segments);
  for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(results[0].specular[ch], c.path.specular[ch]);
  for (size_t k = 0; k < path.size(); ++k) {
    EXPECT_EQ(path[k].ray.origin, c.segments[k].ray.origin) << k;
    EXPECT_EQ(path[k].ray.direction, c.segments[k].ray.direction) << k;
    ASSERT_EQ(path[k].hits.hits.size(), c.segments[k].hits.hits.size()) << k;
    for (size_t h = 0; h < path[k].hits.hits.size(); ++h) {
      EXPECT_EQ(path[k].hits.hits[h].id, c.segments[k].hits.hits[h].id);
      EXPECT_EQ(path[k].hits.hits[h].t, c.segments[k].hits.hits[h].t);
      EXPECT_EQ(path[k].hits.hits[h].alpha, c.segments[k].hits.hits[h].alpha);
    }
    for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(path[k].throughput[ch], c.segments[k].throughput[ch]) << k;
  }
}

}  // namespace
}  // namespace glint
