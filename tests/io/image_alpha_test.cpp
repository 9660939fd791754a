// readImageWithAlpha keeps a PNG's alpha (as the NeRF-synthetic layout needs), where
// readImage drops it.
#include <gtest/gtest.h>

#include "core/error.h"
#include "io/image.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

TEST(ReadImageWithAlpha, KeepsThePngAlphaThatReadImageDrops) {
  test::TempFolder folder;
  Image rgba(3, 2, 4);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      for (int c = 0; c < 4; ++c) rgba.at(x, y, c) = float((x + 3 * y + 40 * c) % 256) / 255.0f;
  writeImage(folder / "rgba.png", rgba);

  const Image kept = readImageWithAlpha(folder / "rgba.png");
  ASSERT_EQ(kept.channels, 4);
  EXPECT_EQ(kept.pixels, rgba.pixels);
  const Image dropped = readImage(folder / "rgba.png");
  ASSERT_EQ(dropped.channels, 3);
  EXPECT_FLOAT_EQ(dropped.at(2, 1, 2), rgba.at(2, 1, 2));

  // A grey PNG comes back as RGB, one without alpha as it is.
  Image grey(3, 2, 1, 0.5f);
  writeImage(folder / "grey.png", grey);
  const Image greyKept = readImageWithAlpha(folder / "grey.png");
  ASSERT_EQ(greyKept.channels, 3);
  EXPECT_NEAR(greyKept.at(1, 1, 2), 128.0f / 255.0f, 1e-6);
  EXPECT_THROW(readImageWithAlpha(folder / "missing.png"), Error);
}

}  // namespace
}  // namespace glint
