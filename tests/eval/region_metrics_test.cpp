// Region metrics: the mask selects exactly the pixels whose true surface point lies in the
// box, and masked PSNR pools squared errors over those pixels only.
#include "eval/region_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

// A camera at the origin looking down -z at a wall z = -4 (depth = distance along each ray).
struct WallView {
  Camera camera;
  Image depth;
  WallView() : depth(40, 30, 1) {
    camera.width = 40;
    camera.height = 30;
    camera = Camera::fromFieldOfView(camera.cameraToWorld, 1.0, camera.width, camera.height);
    for (int y = 0; y < 30; ++y)
      for (int x = 0; x < 40; ++x) {
        Ray r = camera.generateRay(x + 0.5, y + 0.5);
        depth.at(x, y) = float(4.0 / -r.direction.z);
      }
  }
};

TEST(RegionMetrics, MaskHoldsThePixelsWhoseSurfacePointIsInTheBox) {
  WallView view;
  view.depth.at(0, 0) = 0.0f;  // no surface: never in the region
  WorldBox box{{-1.0, -0.5, -4.1}, {0.5, 1.0, -3.9}};
  std::vector<uint8_t> mask = regionMask(view.camera, view.depth, box);
  size_t inside = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      Ray r = view.camera.generateRay(x + 0.5, y + 0.5);
      Vec3d p = r.origin + r.direction * (4.0 / -r.direction.z);
      bool expected = p.x >= -1.0 && p.x <= 0.5 && p.y >= -0.5 && p.y <= 1.0 && !(x == 0 && y == 0);
      EXPECT_EQ(mask[size_t(y) * 40 + size_t(x)], expected ? 1 : 0) << x << "," << y;
      inside += expected;
    }
  EXPECT_GT(inside, 50u);
  WorldBox behind{{-10, -10, -3.5}, {10, 10, -1}};  // in front of the wall: nothing
  for (uint8_t m : regionMask(view.camera, view.depth, behind)) EXPECT_EQ(m, 0);
}

TEST(RegionMetrics, MaskedPsnrIgnoresPixelsOutsideTheMask) {
  Image a(4, 2, 3), b(4, 2, 3);
  std::vector<uint8_t> mask = {1, 1, 0, 0, 0, 0, 0, 0};
  b.pixels[0] = 0.1f;   // inside: one channel off by 0.1
  b.pixels[20] = 5.0f;  // outside: ignored
  MaskedError e = maskedError(a, b, mask);
  EXPECT_EQ(e.values, 6.0);
  EXPECT_NEAR(e.psnr(), 10 * std::log10(6.0 / (0.1 * 0.1)), 1e-4);
  MaskedError pooled = e;
  pooled += maskedError(a, a, mask);
  EXPECT_NEAR(pooled.psnr(), 10 * std::log10(12.0 / (0.1 * 0.1)), 1e-4);
  EXPECT_TRUE(std::isnan(maskedError(a, b, std::vector<uint8_t>(8, 0)).psnr()));
  EXPECT_THROW(maskedError(a, b, std::vector<uint8_t>(3, 1)), std::exception);
}

}  // namespace
}  // namespace glint
