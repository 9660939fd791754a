// The dead-leaves texture is deterministic, covers its image, and does not repeat itself.
#include "synth/procedural_textures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace glint {
namespace {

// Mean absolute difference of two equally sized windows of an image's first channel.
double windowDifference(const Image& image, int ax, int ay, int bx, int by, int size) {
  double sum = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) sum += std::abs(image.at(ax + x, ay + y) - image.at(bx + x, by + y));
  return sum / (size * size);
}

TEST(DeadLeavesTexture, SameSeedSameImageOtherSeedOtherImage) {
  Texture a = makeDeadLeavesTexture("a", 128, 7);
  Texture b = makeDeadLeavesTexture("b", 128, 7);
  Texture c = makeDeadLeavesTexture("c", 128, 8);
  EXPECT_EQ(a.image.pixels, b.image.pixels);
  EXPECT_NE(a.image.pixels, c.image.pixels);
}

TEST(DeadLeavesTexture, ValuesStayNearTheAlbedoRangeAndVary) {
  Texture t = makeDeadLeavesTexture("t", 256, 3, 0.1f, 0.7f);
  double sum = 0, sumSquares = 0;
  for (float v : t.image.pixels) {
    // The shading gradient may push a value 25% past the range, never further.
    EXPECT_GE(v, 0.1f * 0.75f - 1e-6f);
    EXPECT_LE(v, 0.7f * 1.25f + 1e-6f);
    sum += v, sumSquares += double(v) * v;
  }
  double n = double(t.image.pixels.size());
  double deviation = std::sqrt(sumSquares / n - (sum / n) * (sum / n));
  EXPECT_GT(deviation, 0.08);  // contrast for a feature detector, not a flat wall
}

TEST(DeadLeavesTexture, NoWindowRepeatsElsewhere) {
  // A checker or tiled texture has windows that recur exactly; a dead-leaves image's
  // windows differ from every other window by about the image's contrast.
  Texture t = makeDeadLeavesTexture("t", 256, 5);
  const int window = 32;
  for (int ay = 0; ay + window <= 256; ay += 64)
    for (int ax = 0; ax + window <= 256; ax += 64)
      for (int by = 0; by + window <= 256; by += 16)
        for (int bx = 0; bx + window <= 256; bx += 16) {
          if (std::abs(ax - bx) < window && std::abs(ay - by) < window) continue;  // overlapping
          EXPECT_GT(windowDifference(t.image, ax, ay, bx, by, window), 0.03)
              << "window at " << ax << "," << ay << " recurs at " << bx << "," << by;
        }
}

TEST(DeadLeavesTexture, HasDetailAtFineAndCoarseScales) {
  // Neighbouring texels differ often (small discs' edges), and so do texels 32 apart.
  Texture t = makeDeadLeavesTexture("t", 256, 11);
  int fineChanges = 0, coarseChanges = 0, count = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x + 32 < 256; ++x) {
      fineChanges += std::abs(t.image.at(x, y) - t.image.at(x + 1, y)) > 0.05f;
      coarseChanges += std::abs(t.image.at(x, y) - t.image.at(x + 32, y)) > 0.05f;
      ++count;
    }
  EXPECT_GT(fineChanges, count / 20);
  EXPECT_GT(coarseChanges, count / 2);
}

}  // namespace
}  // namespace glint
