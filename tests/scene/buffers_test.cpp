// Buffer names, channel counts and allocation.
#include "scene/buffers.h"

#include <gtest/gtest.h>

#include <limits>

namespace glint {
namespace {

TEST(Buffers, NamesRoundTripAndMatchTheFolderLayout) {
  const char* expected[] = {"render", "diffuse", "specular", "depth", "normal", "roughness", "f0"};
  for (int i = 0; i < kBufferCount; ++i) {
    Buffer b = kAllBuffers[i];
    EXPECT_STREQ(bufferName(b), expected[i]);
    ASSERT_TRUE(bufferFromName(expected[i]).has_value());
    EXPECT_EQ(*bufferFromName(expected[i]), b);
  }
  EXPECT_FALSE(bufferFromName("albedo").has_value());
  EXPECT_FALSE(bufferFromName("Render").has_value());
}

TEST(Buffers, ChannelsAndRadiance) {
  EXPECT_EQ(bufferChannels(Buffer::Render), 3);
  EXPECT_EQ(bufferChannels(Buffer::Normal), 3);
  EXPECT_EQ(bufferChannels(Buffer::F0), 3);
  EXPECT_EQ(bufferChannels(Buffer::Depth), 1);
  EXPECT_EQ(bufferChannels(Buffer::Roughness), 1);
  EXPECT_TRUE(isRadianceBuffer(Buffer::Render));
  EXPECT_TRUE(isRadianceBuffer(Buffer::Diffuse));
  EXPECT_TRUE(isRadianceBuffer(Buffer::Specular));
  EXPECT_FALSE(isRadianceBuffer(Buffer::Normal));
  EXPECT_FALSE(isRadianceBuffer(Buffer::F0));
}

TEST(Buffers, AllocateGivesZeroedImagesWithTheirChannelCounts) {
  ViewBuffers view = ViewBuffers::allocate(5, 4);
  for (Buffer b : kAllBuffers) {
    EXPECT_EQ(view[b].width, 5);
    EXPECT_EQ(view[b].height, 4);
    EXPECT_EQ(view[b].channels, bufferChannels(b));
    for (float v : view[b].pixels) EXPECT_EQ(v, 0.0f);
  }
}

TEST(Buffers, NoSurfaceDepths) {
  EXPECT_FALSE(hasSurface(0.0f));
  EXPECT_FALSE(hasSurface(kNoSurfaceDepth));
  EXPECT_FALSE(hasSurface(1.0e10f));
  EXPECT_FALSE(hasSurface(std::numeric_limits<float>::infinity()));
  EXPECT_TRUE(hasSurface(0.01f));
  EXPECT_TRUE(hasSurface(1.0e6f));
}

}  // namespace
}  // namespace glint
