// Corrupt and truncated COLMAP binary files are refused with a message, never a crash or
// an allocation sized by an untrusted count.
#include "io/colmap_binary.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <string>

#include "core/error.h"
#include "io/colmap_fixture.h"
#include "io/colmap_model.h"

namespace glint {
namespace {

ColmapFiles validBinary() {
  ColmapModel model = parseColmapModel(test::smallColmapText(), ColmapFormat::Text, "fixture");
  return formatColmapModel(model, ColmapFormat::Binary);
}

template <typename T>
void overwrite(std::string& bytes, size_t offset, T value) {
  std::memcpy(bytes.data() + offset, &value, sizeof(T));
}

template <typename Parse>
std::string errorOf(Parse parse, const std::string& bytes, const std::string& fileName) {
  try {
    parse(bytes, fileName);
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), fileName);
    return e.what();
  }
  return "";
}

// Byte offsets in the fixture written by formatColmapModel.
constexpr size_t kFirstRecord = 8;
constexpr size_t kCameraModelOffset = kFirstRecord + 4;
constexpr size_t kCameraWidthOffset = kFirstRecord + 8;
constexpr size_t kImageNameOffset = kFirstRecord + 4 + 56 + 4;

TEST(ColmapBinary, EveryTruncationIsRefusedCleanly) {
  ColmapFiles files = validBinary();
  for (size_t length = 0; length < files.cameras.size(); ++length)
    EXPECT_NE(errorOf(parseColmapCamerasBinary, files.cameras.substr(0, length), "cameras.bin"), "") << length;
  for (size_t length = 0; length < files.images.size(); ++length)
    EXPECT_NE(errorOf(parseColmapImagesBinary, files.images.substr(0, length), "images.bin"), "") << length;
  for (size_t length = 0; length < files.points.size(); ++length)
    EXPECT_NE(errorOf(parseColmapPointsBinary, files.points.substr(0, length), "points3D.bin"), "") << length;
  std::string message = errorOf(parseColmapCamerasBinary, files.cameras.substr(0, 30), "cameras.bin");
  EXPECT_NE(message.find("cameras.bin: "), std::string::npos) << message;
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
}

TEST(ColmapBinary, HugeCountsAreRefusedBeforeAllocating) {
  ColmapFiles files = validBinary();
  for (uint64_t count : {uint64_t(1) << 40, std::numeric_limits<uint64_t>::max(), uint64_t(1) << 20}) {
    std::string cameras = files.cameras;
    overwrite(cameras, 0, count);
    std::string message = errorOf(parseColmapCamerasBinary, cameras, "cameras.bin");
    EXPECT_NE(message.find("cameras.bin: "), std::string::npos) << message;
    std::string images = files.images;
    overwrite(images, 0, count);
    EXPECT_NE(errorOf(parseColmapImagesBinary, images, "images.bin"), "");
    std::string points = files.points;
    overwrite(points, 0, count);
    EXPECT_NE(errorOf(parseColmapPointsBinary, points, "points3D.bin"), "");
  }
  std::string points = files.points;
  overwrite(points, 0, uint64_t(1) << 40);
  std::string message = errorOf(parseColmapPointsBinary, points, "points3D.bin");
  EXPECT_NE(message.find("the header counts 1099511627776 points, but the"), std::string::npos) << message;
  // One record more than the file holds: the count check lets it through, the reader
  // then meets the end of the file.
  std::string cameras = files.cameras;
  overwrite(cameras, 0, uint64_t(3));
  message = errorOf(parseColmapCamerasBinary, cameras + std::string(50, '\0'), "cameras.bin");
  EXPECT_NE(message.find("cameras.bin: record 2 at byte"), std::string::npos) << message;
}

TEST(ColmapBinary, HugeInnerCountsAreRefused) {
  ColmapFiles files = validBinary();
  // The first image's 2D point count follows its name and NUL.
  size_t countOffset = files.images.find('\0', kImageNameOffset) + 1;
  std::string images = files.images;
  overwrite(images, countOffset, std::numeric_limits<uint64_t>::max() / 2);
  std::string message = errorOf(parseColmapImagesBinary, images, "images.bin");
  EXPECT_NE(message.find("images.bin: record 0 at byte 8: "), std::string::npos) << message;
  EXPECT_NE(message.find("2D points of 24 bytes each do not fit"), std::string::npos) << message;

  // The first point's track length is its last field.
  std::string points = files.points;
  overwrite(points, kFirstRecord + 8 + 24 + 3 + 8, std::numeric_limits<uint64_t>::max());
  message = errorOf(parseColmapPointsBinary, points, "points3D.bin");
  EXPECT_NE(message.find("track elements of 8 bytes each do not fit"), std::string::npos) << message;
}

TEST(ColmapBinary, RecordProblemsNameTheRecord) {
  ColmapFiles files = validBinary();
  std::string cameras = files.cameras;
  overwrite(cameras, kCameraModelOffset, int32_t(42));
  std::string message = errorOf(parseColmapCamerasBinary, cameras, "cameras.bin");
  EXPECT_NE(message.find("cameras.bin: record 0 at byte 8: camera 7: unknown camera model id 42"), std::string::npos)
      << message;

  cameras = files.cameras;
  overwrite(cameras, kCameraWidthOffset, uint64_t(1) << 62);
  message = errorOf(parseColmapCamerasBinary, cameras, "cameras.bin");
  // The width as stored (issue 39: it was quoted clamped, as 1048577).
  EXPECT_NE(message.find("image size 4611686018427387904 x "), std::string::npos) << message;
  EXPECT_NE(message.find("is not in [1, 1048576]"), std::string::npos) << message;

  cameras = files.cameras;
  overwrite(cameras, kCameraWidthOffset + 16, std::numeric_limits<double>::quiet_NaN());
  message = errorOf(parseColmapCamerasBinary, cameras, "cameras.bin");
  EXPECT_NE(message.find("parameter 0 is not a finite number"), std::string::npos) << message;

  std::string images = files.images;
  overwrite(images, kFirstRecord + 4, 2.0);  // qw
  message = errorOf(parseColmapImagesBinary, images, "images.bin");
  EXPECT_NE(message.find("record 0 at byte 8: image 3: the quaternion"), std::string::npos) << message;

  // The last record cut inside its name: its one 2D point (24 bytes), 8 bytes of 2D point
  // count and the NUL go.
  images = files.images.substr(0, files.images.size() - 24 - 9);
  message = errorOf(parseColmapImagesBinary, images, "images.bin");
  EXPECT_NE(message.find("NAME has no terminating NUL byte"), std::string::npos) << message;

  images = files.images;
  images[kImageNameOffset] = '\0';  // empty name
  message = errorOf(parseColmapImagesBinary, images, "images.bin");
  EXPECT_NE(message.find("image 3: "), std::string::npos) << message;

  std::string points = files.points + "xyz";
  message = errorOf(parseColmapPointsBinary, points, "points3D.bin");
  EXPECT_NE(message.find("points3D.bin: 3 unexpected bytes after the last record"), std::string::npos) << message;
}

TEST(ColmapBinary, DuplicateIdsAreRefused) {
  ColmapModel model = parseColmapModel(test::smallColmapText(), ColmapFormat::Text, "fixture");
  model.cameras[1].id = model.cameras[0].id;
  model.points[2].id = model.points[0].id;
  model.images[2].name = model.images[0].name;
  std::string message = errorOf(parseColmapCamerasBinary, formatColmapCamerasBinary(model.cameras), "cameras.bin");
  EXPECT_NE(message.find("record 1 at byte 64: camera id 7 is used twice"), std::string::npos) << message;
  message = errorOf(parseColmapPointsBinary, formatColmapPointsBinary(model.points), "points3D.bin");
  EXPECT_NE(message.find("record 2 at byte"), std::string::npos) << message;
  EXPECT_NE(message.find("point id 4 is used twice"), std::string::npos) << message;
  message = errorOf(parseColmapImagesBinary, formatColmapImagesBinary(model.images), "images.bin");
  EXPECT_NE(message.find("the name \"frames/b.png\" is used by an earlier image too"), std::string::npos) << message;
}

}  // namespace
}  // namespace glint
