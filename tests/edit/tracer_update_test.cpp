// Refit-or-rebuild after an edit: whichever structure is kept traces the edited scene like a
// fresh build, and a changed Gaussian count is never refitted.
#include "render/tracer_update.h"

#include <gtest/gtest.h>

#include <cmath>

#include "edit/gaussian_edits.h"
#include "math/rng.h"

namespace glint {
namespace {

GaussianScene randomCloud(int count, uint64_t seed) {
  Rng rng(seed);
  GaussianScene s;
  s.resize(size_t(count));
  for (int i = 0; i < count; ++i) {
    s.position[i] = {rng.uniform() * 2 - 1, rng.uniform() * 2 - 1, rng.uniform() * 2 - 1};
    s.logScale[i] = Vec3f(std::log(0.03f + 0.05f * rng.uniform()));
    s.opacityLogit[i] = 2.0f * rng.uniform() - 0.5f;
    s.diffuse[i] = {rng.uniform(), rng.uniform(), rng.uniform()};
  }
  return s;
}

Camera probeCamera() {
  Camera c;
  c.cameraToWorld = Mat4::lookAt(Vec3d(0.3, -4, 0.5), Vec3d(0, 0, 0), Vec3d(0, 0, 1));
  c.width = 64;
  c.height = 64;
  c = Camera::fromFieldOfView(c.cameraToWorld, 0.7, c.width, c.height);
  return c;
}

// The diffuse of the probe rays through the tracer.
std::vector<Rgb> probeDiffuse(const GaussianTracer& tracer) {
  Camera c = probeCamera();
  std::vector<Rgb> out;
  for (int y = 0; y < kProbeSize; y += 3)
    for (int x = 0; x < kProbeSize; x += 3) {
      Ray r = c.generateRay(x + 0.5, y + 0.5);
      out.push_back(tracer.trace({Vec3f(r.origin), Vec3f(r.direction)}).diffuse);
    }
  return out;
}

// Expects `tracer` to trace `scene` like a tracer freshly built on it (the probe must see
// the cloud, or the comparison would be vacuous).
void expectTracesLikeAFreshBuild(const GaussianTracer& tracer, const GaussianScene& scene) {
  auto fresh = makeGaussianTracer("fast");
  fresh->build(scene, TraceSettings{});
  std::vector<Rgb> expected = probeDiffuse(*fresh), got = probeDiffuse(tracer);
  float seen = 0;
  for (size_t k = 0; k < expected.size(); ++k) {
    EXPECT_NEAR(got[k].x, expected[k].x, 1e-5f) << k;
    EXPECT_NEAR(got[k].z, expected[k].z, 1e-5f) << k;
    seen += expected[k].x;
  }
  EXPECT_GT(seen, 1.0f);
}

EditDocument moveHalf(Operation::Kind kind) {
  EditDocument doc;
  Selection half;
  half.kind = Selection::Kind::Shape;
  half.shape.center = {0.5f, 0, 0};
  half.shape.halfExtent = {0.5f, 1, 1};
  doc.selections["half"] = half;
  Operation op;
  op.kind = kind;
  op.selection = "half";
  op.offset = {0.0f, 0.0f, 1.5f};
  doc.operations = {op};
  return doc;
}

TEST(TracerUpdate, TheKeptStructureTracesTheEditedSceneLikeAFreshBuild) {
  for (double workRays : {0.0, 1e12}) {  // favour the cheaper update, then the faster tracing
    GaussianScene scene = randomCloud(3000, 1);
    auto tracer = makeGaussianTracer("fast");
    tracer->build(scene, TraceSettings{});
    EditReport report = applyEdits(moveHalf(Operation::Kind::Translate), scene);
    ASSERT_FALSE(report.countChanged());
    UpdatedTracer updated = updateTracerAfterEdit(std::move(tracer), scene, TraceSettings{}, "fast", true,
                                                  probeCamera(), workRays);
    EXPECT_TRUE(updated.times.refitPossible);
    EXPECT_GT(updated.times.rebuildSeconds, 0.0);
    EXPECT_GT(updated.times.refitProbeSeconds, 0.0);
    EXPECT_NE(describeTracerUpdate(updated.times).find("kept the"), std::string::npos);
    expectTracesLikeAFreshBuild(*updated.tracer, scene);
  }
}

TEST(TracerUpdate, AChangedCountIsRebuilt) {
  GaussianScene scene = randomCloud(2000, 2);
  auto tracer = makeGaussianTracer("fast");
  tracer->build(scene, TraceSettings{});
  EditReport report = applyEdits(moveHalf(Operation::Kind::Duplicate), scene);
  ASSERT_TRUE(report.countChanged());
  UpdatedTracer updated = updateTracerAfterEdit(std::move(tracer), scene, TraceSettings{}, "fast", false,
                                                probeCamera(), 1e6);
  EXPECT_FALSE(updated.times.refitPossible);
  EXPECT_FALSE(updated.times.refitChosen);
  expectTracesLikeAFreshBuild(*updated.tracer, scene);
}

}  // namespace
}  // namespace glint
