// A mirror made of Gaussians (roughness 0.01) reflects a pattern the camera cannot see
// directly to the pixels predicted analytically: the pattern mirrored through the floor
// plane and projected with the pinhole camera (issue 5).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "raytrace/gaussian_tracer.h"
#include "render/gaussian_layers.h"
#include "render/gaussian_renderer.h"

namespace glint {
namespace {

using test::addLayer;

constexpr float kF0 = 0.9f;              // the mirror's base reflectance (grey)
constexpr float kCeilingHeight = 1.5f;   // a grey ceiling above the mirror...
constexpr float kPatternHeight = 1.45f;  // ...with coloured squares hung just below it
constexpr Rgb kCeilingColour{0.2f, 0.2f, 0.2f};
constexpr float kSpacing = 0.04f;  // of the squares' Gaussians
constexpr int kCount = 12;         // Gaussians per side of a square
constexpr double kHalfSide = 0.5 * kSpacing * kCount;  // nominal half side, 0.24 m

struct Square {
  double x, y;  // centre, at height kPatternHeight
  Rgb colour;
};
const Square kSquares[] = {{0.0, 1.65, Rgb(1.0f, 0.0f, 0.0f)},
                           {-0.9, 2.5, Rgb(0.0f, 1.0f, 0.0f)},
                           {0.8, 1.0, Rgb(0.0f, 0.0f, 1.0f)}};

// Where the camera ray through pixel position (px, py), reflected by the ideal mirror
// z = 0, meets the plane z = height: the unreflected ray meets the mirrored plane
// z = -height at the same (x, y).
Vec3d reflectedHit(const Camera& camera, double px, double py, double height) {
  Ray ray = camera.generateRay(px, py);
  double t = (-height - ray.origin.z) / ray.direction.z;
  return {ray.origin.x + t * ray.direction.x, ray.origin.y + t * ray.direction.y, height};
}

// Pixel position of a world point under the pinhole model of scene/camera.h.
Vec2d project(const Camera& camera, const Vec3d& p) {
  Vec3d local = camera.cameraToWorld.inverse().transformPoint(p);
  return {camera.cx + camera.fx * local.x / -local.z, camera.cy - camera.fy * local.y / -local.z};
}

// Signed distance-like margin of a point of the pattern plane to square s: positive inside,
// the distance to the nearest edge (Chebyshev).
double insideBy(const Vec3d& h, const Square& s) {
  return kHalfSide - std::max(std::abs(h.x - s.x), std::abs(h.y - s.y));
}

// Schlick's Fresnel of the mirror for the camera ray through the pixel centre.
float mirrorFresnel(const Camera& camera, int x, int y) {
  float cosTheta = float(-camera.generateRay(x + 0.5, y + 0.5).direction.z);
  return kF0 + (1 - kF0) * std::pow(1 - cosTheta, 5.0f);
}

// The centroid of the analytic image of square s: the fraction of each pixel whose
// reflected ray meets the square, from 8 x 8 sub-pixel positions.
Vec2d analyticCentroid(const Camera& camera, const Square& s) {
  double sum = 0, sx = 0, sy = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x)
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 8; ++j) {
          double px = x + (i + 0.5) / 8, py = y + (j + 0.5) / 8;
          if (insideBy(reflectedHit(camera, px, py, kPatternHeight), s) < 0) continue;
          sum += 1, sx += px, sy += py;
        }
  return {sx / sum, sy / sum};
}

struct MirrorSetup {
  GaussianScene scene;
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer("fast");
  Camera camera;

  MirrorSetup() {
    // A 3.2 x 2.8 m mirror floor, a grey ceiling and three coloured squares facing down.
    addLayer(&scene, 0.0f, 0.5f, 0.0f, 32, 28, 0.1f, {Rgb(0.0f), Vec3f(0, 0, 1), 0.01f, Rgb(kF0)});
    addLayer(&scene, 0.0f, 2.3f, kCeilingHeight, 64, 50, 0.1f, {kCeilingColour, Vec3f(0, 0, -1)});
    for (const Square& s : kSquares)
      addLayer(&scene, float(s.x), float(s.y), kPatternHeight, kCount, kCount, kSpacing, {s.colour, Vec3f(0, 0, -1)});
    // The blended depth sum w_i t_i falls short of the layer by T t, T the transmittance
    // left when compositing stops, which moves the reflection origin back along the ray:
    // at the default minTransmittance (1%) that is up to 2.4 cm here, and it moves the
    // reflected squares by 0.17 pixel on average. Trained scenes fold this into their depth
    // supervision; compositing these hand-made layers down to T < 1e-4 makes their blended
    // depth the plane's.
    TraceSettings trace;
    trace.minTransmittance = 1e-4f;
    trace.kernelPower = 3.0f;  // the layers' spacing was chosen for the flat-topped kernel of power 3
    tracer->build(scene, trace);
    camera.cameraToWorld = Mat4::lookAt(Vec3d(0, -1, 1.2), Vec3d(0, 0.2, 0), Vec3d(0, 0, 1));
    camera.width = 64;
    camera.height = 48;
    camera = Camera::fromFieldOfView(camera.cameraToWorld, 0.8, camera.width, camera.height);
  }
};

TEST(MirrorReflection, PatternSeenOnlyInTheMirrorLandsWhereTheMirroredPatternProjects) {
  MirrorSetup m;
  const Camera& camera = m.camera;
  // The camera looks down at the mirror: every primary ray goes downwards, so the ceiling
  // and the squares, above the camera, can appear only in the mirror.
  for (int y = 0; y <= camera.height; y += camera.height)
    for (int x = 0; x <= camera.width; x += camera.width) {
      Ray corner = camera.generateRay(x, y);
      ASSERT_LT(corner.direction.z, -0.2);
      // The view's reflection stays well inside the ceiling (3.2 m either side of x = 0,
      // y from -0.2 to 4.8), so "outside the squares" means the grey ceiling everywhere...
      Vec3d h = reflectedHit(camera, x, y, kCeilingHeight);
      ASSERT_LT(std::abs(h.x), 3.0);
      ASSERT_GT(h.y, 0.0);
      ASSERT_LT(h.y, 4.6);
      // ...and the mirror (x within 1.6 m of 0, y from -0.9 to 1.9) fills the view.
      double t = -corner.origin.z / corner.direction.z;
      ASSERT_LT(std::abs(corner.origin.x + t * corner.direction.x), 1.4);
      ASSERT_GT(corner.origin.y + t * corner.direction.y, -0.7);
      ASSERT_LT(corner.origin.y + t * corner.direction.y, 1.7);
    }

  RenderSettings settings;
  settings.spp = 64;
  settings.seed = 11;
  settings.path.bounces = 1;
  ViewBuffers image = renderGaussianView(*m.tracer, camera, settings, 0);
  const Image& specular = image[Buffer::Specular];

  // Seen directly there is only the black mirror: the pattern is not in the diffuse buffer.
  for (float v : image[Buffer::Diffuse].pixels) ASSERT_LT(v, 1e-6f);

  // Each square's reflected centroid is where the mirrored square projects. A pixel
  // weighs how far its colour is from the reflected grey ceiling, which is linear in how
  // much of the pixel the square covers.
  for (const Square& s : kSquares) {
    SCOPED_TRACE(testing::Message() << "square at " << s.x << ", " << s.y);
    Vec2d centre = project(camera, Vec3d(s.x, s.y, -kPatternHeight));
    Vec2d centroid = analyticCentroid(camera, s);
    ASSERT_GT(std::min(centre.x, centre.y), 8.0);
    ASSERT_LT(centre.x, camera.width - 8.0);
    ASSERT_LT(centre.y, camera.height - 8.0);
    double sum = 0, sx = 0, sy = 0;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        if (insideBy(reflectedHit(camera, x + 0.5, y + 0.5, kPatternHeight), s) < -0.15) continue;
        Rgb background = kCeilingColour * mirrorFresnel(camera, x, y);
        Rgb v = specular.rgb(x, y);
        double w = std::abs(v.x - background.x) + std::abs(v.y - background.y) + std::abs(v.z - background.z);
        sum += w, sx += w * (x + 0.5), sy += w * (y + 0.5);
      }
    ASSERT_GT(sum, 0.0);
    Vec2d measured(sx / sum, sy / sum);
    // The projected centre is the half-pixel demand. The exact prediction is the
    // centroid of the square's perspective image, which the projected centre misses by
    // the foreshortening (0.18 to 0.31 pixel here); the render meets it within 0.06 pixel
    // (0.17 pixel at the default minTransmittance, from the depth shortfall above).
    EXPECT_NEAR(measured.x, centre.x, 0.5);
    EXPECT_NEAR(measured.y, centre.y, 0.5);
    EXPECT_NEAR(measured.x, centroid.x, 0.1);
    EXPECT_NEAR(measured.y, centroid.y, 0.1);
  }
}

TEST(MirrorReflection, PixelsInsideAndOutsideTheReflectedPatternHaveItsColourAndTheCeilings) {
  MirrorSetup m;
  const Camera& camera = m.camera;
  // Nine single-sample renders through the pixel centres. GGX's long tail (a fraction
  // alpha^2 / tan^2 of the microfacet normals tilts by more than an angle, with alpha
  // clamped to 1e-3 by the lobe) sends a few percent of the samples more than a pixel
  // away; the median of nine ignores such strays, so every pixel can be checked tightly.
  constexpr int kRenders = 9;
  std::vector<ViewBuffers> renders;
  for (int r = 0; r < kRenders; ++r) {
    RenderSettings settings;
    settings.spp = 1;
    settings.jitter = false;
    settings.seed = uint64_t(100 + r);
    settings.path.bounces = 1;
    renders.push_back(renderGaussianView(*m.tracer, camera, settings, 0));
  }
  auto medianSpecular = [&](int x, int y, int c) {
    std::array<float, kRenders> v;
    for (int r = 0; r < kRenders; ++r) v[size_t(r)] = renders[size_t(r)][Buffer::Specular].at(x, y, c);
    std::nth_element(v.begin(), v.begin() + kRenders / 2, v.end());
    return v[kRenders / 2];
  };

  // Pixels whose centre reflects inside a square by one Gaussian spacing show its colour x
  // Fresnel; pixels reflecting farther from every square than its Gaussians reach (1.8
  // sigma = 1.44 spacings past the outer centres, 0.94 spacing past the nominal edge)
  // show the grey ceiling x Fresnel.
  int inside = 0, outside = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      Vec3d h = reflectedHit(camera, x + 0.5, y + 0.5, kPatternHeight);
      const Square* in = nullptr;
      bool near = false;
      for (const Square& s : kSquares) {
        if (insideBy(h, s) > kSpacing) in = &s;
        near |= insideBy(h, s) > -kSpacing;
      }
      float F = mirrorFresnel(camera, x, y);
      Rgb expected;
      if (in) {
        expected = in->colour * F;
        ++inside;
      } else if (!near) {
        expected = kCeilingColour * F;
        ++outside;
      } else {
        continue;
      }
      // The layers blend to (1 - T) of their colours and F0 with T below 1e-4 here, so
      // within a percent (measured: 0.2%; 4.6% at the default minTransmittance).
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(medianSpecular(x, y, c), expected[c], 0.01 * expected[c] + 1e-3) << x << ", " << y;
    }
  EXPECT_GT(inside, 3 * 20);
  EXPECT_GT(outside, camera.width * camera.height / 2);
}

}  // namespace
}  // namespace glint
