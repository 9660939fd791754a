// Finite-difference tests of the ray-Gaussian kernel's VJPs: each step on its own, then
// the whole kernel against evaluateGaussian itself (random Gaussians and rays, p = 1, 2, 3,
// rays at several Mahalanobis distances, non-normalised quaternions, the tMin clamp).
#include "raytrace/gaussian_kernel_vjp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/finite_difference.h"
#include "math/rng.h"

namespace glint {
namespace {

using test::symmetric;
Vec3d randomVec(Rng& rng) { return {symmetric(rng), symmetric(rng), symmetric(rng)}; }
Vec3d randomUnit(Rng& rng) {
  for (;;) {
    Vec3d v = randomVec(rng);
    double n = length(v);
    if (n > 0.1 && n <= 1) return v / n;
  }
}

// A Gaussian with a non-normalised quaternion (norm 0.5-2), scales 0.2-1.6 and opacity
// 0.2-0.95.
KernelParams<double> randomGaussian(Rng& rng) {
  KernelParams<double> g;
  g.mean = randomVec(rng) * 3.0;
  double qScale = 0.5 + 1.5 * rng.uniformDouble();
  Vec3d axis = randomUnit(rng);
  double w = symmetric(rng);
  double n = std::sqrt(w * w + 1);
  g.rotation = Quatd{w / n * qScale, axis.x / n * qScale, axis.y / n * qScale, axis.z / n * qScale};
  for (int k = 0; k < 3; ++k) g.logScale[k] = std::log(0.2 + 1.4 * rng.uniformDouble());
  g.opacityLogit = std::log(0.25) + (std::log(19.0) - std::log(0.25)) * rng.uniformDouble();
  return g;
}

// Parameters as one vector: mean (3), rotation (w, x, y, z), log-scales (3), opacity logit.
std::vector<double> flatten(const KernelParams<double>& g) {
  return {g.mean.x, g.mean.y, g.mean.z, g.rotation.w, g.rotation.x, g.rotation.y,
          g.rotation.z, g.logScale.x, g.logScale.y, g.logScale.z, g.opacityLogit};
}
KernelParams<double> unflatten(const std::vector<double>& x) {
  return {{x[0], x[1], x[2]}, Quatd{x[3], x[4], x[5], x[6]}, {x[7], x[8], x[9]}, x[10]};
}
std::vector<double> flatten(const KernelGrad<double>& v) {
  return {v.v_mean.x, v.v_mean.y, v.v_mean.z, v.v_rotation.w, v.v_rotation.x, v.v_rotation.y,
          v.v_rotation.z, v.v_logScale.x, v.v_logScale.y, v.v_logScale.z, v.v_opacityLogit};
}

// Settings whose proxy is wide enough that every test ray (Mahalanobis distance <= 1.6)
// is accepted at every finite-difference step.
TraceSettings settingsFor(double power) {
  TraceSettings s;
  s.kernelPower = float(power);
  s.alphaMin = 1e-6f;
  return s;
}

// A unit ray passing the Gaussian at about `distance` scale units, starting 2-8 units
// before that point.
void rayPassing(const KernelParams<double>& g, double distance, Rng& rng, Vec3d* o, Vec3d* d) {
  Mat3d R = quatToRotation(g.rotation);
  Vec3d u = randomUnit(rng) * distance;
  Vec3d offset = R * Vec3d(u.x * std::exp(g.logScale.x), u.y * std::exp(g.logScale.y), u.z * std::exp(g.logScale.z));
  *d = randomUnit(rng);
  *o = g.mean + offset - *d * (2.0 + 6.0 * rng.uniformDouble());
}

TEST(GaussianKernelVjp, FrameMatchesMakeGaussianFrame) {
  Rng rng(501);
  GaussianScene scene;
  scene.resize(20);
  TraceSettings s = settingsFor(3);
  for (size_t i = 0; i < scene.size(); ++i) {
    KernelParams<double> g = randomGaussian(rng);
    scene.position[i] = Vec3f(g.mean);
    scene.rotation[i] = Quatf{float(g.rotation.w), float(g.rotation.x), float(g.rotation.y), float(g.rotation.z)};
    scene.logScale[i] = Vec3f(g.logScale);
    scene.opacityLogit[i] = float(g.opacityLogit);
    GaussianFrame<double> expected = makeGaussianFrame<double>(scene, i, s);
    GaussianFrame<double> actual = gaussianFrame(kernelParams<double>(scene, i), s);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(actual.worldToLocal.m[r][c], expected.worldToLocal.m[r][c], 1e-14);
    EXPECT_EQ(actual.mean, expected.mean);
    EXPECT_NEAR(actual.opacity, expected.opacity, 1e-15);
    EXPECT_NEAR(actual.proxyRadius, expected.proxyRadius, 1e-13);
  }
}

TEST(GaussianKernelVjp, OpacityMatchesFiniteDifferences) {
  for (double logit : {-4.0, -0.5, 0.0, 1.3, 5.0}) {
    auto loss = [](const std::vector<double>& x) { return 0.7 * opacityFromLogit(x[0]); };
    double analytic = opacityFromLogit_vjp(opacityFromLogit(logit), 0.7);
    test::expectGradientNear({analytic}, test::centralGradient(loss, {logit}), 1e-6, "sigmoid");
  }
}

TEST(GaussianKernelVjp, WorldToLocalMatchesFiniteDifferences) {
  Rng rng(502);
  for (int trial = 0; trial < 30; ++trial) {
    KernelParams<double> g = randomGaussian(rng);
    Mat3d v_W;
    for (int r = 0; r < 3; ++r) v_W.m[r] = randomVec(rng);
    auto loss = [&](const std::vector<double>& x) {
      Mat3d W = worldToLocal(Quatd{x[0], x[1], x[2], x[3]}, Vec3d(x[4], x[5], x[6]));
      return dot(v_W.m[0], W.m[0]) + dot(v_W.m[1], W.m[1]) + dot(v_W.m[2], W.m[2]);
    };
    Quatd v_q;
    Vec3d v_s;
    worldToLocal_vjp(g.rotation, g.logScale, v_W, &v_q, &v_s);
    std::vector<double> x = {g.rotation.w, g.rotation.x, g.rotation.y, g.rotation.z,
                             g.logScale.x, g.logScale.y, g.logScale.z};
    test::expectGradientNear({v_q.w, v_q.x, v_q.y, v_q.z, v_s.x, v_s.y, v_s.z}, test::centralGradient(loss, x),
                             1e-6, "worldToLocal");
  }
}

TEST(GaussianKernelVjp, LocalRayMatchesFiniteDifferences) {
  Rng rng(503);
  for (int trial = 0; trial < 30; ++trial) {
    // Parameters: W row by row (9), then the mean (3); o, d and t0 are constants.
    std::vector<double> x(12);
    for (double& v : x) v = 2 * symmetric(rng);
    Vec3d o = randomVec(rng) * 5.0, d = randomUnit(rng);
    double t0 = 3 * symmetric(rng);
    LocalRay<double> v_local{randomVec(rng), randomVec(rng)};
    auto unpack = [](const std::vector<double>& p, Mat3d* W, Vec3d* mean) {
      for (int r = 0; r < 3; ++r) W->m[r] = {p[3 * r], p[3 * r + 1], p[3 * r + 2]};
      *mean = {p[9], p[10], p[11]};
    };
    auto loss = [&](const std::vector<double>& p) {
      Mat3d W;
      Vec3d mean;
      unpack(p, &W, &mean);
      LocalRay<double> local = localRay(W, mean, o, d, t0);
      return dot(v_local.origin, local.origin) + dot(v_local.direction, local.direction);
    };
    Mat3d W;
    Vec3d mean;
    unpack(x, &W, &mean);
    Mat3d v_W = zeroMat3<double>();
    Vec3d v_mean = localRay_vjp(W, mean, o, d, t0, v_local, &v_W);
    std::vector<double> analytic;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) analytic.push_back(v_W.m[r][c]);
    for (int k = 0; k < 3; ++k) analytic.push_back(v_mean[k]);
    test::expectGradientNear(analytic, test::centralGradient(loss, x), 1e-6, "localRay");
  }
}

TEST(GaussianKernelVjp, ClosestApproachMatchesFiniteDifferences) {
  Rng rng(504);
  for (int trial = 0; trial < 30; ++trial) {
    std::vector<double> x(6);  // oL, then dL
    for (double& v : x) v = 2 * symmetric(rng);
    double v_tc = symmetric(rng), v_r2 = symmetric(rng);
    auto rayOf = [](const std::vector<double>& p) {
      return LocalRay<double>{{p[0], p[1], p[2]}, {p[3], p[4], p[5]}};
    };
    auto loss = [&](const std::vector<double>& p) {
      ClosestApproach<double> c = closestApproach(rayOf(p));
      return v_tc * c.tc + v_r2 * c.r2;
    };
    LocalRay<double> ray = rayOf(x);
    LocalRay<double> v = closestApproach_vjp(ray, closestApproach(ray), v_tc, v_r2);
    test::expectGradientNear({v.origin.x, v.origin.y, v.origin.z, v.direction.x, v.direction.y, v.direction.z},
                             test::centralGradient(loss, x), 1e-6, "closestApproach");
  }
}

TEST(GaussianKernelVjp, ResponseMatchesFiniteDifferences) {
  for (double power : {1.0, 2.0, 3.0})
    for (double r2 : {0.01, 0.3, 1.0, 2.5}) {
      auto loss = [&](const std::vector<double>& x) { return -1.3 * gaussianResponse(x[0], power); };
      test::expectGradientNear({gaussianResponse_vjp(r2, power, -1.3)}, test::centralGradient(loss, {r2}), 1e-6,
                               "response p=" + std::to_string(power));
    }
  // At the centre the derivative is -1/2 for p = 1 and 0 for p > 1.
  EXPECT_DOUBLE_EQ(gaussianResponse_vjp(0.0, 1.0, 1.0), -0.5);
  EXPECT_EQ(gaussianResponse_vjp(0.0, 3.0, 1.0), 0.0);
}

TEST(GaussianKernelVjp, AlphaMatchesFiniteDifferences) {
  auto loss = [](const std::vector<double>& x) { return 0.4 * hitAlpha(x[0], x[1]); };
  double v_opacity, v_response;
  hitAlpha_vjp(0.6, 0.3, 0.4, &v_opacity, &v_response);
  test::expectGradientNear({v_opacity, v_response}, test::centralGradient(loss, {0.6, 0.3}), 1e-6, "alpha");
}

// L = v_alpha alpha + v_key key of one hit of the real evaluateGaussian (which recomputes
// t0 from the perturbed mean, so the t0 reparametrisation is checked too).
double hitLoss(const std::vector<double>& x, const Vec3d& o, const Vec3d& d, double tMin, const TraceSettings& s,
               double v_alpha, double v_key, KernelHit<double>* hitOut = nullptr) {
  KernelHit<double> hit;
  if (!evaluateGaussian(gaussianFrame(unflatten(x), s), o, d, tMin, s, &hit)) {
    ADD_FAILURE() << "the test ray missed the Gaussian";
    return std::nan("");
  }
  if (hitOut) *hitOut = hit;
  return v_alpha * hit.alpha + v_key * hit.key;
}

void expectKernelGradient(const KernelParams<double>& g, const Vec3d& o, const Vec3d& d, double tMin,
                          const TraceSettings& s, double v_alpha, double v_key, const std::string& what) {
  KernelGrad<double> grad = evaluateGaussian_vjp(g, o, d, tMin, s, v_alpha, v_key);
  auto loss = [&](const std::vector<double>& x) { return hitLoss(x, o, d, tMin, s, v_alpha, v_key); };
  test::expectGradientNear(flatten(grad), test::centralGradient(loss, flatten(g)), 1e-6, what);
}

TEST(GaussianKernelVjp, KernelMatchesFiniteDifferences) {
  Rng rng(505);
  for (double power : {1.0, 2.0, 3.0}) {
    TraceSettings s = settingsFor(power);
    for (double distance : {0.05, 0.3, 0.7, 1.1, 1.6})
      for (int trial = 0; trial < 8; ++trial) {
        KernelParams<double> g = randomGaussian(rng);
        Vec3d o, d;
        rayPassing(g, distance, rng, &o, &d);
        double v_alpha = symmetric(rng), v_key = symmetric(rng);
        std::string what = "p=" + std::to_string(power) + " distance=" + std::to_string(distance);
        expectKernelGradient(g, o, d, 0.0, s, v_alpha, v_key, what);
        // Each upstream adjoint alone, so one cannot hide an error in the other.
        expectKernelGradient(g, o, d, 0.0, s, 1.0, 0.0, what + " alpha only");
        expectKernelGradient(g, o, d, 0.0, s, 0.0, 1.0, what + " key only");
      }
  }
}

// A ray that starts inside the Gaussian: with tMin before the peak the key is tPeak and
// its gradient passes; with tMin past the peak the key is tMin, a constant (D9).
TEST(GaussianKernelVjp, KeyClampedToTMinHasNoGradient) {
  Rng rng(506);
  for (double power : {1.0, 3.0})
    for (int trial = 0; trial < 10; ++trial) {
      TraceSettings s = settingsFor(power);
      KernelParams<double> g = randomGaussian(rng);
      Vec3d o, d;
      rayPassing(g, 0.5, rng, &o, &d);
      KernelHit<double> hit;
      hitLoss(flatten(g), o, d, 0.0, s, 0.0, 1.0, &hit);
      double beforePeak = 0.5 * (hit.tEnter + hit.tPeak);
      double afterPeak = 0.5 * (hit.tPeak + hit.tExit);
      expectKernelGradient(g, o, d, beforePeak, s, 0.3, 1.0, "tMin before the peak");
      KernelHit<double> clamped;
      hitLoss(flatten(g), o, d, afterPeak, s, 0.0, 1.0, &clamped);
      EXPECT_EQ(clamped.key, afterPeak);
      EXPECT_EQ(hitKey(clamped.tPeak, clamped.tEnter, clamped.tExit, afterPeak), clamped.key);
      EXPECT_EQ(hitKey(hit.tPeak, hit.tEnter, hit.tExit, beforePeak), hit.tPeak);
      // Past the peak the key is exactly tMin at every step, so its difference quotient is
      // exactly 0 (checked on its own: added to alpha's, the large constant would only
      // bring rounding noise), and the alpha gradient is unchanged by v_key.
      auto keyLoss = [&](const std::vector<double>& x) { return hitLoss(x, o, d, afterPeak, s, 0.0, 1.0); };
      for (double v : test::centralGradient(keyLoss, flatten(g))) EXPECT_EQ(v, 0.0);
      for (double v : flatten(evaluateGaussian_vjp(g, o, d, afterPeak, s, 0.0, 1.0))) EXPECT_EQ(v, 0.0);
      expectKernelGradient(g, o, d, afterPeak, s, 1.0, 0.0, "tMin after the peak, alpha");
      EXPECT_EQ(flatten(evaluateGaussian_vjp(g, o, d, afterPeak, s, 0.3, 1.0)),
                flatten(evaluateGaussian_vjp(g, o, d, afterPeak, s, 0.3, 0.0)));
    }
}

// The float instantiation (the one the trainer runs) agrees with double to float precision.
TEST(GaussianKernelVjp, FloatAgreesWithDouble) {
  Rng rng(507);
  TraceSettings s = settingsFor(3);
  for (int trial = 0; trial < 20; ++trial) {
    KernelParams<double> g = randomGaussian(rng);
    Vec3d o, d;
    rayPassing(g, 0.6, rng, &o, &d);
    KernelParams<float> gf{Vec3f(g.mean),
                           Quatf{float(g.rotation.w), float(g.rotation.x), float(g.rotation.y), float(g.rotation.z)},
                           Vec3f(g.logScale), float(g.opacityLogit)};
    // The double reference sees exactly the float inputs.
    KernelParams<double> gd{Vec3d(gf.mean), Quatd{gf.rotation.w, gf.rotation.x, gf.rotation.y, gf.rotation.z},
                            Vec3d(gf.logScale), gf.opacityLogit};
    Vec3f of(o), df(normalize(d));
    std::vector<double> expected = flatten(evaluateGaussian_vjp(gd, Vec3d(of), Vec3d(df), 0.0, s, 0.8, -0.5));
    KernelGrad<float> vf = evaluateGaussian_vjp(gf, of, df, 0.0f, s, 0.8f, -0.5f);
    std::vector<double> actual = {vf.v_mean.x, vf.v_mean.y, vf.v_mean.z, vf.v_rotation.w,
                                  vf.v_rotation.x, vf.v_rotation.y, vf.v_rotation.z, vf.v_logScale.x,
                                  vf.v_logScale.y, vf.v_logScale.z, vf.v_opacityLogit};
    double largest = 0;
    for (double v : expected) largest = std::max(largest, std::abs(v));
    for (size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(actual[k], expected[k], 1e-4 * largest) << k;
  }
}

}  // namespace
}  // namespace glint
