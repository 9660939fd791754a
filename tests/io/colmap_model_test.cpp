// COLMAP models: hand-written text and binary files, text <-> binary round trips, the
// folder reader's choices, and one clear error per kind of mistake.
#include "io/colmap_model.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "core/error.h"
#include "io/colmap_fixture.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

// Little-endian bytes of hand-made binary files.
struct Bytes {
  std::string data;
  template <typename T>
  Bytes& put(T value) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    data.append(raw, sizeof(T));
    return *this;
  }
  Bytes& name(const std::string& s) {
    data.append(s.c_str(), s.size() + 1);
    return *this;
  }
};

ColmapFiles handWrittenBinary() {
  ColmapFiles files;
  Bytes cameras;
  cameras.put<uint64_t>(1).put<uint32_t>(4).put<int32_t>(1).put<uint64_t>(800).put<uint64_t>(600);
  for (double p : {700.0, 710.0, 400.5, 299.5}) cameras.put(p);
  files.cameras = cameras.data;

  Bytes images;
  images.put<uint64_t>(2);
  images.put<uint32_t>(12);
  for (double v : {0.0, 1.0, 0.0, 0.0, 0.5, 0.25, -3.0}) images.put(v);
  images.put<uint32_t>(4).name("img_12.jpg").put<uint64_t>(2);
  images.put(1.5).put(2.5).put<uint64_t>(77).put(3.5).put(4.5).put<uint64_t>(~uint64_t(0));
  images.put<uint32_t>(11);
  for (double v : {1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0}) images.put(v);
  images.put<uint32_t>(4).name("img_11.jpg").put<uint64_t>(0);
  files.images = images.data;

  Bytes points;
  points.put<uint64_t>(1).put<uint64_t>(77).put(1.0).put(-2.0).put(3.0);
  points.put<uint8_t>(9).put<uint8_t>(8).put<uint8_t>(7).put(0.75).put<uint64_t>(2);
  points.put<uint32_t>(12).put<uint32_t>(0).put<uint32_t>(11).put<uint32_t>(5);
  files.points = points.data;
  return files;
}

// The message of the Error parsing throws, or "" if it parses.
std::string parseError(const ColmapFiles& files, ColmapFormat format) {
  try {
    parseColmapModel(files, format, "sparse/0");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ColmapModel, ParsesHandWrittenText) {
  ColmapModel model = parseColmapModel(test::smallColmapText(), ColmapFormat::Text, "sparse/0");
  EXPECT_EQ(model.format, ColmapFormat::Text);
  ASSERT_EQ(model.cameras.size(), 2u);
  EXPECT_EQ(model.cameras[0].id, 7u);
  EXPECT_EQ(model.cameras[0].model, "PINHOLE");
  EXPECT_EQ(model.cameras[0].width, 640);
  EXPECT_EQ(model.cameras[0].height, 480);
  EXPECT_EQ(model.cameras[0].params, (std::vector<double>{500.5, 501.25, 320.5, 239.75}));
  EXPECT_EQ(model.cameras[1].model, "SIMPLE_PINHOLE");
  EXPECT_EQ(model.cameras[1].params, (std::vector<double>{300, 160, 100}));

  ASSERT_EQ(model.images.size(), 3u);
  EXPECT_EQ(model.images[0].id, 3u);
  EXPECT_EQ(model.images[0].qvec.w, 0.5);
  EXPECT_EQ(model.images[0].qvec.y, -0.5);
  EXPECT_EQ(model.images[0].tvec, Vec3d(1.5, -2, 0.25));
  EXPECT_EQ(model.images[0].cameraId, 7u);
  EXPECT_EQ(model.images[0].name, "frames/b.png");
  // The empty 2D point line of image 1 is its own, not skipped as blank.
  EXPECT_EQ(model.images[1].name, "frames/a.png");
  EXPECT_EQ(model.images[1].cameraId, 2u);
  EXPECT_EQ(model.images[2].name, "frames/c d.png");
  // 2D points, "-1" (no 3D point) and an id beyond int64 kept as written.
  ASSERT_EQ(model.images[0].points2D.size(), 2u);
  EXPECT_EQ(model.images[0].points2D[0].xy.x, 10.5);
  EXPECT_EQ(model.images[0].points2D[0].xy.y, 20.25);
  EXPECT_EQ(model.images[0].points2D[0].point3DId, 4u);
  EXPECT_EQ(model.images[0].points2D[1].point3DId, kColmapNoPoint3D);
  EXPECT_TRUE(model.images[1].points2D.empty());
  ASSERT_EQ(model.images[2].points2D.size(), 1u);
  EXPECT_EQ(model.images[2].points2D[0].point3DId, 18446744073709551614u);

  ASSERT_EQ(model.points.size(), 4u);
  EXPECT_EQ(model.points[0].id, 4u);
  EXPECT_EQ(model.points[0].xyz, Vec3d(1, 2, 3));
  EXPECT_EQ(model.points[0].rgb, (std::array<uint8_t, 3>{255, 128, 0}));
  EXPECT_EQ(model.points[0].error, 0.5);
  // The track: (image 3, its 2D point 0) and (image 1, its 2D point 1).
  ASSERT_EQ(model.points[0].track.size(), 2u);
  EXPECT_EQ(model.points[0].track[0].imageId, 3u);
  EXPECT_EQ(model.points[0].track[0].point2DIndex, 0u);
  EXPECT_EQ(model.points[0].track[1].imageId, 1u);
  EXPECT_EQ(model.points[0].track[1].point2DIndex, 1u);
  EXPECT_TRUE(model.points[1].track.empty());
  EXPECT_EQ(model.points[1].id, ~uint64_t(0));
  EXPECT_EQ(model.points[1].error, -1.0);
  EXPECT_EQ(model.points[3].xyz, Vec3d(1e-3, -450, 7));
}

TEST(ColmapModel, ParsesHandWrittenBinaryWithPointsAndTracks) {
  ColmapModel model = parseColmapModel(handWrittenBinary(), ColmapFormat::Binary, "sparse/0");
  EXPECT_EQ(model.format, ColmapFormat::Binary);
  ASSERT_EQ(model.cameras.size(), 1u);
  EXPECT_EQ(model.cameras[0].id, 4u);
  EXPECT_EQ(model.cameras[0].model, "PINHOLE");
  EXPECT_EQ(model.cameras[0].width, 800);
  EXPECT_EQ(model.cameras[0].params, (std::vector<double>{700, 710, 400.5, 299.5}));
  ASSERT_EQ(model.images.size(), 2u);
  EXPECT_EQ(model.images[0].id, 12u);
  EXPECT_EQ(model.images[0].qvec.x, 1.0);
  EXPECT_EQ(model.images[0].tvec, Vec3d(0.5, 0.25, -3));
  EXPECT_EQ(model.images[0].name, "img_12.jpg");
  EXPECT_EQ(model.images[1].name, "img_11.jpg");
  ASSERT_EQ(model.images[0].points2D.size(), 2u);
  EXPECT_EQ(model.images[0].points2D[0].xy.x, 1.5);
  EXPECT_EQ(model.images[0].points2D[0].xy.y, 2.5);
  EXPECT_EQ(model.images[0].points2D[0].point3DId, 77u);
  EXPECT_EQ(model.images[0].points2D[1].xy.x, 3.5);
  EXPECT_EQ(model.images[0].points2D[1].xy.y, 4.5);
  EXPECT_EQ(model.images[0].points2D[1].point3DId, kColmapNoPoint3D);
  EXPECT_TRUE(model.images[1].points2D.empty());
  ASSERT_EQ(model.points.size(), 1u);
  EXPECT_EQ(model.points[0].id, 77u);
  EXPECT_EQ(model.points[0].xyz, Vec3d(1, -2, 3));
  EXPECT_EQ(model.points[0].rgb, (std::array<uint8_t, 3>{9, 8, 7}));
  EXPECT_EQ(model.points[0].error, 0.75);
  ASSERT_EQ(model.points[0].track.size(), 2u);
  EXPECT_EQ(model.points[0].track[0].imageId, 12u);
  EXPECT_EQ(model.points[0].track[0].point2DIndex, 0u);
  EXPECT_EQ(model.points[0].track[1].imageId, 11u);
  EXPECT_EQ(model.points[0].track[1].point2DIndex, 5u);
}

TEST(ColmapModel, RoundTripsTextToBinaryToTextExactly) {
  ColmapModel text = parseColmapModel(test::smallColmapText(), ColmapFormat::Text, "a");
  ColmapFiles binaryFiles = formatColmapModel(text, ColmapFormat::Binary);
  ColmapModel binary = parseColmapModel(binaryFiles, ColmapFormat::Binary, "b");
  test::expectSameModel(text, binary);
  ColmapFiles textFiles = formatColmapModel(binary, ColmapFormat::Text);
  ColmapModel again = parseColmapModel(textFiles, ColmapFormat::Text, "c");
  test::expectSameModel(text, again);
  // Formatting is a function of the model: the second text is the first, byte for byte.
  ColmapFiles textAgain = formatColmapModel(again, ColmapFormat::Text);
  EXPECT_EQ(textAgain.cameras, textFiles.cameras);
  EXPECT_EQ(textAgain.images, textFiles.images);
  EXPECT_EQ(textAgain.points, textFiles.points);
  EXPECT_EQ(formatColmapModel(again, ColmapFormat::Binary).images, binaryFiles.images);
  // Values that need all 17 digits survive.
  text.images[0].tvec.x = 0.1 + 0.2;
  text.points[0].xyz.z = 1.0 / 3.0;
  ColmapModel precise = parseColmapModel(formatColmapModel(text, ColmapFormat::Text), ColmapFormat::Text, "d");
  EXPECT_EQ(precise.images[0].tvec.x, 0.1 + 0.2);
  EXPECT_EQ(precise.points[0].xyz.z, 1.0 / 3.0);
}

TEST(ColmapModel, FolderReaderPrefersBinaryAndSaysWhichItRead) {
  test::TempFolder folder;
  ColmapModel text = parseColmapModel(test::smallColmapText(), ColmapFormat::Text, "a");
  writeColmapModelText(folder / "sparse", text);
  ColmapModel read = readColmapModel(folder / "sparse");
  EXPECT_EQ(read.format, ColmapFormat::Text);
  test::expectSameModel(read, text);

  ColmapModel other = parseColmapModel(handWrittenBinary(), ColmapFormat::Binary, "b");
  writeColmapModelBinary(folder / "sparse", other);
  read = readColmapModel(folder / "sparse");
  EXPECT_EQ(read.format, ColmapFormat::Binary);
  test::expectSameModel(read, other);
}

TEST(ColmapModel, CommittedFixtureReadsAndWritesBackByteForByte) {
  std::filesystem::path fixture = std::filesystem::path(GLINT_TEST_DATA) / "colmap_small";
  ColmapModel read = readColmapModel(fixture);
  EXPECT_EQ(read.format, ColmapFormat::Text);
  test::expectSameModel(read, parseColmapModel(test::smallColmapText(), ColmapFormat::Text, "a"));
  test::TempFolder folder;
  writeColmapModelText(folder.path(), read);
  for (const char* name : {"cameras.txt", "images.txt", "points3D.txt"})
    EXPECT_EQ(test::readBytes(folder / name), test::readBytes(fixture / name)) << name;
}

TEST(ColmapModel, FolderErrorsNameTheFolderOrFile) {
  test::TempFolder folder;
  auto message = [](const std::filesystem::path& path) -> std::string {
    try {
      readColmapModel(path);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  std::string missing = message(folder / "nothing");
  EXPECT_NE(missing.find("nothing: COLMAP model folder not found"), std::string::npos) << missing;
  std::string empty = message(folder.path());
  EXPECT_NE(empty.find("neither cameras.bin nor cameras.txt"), std::string::npos) << empty;
  test::writeBytes(folder / "cameras.txt", "1 PINHOLE 4 4 1 1 2 2\n");
  std::string noImages = message(folder.path());
  EXPECT_NE(noImages.find("images.txt"), std::string::npos) << noImages;
}

struct BadText {
  const char* name;
  const char* file;  // which of the three files the text replaces
  std::string text;
  const char* expected;  // part of the message
};

void PrintTo(const BadText& bad, std::ostream* out) { *out << bad.name; }

class ColmapTextErrors : public testing::TestWithParam<BadText> {};

TEST_P(ColmapTextErrors, NameTheFileLineAndProblem) {
  ColmapFiles files = test::smallColmapText();
  std::string bad = GetParam().text;
  std::string which = GetParam().file;
  (which == "cameras" ? files.cameras : which == "images" ? files.images : files.points) = bad;
  std::string message = parseError(files, ColmapFormat::Text);
  std::string fileName = "sparse/0/" + which + (which == "points" ? "3D" : "") + ".txt: ";
  EXPECT_EQ(message.rfind(fileName, 0), 0u) << message;
  EXPECT_NE(message.find(GetParam().expected), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    Mistakes, ColmapTextErrors,
    testing::Values(
        BadText{"UnknownModel", "cameras", "7 PINHOLE 640 480 1 1 1 1\n2 SIMPLE_PINHOLE 320 200 300 160 100\n"
                                           "3 KANNALA 4 4 1 2 3\n",
                "line 3: camera 3: unknown camera model \"KANNALA\""},
        BadText{"ParamCount", "cameras", "7 PINHOLE 640 480 500 501 320\n",
                "line 1: camera 7: camera model PINHOLE takes 4 parameters, but 3 are given"},
        BadText{"NaN", "cameras", "7 PINHOLE 640 480 nan 1 1 1\n", "line 1: camera parameter is not a finite number"},
        BadText{"Inf", "cameras", "7 PINHOLE 640 480 inf 1 1 1\n", "camera parameter is not a finite number"},
        BadText{"Word", "cameras", "7 PINHOLE 640 480 five 1 1 1\n", "camera parameter \"five\" is not a number"},
        BadText{"ZeroWidth", "cameras", "7 PINHOLE 0 480 1 1 1 1\n", "image size 0 x 480 is not in [1, 1048576]"},
        BadText{"HugeHeight", "cameras", "7 PINHOLE 4 99999999999 1 1 1 1\n", "is not in [1, 1048576]"},
        // Issue 39: sizes are quoted as written, not as clamped values (1048577, -1).
        BadText{"BillionWidth", "cameras", "7 PINHOLE 1000000000 480 1 1 1 1\n",
                "image size 1000000000 x 480 is not in [1, 1048576]"},
        BadText{"NegativeWidth", "cameras", "7 PINHOLE -64 480 1 1 1 1\n", "image size -64 x 480 is not"},
        BadText{"Width2Pow63", "cameras", "7 PINHOLE 9223372036854775808 480 1 1 1 1\n",
                "image size 9223372036854775808 x 480 is not"},
        BadText{"WordWidth", "cameras", "7 PINHOLE wide 480 1 1 1 1\n", "WIDTH \"wide\" is not an integer"},
        BadText{"NegativeId", "cameras", "-7 PINHOLE 4 4 1 1 1 1\n", "CAMERA_ID \"-7\" is not an integer in range"},
        BadText{"DuplicateCamera", "cameras", "7 PINHOLE 4 4 1 1 1 1\n\n# again\n7 PINHOLE 4 4 1 1 1 1\n",
                "line 4: camera id 7 is used twice"},
        BadText{"ShortImage", "images", "1 1 0 0 0 0 0\n\n", "line 1: TZ is missing"},
        BadText{"MissingName", "images", "1 1 0 0 0 0 0 0 7\n\n", "line 1: NAME is missing"},
        BadText{"NonUnitQuaternion", "images", "1 1 0 0 0.1 0 0 0 7 a.png\n\n",
                "line 1: image 1: the quaternion (1, 0, 0, 0.1) has norm 1.00499"},
        BadText{"ZeroQuaternion", "images", "1 0 0 0 0 0 0 0 7 a.png\n\n", "has norm 0"},
        BadText{"NaNTranslation", "images", "1 1 0 0 0 nan 0 0 7 a.png\n\n", "TX is not a finite number"},
        BadText{"MissingCamera", "images", "1 1 0 0 0 0 0 0 5 a.png\n\n",
                "image 1 (\"a.png\") refers to camera 5, which cameras.txt does not define"},
        BadText{"DuplicateImage", "images", "1 1 0 0 0 0 0 0 7 a.png\n\n1 1 0 0 0 0 0 0 7 b.png\n\n",
                "line 3: image id 1 is used twice"},
        BadText{"DuplicateName", "images", "1 1 0 0 0 0 0 0 7 a.png\n\n2 1 0 0 0 0 0 0 7 a.png\n\n",
                "line 3: image 2: the name \"a.png\" is used by an earlier image too"},
        BadText{"ParentName", "images", "1 1 0 0 0 0 0 0 7 ../secret.png\n\n", "leaves the image folder"},
        BadText{"AbsoluteName", "images", "1 1 0 0 0 0 0 0 7 /etc/passwd\n\n", "is an absolute path"},
        BadText{"PointsNotTriples", "images", "1 1 0 0 0 0 0 0 7 a.png\n1 2 3 4 5\n",
                "line 2: image 1: 2D point 1 has no POINT3D_ID"},
        BadText{"BadPoint3DId", "images", "1 1 0 0 0 0 0 0 7 a.png\n1 2 -2\n",
                "POINT3D_ID \"-2\" is neither -1 nor an unsigned integer"},
        BadText{"ColourRange", "points", "1 0 0 0 256 0 0 0\n", "line 1: R \"256\" is not an integer in range"},
        BadText{"MissingError", "points", "1 0 0 0 1 2 3\n", "line 1: ERROR is missing"},
        BadText{"OddTrack", "points", "1 0 0 0 1 2 3 0.5 4 0 5\n", "point 1: the track ends inside a pair"},
        BadText{"DuplicatePoint", "points", "1 0 0 0 1 2 3 0.5\n1 0 0 0 1 2 3 0.5\n", "line 2: point id 1 is used twice"}),
    [](const auto& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace glint
