// TrainingViews' F0 targets from a metalness prior: with f0_tint_from_reflections only the
// metals' brightness is trained, so L_r can tint them; the dielectrics keep every channel.
// And the photographs held for the photograph term.
#include "train/training_views.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "io/temp_folder.h"
#include "scene/dataset.h"
#include "scene/predicted_buffers.h"
#include "train/room_capture.h"

namespace glint {
namespace {

TEST(TrainingViews, MetalnessTrainsTheBrightnessOfMetalsOnly) {
  test::TempFolder temp;
  test::writeRoomCapture(temp / "capture", PriorErrors::Monocular);  // metalness, no F0 file
  const Dataset dataset = Dataset::open(temp / "capture", true, 8);
  const TrainingViews tinted = TrainingViews::load(dataset, dataset.train(), ColourTarget::Diffuse, true, 0.3f);
  const TrainingViews plain = TrainingViews::load(dataset, dataset.train());
  ASSERT_TRUE(tinted.supervised().f0BrightnessOnly);
  EXPECT_FALSE(plain.supervised().f0BrightnessOnly);
  EXPECT_EQ(tinted.supervised().f0TintPrior, 0.3f);
  EXPECT_EQ(plain.supervised().f0TintPrior, 0.0f);
  size_t metals = 0, dielectrics = 0;
  for (size_t view = 0; view < tinted.viewCount(); ++view)
    for (size_t pixel = 0; pixel < tinted.pixelCount(view); ++pixel) {
      if (!tinted.surfaceAt(view, pixel)) continue;
      const PixelTarget t = tinted.target(view, pixel);
      ASSERT_EQ(t.f0.x, t.f0.y);  // grey, by the white-base rule
      ASSERT_EQ(t.f0.x, t.f0.z);
      EXPECT_EQ(t.f0BrightnessOnly, greyF0IsMetal(t.f0));
      if (t.f0BrightnessOnly) {
        EXPECT_EQ(t.f0TintPrior, 0.3f);  // the share of the grey prior kept
      }
      EXPECT_FALSE(plain.target(view, pixel).f0BrightnessOnly);
      ++(t.f0BrightnessOnly ? metals : dielectrics);
    }
  // The room's mirror, pot and lid are metals; its walls, floor and table are not.
  EXPECT_GT(metals, 0u);
  EXPECT_GT(dielectrics, metals);
}

// With the photograph term each pixel also holds its view's render buffer (the photograph),
// beside the diffuse prior; without it none is held.
TEST(TrainingViews, PhotographTermHoldsEachViewsRenderBuffer) {
  test::TempFolder temp;
  test::writeRoomCapture(temp / "capture", PriorErrors::Monocular);
  const Dataset dataset = Dataset::open(temp / "capture", true, 8);
  const TrainingViews with =
      TrainingViews::load(dataset, dataset.train(), ColourTarget::Diffuse, false, 0.1f, /*photograph=*/true);
  const TrainingViews without = TrainingViews::load(dataset, dataset.train());
  ASSERT_TRUE(with.supervised().photograph);
  EXPECT_FALSE(without.supervised().photograph);
  size_t pixels = 0;
  for (size_t view = 0; view < with.viewCount(); ++view) pixels += with.pixelCount(view);
  EXPECT_EQ(with.memoryBytes(), without.memoryBytes() + 4 * pixels);
  const Image render = dataset.loadBuffer(dataset.train(), 0, Buffer::Render);
  double differs = 0;
  for (size_t pixel = 0; pixel < with.pixelCount(0); ++pixel) {
    const PixelTarget t = with.target(0, pixel);
    ASSERT_TRUE(t.hasPhotograph);
    EXPECT_FALSE(without.target(0, pixel).hasPhotograph);
    const Rgb expected = render.rgb(int(pixel % size_t(render.width)), int(pixel / size_t(render.width)));
    // Shared exponents: each channel to 9 bits of the pixel's largest.
    const float step = std::max({expected.x, expected.y, expected.z, 1e-4f}) / 256.0f;
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(t.photograph[c], expected[c], step) << pixel;
      differs += std::abs(t.photograph[c] - t.diffuse[c]);
    }
  }
  EXPECT_GT(differs, 1.0);  // the photograph is not the diffuse prior

}

}  // namespace
}  // namespace glint
