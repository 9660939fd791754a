// Issue 6: duplicating an object visibly adds its reflection. A Gaussian mirror floor
// (roughness 0.01) reflects a red square hung above the camera, seen only in the mirror;
// an edit file duplicates the square, and the pixels that change between the renders before
// and after are those onto which the copy's mirror image (its points reflected through the
// floor plane, projected with the pinhole camera) falls, up to a two-pixel border.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "edit/edit_file.h"
#include "edit/gaussian_edits.h"
#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_layers.h"
#include "render/gaussian_renderer.h"

namespace glint {
namespace {

using test::addLayer;

constexpr float kSquareHeight = 1.45f;  // above the camera (1.2 m): seen only in the mirror
constexpr float kSpacing = 0.04f;
constexpr int kCount = 12;  // Gaussians per side of the square
constexpr int kBorder = 2;  // pixels either side of the predicted outline left unjudged

const char* kEdits = R"({
  "glint_edits": 1,
  "selections": {"square": {"box": {"min": [-0.3, 1.35, 1.4], "max": [0.3, 1.95, 1.5]}}},
  "operations": [{"op": "duplicate", "selection": "square", "offset": [-0.9, 0.85, 0]}]
})";

GaussianScene mirrorAndSquare() {
  GaussianScene scene;
  addLayer(&scene, 0.0f, 0.5f, 0.0f, 32, 28, 0.1f, {Rgb(0.0f), Vec3f(0, 0, 1), 0.01f, Rgb(0.9f)});
  addLayer(&scene, 0.0f, 1.65f, kSquareHeight, kCount, kCount, kSpacing, {Rgb(1.0f, 0.0f, 0.0f), Vec3f(0, 0, -1)});
  return scene;
}

Camera lookingDownAtTheMirror() {
  Camera camera;
  camera.cameraToWorld = Mat4::lookAt(Vec3d(0, -1, 1.2), Vec3d(0, 0.2, 0), Vec3d(0, 0, 1));
  camera.width = 128;  // the copy's mirror image is then about 20 x 9 pixels
  camera.height = 96;
  camera = Camera::fromFieldOfView(camera.cameraToWorld, 0.8, camera.width, camera.height);
  return camera;
}

ViewBuffers render(const GaussianScene& scene, const Camera& camera) {
  TraceSettings trace;
  trace.minTransmittance = 1e-4f;  // blended depth on the layer (see mirror_reflection_test)
  auto tracer = makeGaussianTracer("fast");
  tracer->build(scene, trace);
  RenderSettings settings;
  settings.spp = 64;
  settings.seed = 3;
  settings.path.bounces = 1;
  return renderGaussianView(*tracer, camera, settings, 0);
}

Vec2d project(const Camera& camera, const Vec3d& p) {
  Vec3d local = camera.cameraToWorld.inverse().transformPoint(p);
  return {camera.cx + camera.fx * local.x / -local.z, camera.cy - camera.fy * local.y / -local.z};
}

double cross2(const Vec2d& a, const Vec2d& b, const Vec2d& p) {
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// Inside the convex quadrilateral (corners in order, either orientation).
bool insideQuad(const std::vector<Vec2d>& quad, const Vec2d& p) {
  bool positive = true, negative = true;
  for (size_t k = 0; k < 4; ++k) {
    double c = cross2(quad[k], quad[(k + 1) % 4], p);
    positive = positive && c >= 0;
    negative = negative && c <= 0;
  }
  return positive || negative;
}

TEST(DuplicateReflection, ChangedPixelsAreWhereTheCopysMirrorImageProjects) {
  GaussianScene before = mirrorAndSquare();
  GaussianScene after = before;
  EditReport report = applyEdits(parseEditDocument(nlohmann::json::parse(kEdits), "duplicate.json"), after);
  ASSERT_EQ(report.operations[0].selected, size_t(kCount * kCount));  // the square, not the mirror
  ASSERT_EQ(after.size(), before.size() + kCount * kCount);

  // The copy's outline: its Gaussians' centres extended by half a spacing (the layer's
  // nominal edge), reflected through the mirror plane z = 0 and projected.
  Vec3f lo(1e9f), hi(-1e9f);
  for (size_t i = before.size(); i < after.size(); ++i) {
    lo = min(lo, after.position[i]);
    hi = max(hi, after.position[i]);
  }
  lo -= Vec3f(kSpacing / 2), hi += Vec3f(kSpacing / 2);
  Camera camera = lookingDownAtTheMirror();
  std::vector<Vec2d> outline;
  for (Vec2d corner : {Vec2d(lo.x, lo.y), Vec2d(hi.x, lo.y), Vec2d(hi.x, hi.y), Vec2d(lo.x, hi.y)})
    outline.push_back(project(camera, Vec3d(corner.x, corner.y, -double(kSquareHeight))));
  for (const Vec2d& p : outline) {  // the whole mirror image lies in the view
    ASSERT_GT(std::min(p.x, p.y), kBorder + 1.0);
    ASSERT_LT(p.x, camera.width - kBorder - 1.0);
    ASSERT_LT(p.y, camera.height - kBorder - 1.0);
  }
  auto predicted = [&](int x, int y) { return insideQuad(outline, Vec2d(x + 0.5, y + 0.5)); };

  ViewBuffers imageBefore = render(before, camera);
  ViewBuffers imageAfter = render(after, camera);
  // Seen directly nothing changes: the copy, like the original, is above the camera.
  EXPECT_EQ(imageAfter[Buffer::Diffuse].pixels, imageBefore[Buffer::Diffuse].pixels);
  EXPECT_EQ(imageAfter[Buffer::Depth].pixels, imageBefore[Buffer::Depth].pixels);

  // A pixel has changed when its render moved by more than a few stray GGX samples could
  // move it (one of 64 samples reflecting the red copy adds about 0.9 / 64 = 0.014).
  constexpr float kChanged = 0.1f;
  int judged = 0, predictedIn = 0, unchangedExactly = 0, outside = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      Rgb d = imageAfter[Buffer::Render].rgb(x, y) - imageBefore[Buffer::Render].rgb(x, y);
      float change = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
      bool in = predicted(x, y);
      // Pixels within kBorder of the outline may go either way (partial coverage, the
      // Gaussians' soft edge).
      bool border = false;
      for (int dy = -kBorder; dy <= kBorder; ++dy)
        for (int dx = -kBorder; dx <= kBorder; ++dx) border = border || predicted(x + dx, y + dy) != in;
      if (border) continue;
      ++judged;
      if (in) {
        ++predictedIn;
        EXPECT_GT(change, kChanged) << "pixel " << x << ", " << y << " should show the copy's reflection";
        EXPECT_GT(d.x, 0.5f) << "pixel " << x << ", " << y << ": the reflection is red";
      } else {
        ++outside;
        EXPECT_LT(change, kChanged) << "pixel " << x << ", " << y << " should be unchanged";
        unchangedExactly += change == 0.0f;
      }
    }
  std::printf("%d pixels predicted inside the copy's reflection, %d outside\n", predictedIn, outside);
  EXPECT_GT(predictedIn, 40);  // the copy's reflection covers a fair patch of the image
  EXPECT_GT(judged, camera.width * camera.height * 3 / 4);
  // Away from the copy nearly every pixel is identical bit for bit (the others hold a
  // stray sample or two of the GGX tail).
  EXPECT_GT(unchangedExactly, outside * 95 / 100);
}

}  // namespace
}  // namespace glint
