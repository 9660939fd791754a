// The Embree k=16 baseline against a brute-force double-precision oracle written here
// (every Gaussian, full sort by (key, id)): random scenes, both kernel powers, both
// thresholds, exact tail on and off, rays from outside and inside the cloud, many k-buffer
// rounds, refit versus a fresh build, and the degenerate scenes.
#include "tracers/embree_tracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "math/rng.h"
#include "math/sampling.h"
#include "raytrace/compositor.h"
#include "raytrace/gaussian_kernel.h"

namespace glint {
namespace {

struct SceneShape {
  float boxHalf = 2.0f;               // means uniform in [-boxHalf, boxHalf]^3
  float minScale = 0.04f, maxScale = 0.3f;   // log-uniform per axis
  float minLogit = -3.0f, maxLogit = 5.0f;   // opacity logits
  float noProxyFraction = 0.03f;      // Gaussians too faint to ever reach alphaMin
};

Quatf randomOrientation(Rng& rng) {
  // Uniform rotation (Shoemake, "Uniform random rotations", Graphics Gems III), stored
  // unnormalised to check that every path normalises it.
  float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
  float a = std::sqrt(1 - u1), b = std::sqrt(u1), len = 0.5f + 1.5f * rng.uniform();
  return {len * a * std::sin(2 * kPi * u2), len * a * std::cos(2 * kPi * u2), len * b * std::sin(2 * kPi * u3),
          len * b * std::cos(2 * kPi * u3)};
}

GaussianScene randomScene(size_t n, uint64_t seed, const SceneShape& shape = {}) {
  Rng rng(seed);
  GaussianScene scene;
  scene.resize(n);
  auto inBox = [&] {
    return Vec3f((2 * rng.uniform() - 1) * shape.boxHalf, (2 * rng.uniform() - 1) * shape.boxHalf,
                 (2 * rng.uniform() - 1) * shape.boxHalf);
  };
  float logMin = std::log(shape.minScale), logMax = std::log(shape.maxScale);
  for (size_t i = 0; i < n; ++i) {
    scene.position[i] = inBox();
    scene.rotation[i] = randomOrientation(rng);
    for (int k = 0; k < 3; ++k) scene.logScale[i][k] = logMin + (logMax - logMin) * rng.uniform();
    scene.opacityLogit[i] = shape.minLogit + (shape.maxLogit - shape.minLogit) * rng.uniform();
    if (rng.uniform() < shape.noProxyFraction) scene.opacityLogit[i] = -7.0f;  // opacity 0.0009
    scene.diffuse[i] = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
    scene.normal[i] = sampleUniformSphere(rng.uniform2()) * (0.5f + rng.uniform());
    scene.roughness[i] = rng.uniform();
    scene.f0[i] = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
  }
  return scene;
}

// Rays from a sphere around the cloud towards points inside it, and rays starting inside
// the cloud (often inside Gaussians, with Gaussians behind them), some with tMin > 0.
std::vector<TraceRay> randomRays(uint64_t seed, float boxHalf, int outside, int inside, int insideWithTMin) {
  Rng rng(seed);
  std::vector<TraceRay> rays;
  auto inBox = [&](float half) {
    return Vec3f((2 * rng.uniform() - 1) * half, (2 * rng.uniform() - 1) * half, (2 * rng.uniform() - 1) * half);
  };
  for (int i = 0; i < outside; ++i) {
    Vec3f origin = sampleUniformSphere(rng.uniform2()) * (3.0f * boxHalf);
    rays.push_back({origin, normalize(inBox(0.75f * boxHalf) - origin), 0.0f});
  }
  for (int i = 0; i < inside + insideWithTMin; ++i) {
    Vec3f origin = inBox(0.9f * boxHalf);
    float tMin = i < inside ? 0.0f : 0.5f * rng.uniform() * boxHalf;
    rays.push_back({origin, sampleUniformSphere(rng.uniform2()), tMin});
  }
  return rays;
}

// The oracle: every Gaussian in double precision, fully sorted by (key, id). It also
// flags rays where float and double may legitimately disagree (a hit within rounding of
// alphaMin or of the ray start, two composited keys within rounding of each other, or the
// transmittance within rounding of the threshold); such rays are excused if they differ.
struct OracleRay {
  RayResult result;
  HitList hits;
  bool nearThreshold = false;
};

class Oracle {
 public:
  Oracle(const GaussianScene& scene, const TraceSettings& settings) : scene_(scene), settings_(settings) {
    loose_ = settings;
    loose_.alphaMin = settings.alphaMin * (1 - 1e-3f);
    for (size_t i = 0; i < scene.size(); ++i) {
      frames_.push_back(makeGaussianFrame<double>(scene, i, settings_));
      looseFrames_.push_back(makeGaussianFrame<double>(scene, i, loose_));
    }
  }

  OracleRay trace(const TraceRay& ray) const {
    struct Entry {
      uint32_t id;
      KernelHit<double> hit;
    };
    OracleRay out;
    std::vector<Entry> entries;
    Vec3d o(ray.origin), d = normalize(Vec3d(ray.direction));
    double tMin = ray.tMin;
    for (size_t i = 0; i < frames_.size(); ++i) {
      KernelHit<double> h;
      if (evaluateGaussian(frames_[i], o, d, tMin, settings_, &h)) entries.push_back({uint32_t(i), h});
      if (evaluateGaussian(looseFrames_[i], o, d, tMin - 1e-4, loose_, &h) &&
          (h.alpha < settings_.alphaMin * (1 + 1e-3) || std::abs(h.tExit - tMin) < 1e-4))
        out.nearThreshold = true;
    }
    std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
      return a.hit.key != b.hit.key ? a.hit.key < b.hit.key : a.id < b.id;
    });
    out.hits.capacity = 100000;
    Compositor<double> compositor(scene_, settings_, &out.hits);
    for (size_t i = 0; i < entries.size(); ++i) {
      if (!compositor.terminated()) {
        double key = entries[i].hit.key;
        if (i + 1 < entries.size() && entries[i + 1].hit.key - key < 1e-4 * (1 + std::abs(key)) &&
            (entries[i + 1].hit.key != key || std::abs(entries[i].hit.tPeak - tMin) < 1e-4))
          out.nearThreshold = true;
      }
      if (!compositor.add(entries[i].id, entries[i].hit) && !settings_.exactTail) break;
      double t = compositor.transmittance();
      if (std::abs(t - settings_.minTransmittance) < 1e-3 * settings_.minTransmittance) out.nearThreshold = true;
    }
    out.result = compositor.finish();
    return out;
  }

 private:
  const GaussianScene& scene_;
  TraceSettings settings_, loose_;
  std::vector<GaussianFrame<double>> frames_, looseFrames_;
};

bool near(double a, double b) { return std::abs(a - b) <= 1e-4 * std::max(1.0, std::abs(b)); }
bool near(const Vec3f& a, const Vec3f& b) { return near(a.x, b.x) && near(a.y, b.y) && near(a.z, b.z); }

// Empty when the tracer's ray matches the oracle's, else what differs.
std::string compare(const RayResult& r, const HitList& hits, const OracleRay& want) {
  const RayResult& w = want.result;
  std::string diff;
  auto check = [&](bool ok, const std::string& what) {
    if (!ok) diff += what + " ";
  };
  check(r.hitCount == w.hitCount, "hitCount " + std::to_string(r.hitCount) + " vs " + std::to_string(w.hitCount));
  check(r.truncated == w.truncated, "truncated");
  check(near(r.diffuse, w.diffuse), "diffuse");
  check(near(r.depth, w.depth), "depth");
  check(near(r.normal, w.normal), "normal");
  check(near(r.normalLength, w.normalLength), "normalLength");
  check(near(r.roughness, w.roughness), "roughness");
  check(near(r.f0, w.f0), "f0");
  check(near(r.transmittance, w.transmittance), "transmittance");
  check(hits.hits.size() == want.hits.hits.size(), "hit list length");
  for (size_t i = 0; i < std::min(hits.hits.size(), want.hits.hits.size()); ++i) {
    const HitRecord &a = hits.hits[i], &b = want.hits.hits[i];
    if (a.id != b.id || !near(a.t, b.t) || !near(a.alpha, b.alpha)) {
      diff += "hit " + std::to_string(i) + " (id " + std::to_string(a.id) + " vs " + std::to_string(b.id) + ") ";
      break;
    }
  }
  return diff;
}

// Traces every ray with the tracer and the oracle; every ray must match except a few
// that sit within rounding of a threshold. Returns the largest number of rounds.
int expectMatchesOracle(const EmbreeK16Tracer& tracer, const GaussianScene& scene, const TraceSettings& settings,
                        const std::vector<TraceRay>& rays, const std::string& label) {
  Oracle oracle(scene, settings);
  int excused = 0, maxRounds = 0, failures = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    HitList hits;
    hits.capacity = 100000;
    EmbreeTraceStats stats;
    RayResult r = tracer.trace(rays[i], &hits, &stats);
    maxRounds = std::max(maxRounds, stats.rounds);
    OracleRay want = oracle.trace(rays[i]);
    std::string diff = compare(r, hits, want);
    if (diff.empty()) continue;
    if (want.nearThreshold) {
      ++excused;
      continue;
    }
    if (++failures <= 5) ADD_FAILURE() << label << " ray " << i << ": " << diff;
  }
  EXPECT_EQ(failures, 0) << label;
  EXPECT_LE(excused, int(rays.size() / 100) + 1) << label << ": too many rays differ near a threshold";
  return maxRounds;
}

TEST(EmbreeK16Tracer, MatchesTheOracleOnRandomScenes) {
  GaussianScene scene = randomScene(2000, 11);
  std::vector<TraceRay> rays = randomRays(12, 2.0f, 150, 150, 60);
  for (float power : {1.0f, 3.0f}) {
    TraceSettings settings;
    settings.kernelPower = power;
    EmbreeK16Tracer tracer;
    for (float minT : {1e-4f, 0.01f}) {
      for (bool exactTail : {false, true}) {
        settings.minTransmittance = minT;
        settings.exactTail = exactTail;
        tracer.build(scene, settings);
        std::string label = "p=" + std::to_string(power) + " minT=" + std::to_string(minT) +
                            " exactTail=" + std::to_string(exactTail);
        expectMatchesOracle(tracer, scene, settings, rays, label);
      }
    }
  }
}

TEST(EmbreeK16Tracer, RaysNeedingManyRoundsMatchTheOracle) {
  // Dense, faint Gaussians: a ray composites ~100 hits before T < 1e-4.
  SceneShape dense;
  dense.boxHalf = 1.0f;
  dense.minScale = 0.05f;
  dense.maxScale = 0.25f;
  dense.minLogit = -4.0f;
  dense.maxLogit = -1.5f;
  GaussianScene scene = randomScene(2000, 21, dense);
  std::vector<TraceRay> rays = randomRays(22, 1.0f, 60, 60, 20);
  TraceSettings settings;
  settings.kernelPower = 1.0f;
  settings.minTransmittance = 1e-4f;
  EmbreeK16Tracer tracer;
  tracer.build(scene, settings);
  int maxRounds = expectMatchesOracle(tracer, scene, settings, rays, "dense");
  EXPECT_GE(maxRounds, 6);
  settings.exactTail = true;
  tracer.build(scene, settings);
  expectMatchesOracle(tracer, scene, settings, rays, "dense exactTail");
}

TEST(EmbreeK16Tracer, HitListOverflowKeepsTheResult) {
  GaussianScene scene = randomScene(2000, 31);
  TraceSettings settings;
  settings.minTransmittance = 1e-4f;
  EmbreeK16Tracer tracer;
  tracer.build(scene, settings);
  for (const TraceRay& ray : randomRays(32, 2.0f, 20, 20, 0)) {
    HitList small;
    small.capacity = 4;
    RayResult a = tracer.trace(ray, &small), b = tracer.trace(ray);
    EXPECT_EQ(a.diffuse, b.diffuse);
    EXPECT_EQ(a.transmittance, b.transmittance);
    EXPECT_EQ(small.hits.size(), size_t(std::min(a.hitCount, 4)));
    EXPECT_EQ(small.overflowed, a.hitCount > 4);
  }
}

void moveGaussians(GaussianScene& scene, uint64_t seed) {
  Rng rng(seed);
  for (size_t i = 0; i < scene.size(); ++i) {
    scene.position[i] += Vec3f(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f) * 0.6f;
    if (i % 2 == 0) scene.rotation[i] = randomOrientation(rng);
    scene.logScale[i] += Vec3f(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f) * 0.4f;
    if (scene.opacityLogit[i] > -6.0f) scene.opacityLogit[i] = std::clamp(scene.opacityLogit[i] + rng.uniform() - 0.5f, -4.0f, 4.0f);
  }
}

TEST(EmbreeK16Tracer, RefitAfterMovingGaussiansEqualsAFreshBuild) {
  for (auto mode : {EmbreeK16Tracer::BvhMode::kMedium, EmbreeK16Tracer::BvhMode::kRefit}) {
    GaussianScene scene = randomScene(2000, 41);
    TraceSettings settings;
    settings.minTransmittance = 1e-4f;
    EmbreeK16Tracer refitted(mode);
    refitted.build(scene, settings);
    std::vector<TraceRay> rays = randomRays(42, 2.0f, 100, 100, 0);
    for (int step = 0; step < 2; ++step) {
      moveGaussians(scene, 43 + step);
      // The second step also switches a Gaussian off (no proxy): refit must rebuild.
      if (step == 1) scene.opacityLogit[7] = -8.0f;
      refitted.refit();
      EmbreeK16Tracer fresh(mode);
      fresh.build(scene, settings);
      for (const TraceRay& ray : rays) {
        HitList a, b;
        RayResult ra = refitted.trace(ray, &a), rb = fresh.trace(ray, &b);
        ASSERT_EQ(ra.hitCount, rb.hitCount);
        EXPECT_EQ(ra.diffuse, rb.diffuse);
        EXPECT_EQ(ra.depth, rb.depth);
        EXPECT_EQ(ra.transmittance, rb.transmittance);
        for (size_t i = 0; i < a.hits.size(); ++i) ASSERT_EQ(a.hits[i].id, b.hits[i].id);
      }
      expectMatchesOracle(refitted, scene, settings, rays, "refit step " + std::to_string(step));
    }
  }
}

TEST(EmbreeK16Tracer, EmptyScenesLetEveryRayThrough) {
  GaussianScene empty;
  GaussianScene faint = randomScene(100, 51);
  for (float& l : faint.opacityLogit) l = -9.0f;  // no Gaussian reaches alphaMin
  for (const GaussianScene* scene : {&empty, &faint}) {
    EmbreeK16Tracer tracer;
    tracer.build(*scene, TraceSettings{});
    HitList hits;
    RayResult r = tracer.trace({{0, 0, 5}, {0, 0, -1}}, &hits);
    EXPECT_EQ(r.hitCount, 0);
    EXPECT_EQ(r.transmittance, 1.0f);
    EXPECT_EQ(r.depth, 0.0f);
    EXPECT_TRUE(hits.hits.empty());
    tracer.refit();
    EXPECT_EQ(tracer.trace({{0, 0, 5}, {0, 0, -1}}).hitCount, 0);
  }
}

TEST(EmbreeK16Tracer, SingleGaussianHasTheClosedFormHit) {
  GaussianScene scene;
  scene.resize(1);
  scene.position[0] = {0.1f, 0, -3};
  scene.logScale[0] = Vec3f(std::log(0.5f));
  scene.opacityLogit[0] = logit(0.8f);
  scene.diffuse[0] = Rgb(1.0f, 0.5f, 0.25f);
  for (float power : {1.0f, 3.0f}) {
    TraceSettings settings;
    settings.kernelPower = power;
    EmbreeK16Tracer tracer;
    tracer.build(scene, settings);
    HitList hits;
    RayResult r = tracer.trace({{0, 0, 0}, {0, 0, -1}}, &hits);
    double r2 = (0.1 / 0.5) * (0.1 / 0.5);
    double alpha = 0.9999 * 0.8 * std::exp(-std::pow(r2, power) / (2 * power));
    ASSERT_EQ(r.hitCount, 1);
    EXPECT_NEAR(r.diffuse.x, alpha, 1e-6);
    EXPECT_NEAR(r.depth, 3 * alpha, 1e-5);
    EXPECT_NEAR(r.transmittance, 1 - alpha, 1e-6);
    ASSERT_EQ(hits.hits.size(), 1u);
    EXPECT_NEAR(hits.hits[0].t, 3.0, 1e-6);
    // From inside, past the peak: the key clamps to tMin.
    r = tracer.trace({{0, 0, -3.2f}, {0, 0, -1}}, &hits);
    ASSERT_EQ(r.hitCount, 1);
    EXPECT_EQ(hits.hits[0].t, 0.0f);
    // Beyond the proxy: nothing.
    EXPECT_EQ(tracer.trace({{0, 0, -8}, {0, 0, -1}}).hitCount, 0);
    EXPECT_GT(tracer.memoryBytes(), 0u);
  }
}

}  // namespace
}  // namespace glint
