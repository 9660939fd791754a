// transforms_{split}.json: accepted variations, one clear error per kind of mistake, and
// a lossless, readable writer.
#include "io/transforms_json.h"

#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

const char* kBlenderIdentityRows = "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]";

std::string blenderFrameJson(const std::string& filePath, const std::string& matrix = kBlenderIdentityRows) {
  return R"({"file_path": ")" + filePath + R"(", "transform_matrix": )" + matrix + "}";
}

std::string blenderFileJson(const std::string& frames, const std::string& angle = "0.69") {
  return R"({"camera_angle_x": )" + angle + R"(, "frames": [)" + frames + "]}";
}

// The message of the Error parsing text throws, or "" if it parses.
std::string blenderParseError(const std::string& text) {
  try {
    parseTransformsJson(text, "transforms_train.json");
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), "transforms_train.json");
    return e.what();
  }
  return "";
}

TEST(TransformsJson, ParsesBlenderStyleFiles) {
  std::string text = R"({"camera_angle_x": 0.6911112070083618, "aabb": [0, 1], "frames": [
      {"file_path": "./train/render/render_0001.png", "rotation": 0.012566, "fl_x": 1111.1,
       "transform_matrix": [[0, -1, 0, 2.5], [1, 0, 0, -1], [0, 0, 1, 4], [0, 0, 0, 1]]},
      {"file_path": "train/render/render_0000", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]},
      {"file_path": "./train/render/render_0002.EXR", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}
  ]})";
  TransformsFile file = parseTransformsJson(text, "transforms_train.json");
  EXPECT_DOUBLE_EQ(file.cameraAngleX, 0.6911112070083618);
  ASSERT_EQ(file.frames.size(), 3u);
  // Sorted by file_path, "./" and extensions stripped.
  EXPECT_EQ(file.frames[0].filePath, "train/render/render_0000");
  EXPECT_EQ(file.frames[1].filePath, "train/render/render_0001");
  EXPECT_EQ(file.frames[2].filePath, "train/render/render_0002");
  const auto& m = file.frames[1].transformMatrix.m;
  EXPECT_EQ(m[0][1], -1.0);
  EXPECT_EQ(m[0][3], 2.5);
  EXPECT_EQ(m[1][0], 1.0);
  EXPECT_EQ(m[2][3], 4.0);
}

TEST(TransformsJson, AcceptsSlightlyImpreciseRotationsAndAnEmptyFrameList) {
  // Six printed digits leave rotations off by ~1e-6.
  std::string rows = "[[0.707107,-0.707107,0,0],[0.707107,0.707107,0,0],[0,0,1,0],[0,0,0,1.00001]]";
  EXPECT_EQ(blenderParseError(blenderFileJson(blenderFrameJson("a/render/render_0", rows))), "");
  EXPECT_TRUE(parseTransformsJson(blenderFileJson(""), "x.json").frames.empty());
}

struct BadBlenderFile {
  const char* name;
  std::string text;
  const char* expected;  // part of the message
};

void PrintTo(const BadBlenderFile& file, std::ostream* out) { *out << file.name; }

class TransformsJsonErrors : public testing::TestWithParam<BadBlenderFile> {};

TEST_P(TransformsJsonErrors, NameTheFileFrameAndKey) {
  std::string message = blenderParseError(GetParam().text);
  EXPECT_NE(message.find("transforms_train.json: "), std::string::npos) << message;
  EXPECT_NE(message.find(GetParam().expected), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    Mistakes, TransformsJsonErrors,
    testing::Values(
        BadBlenderFile{"Syntax", R"({"camera_angle_x": 0.7, "frames": [})", "is not valid JSON at byte 36"},
        BadBlenderFile{"NaN", blenderFileJson(blenderFrameJson("r", "[[NaN,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]")), "must be finite"},
        BadBlenderFile{"Overflow", blenderFileJson(blenderFrameJson("r", "[[1e999,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]")),
                "must be finite"},
        BadBlenderFile{"NotAnObject", "[1, 2]", "must hold a JSON object"},
        BadBlenderFile{"MissingAngle", R"({"frames": []})", "camera_angle_x is missing"},
        BadBlenderFile{"AngleNotANumber", blenderFileJson("", "\"wide\""), "camera_angle_x must be a number"},
        BadBlenderFile{"AngleZero", blenderFileJson("", "0"), "camera_angle_x is 0, but must lie in [0.000175, pi) radians"},
        BadBlenderFile{"AngleTiny", blenderFileJson("", "1e-300"), "camera_angle_x is 1e-300, but must lie in [0.000175, pi)"},
        BadBlenderFile{"AngleTooWide", blenderFileJson("", "3.2"), "must lie in [0.000175, pi)"},
        BadBlenderFile{"MissingFrames", R"({"camera_angle_x": 0.7})", "frames is missing"},
        BadBlenderFile{"FramesNotArray", R"({"camera_angle_x": 0.7, "frames": {}})", "frames must be an array"},
        BadBlenderFile{"FrameNotObject", blenderFileJson(blenderFrameJson("a") + ", 3"), "frame 1: must be an object"},
        BadBlenderFile{"MissingFilePath", blenderFileJson(R"({"transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})"),
                "frame 0: file_path is missing"},
        BadBlenderFile{"FilePathNotString", blenderFileJson(R"({"file_path": 7, "transform_matrix": []})"),
                "frame 0: file_path must be a string"},
        BadBlenderFile{"EmptyFilePath", blenderFileJson(blenderFrameJson("./")), "frame 0: file_path is empty"},
        BadBlenderFile{"AbsoluteFilePath", blenderFileJson(blenderFrameJson("/data/r_0")), "must be relative to the dataset folder"},
        BadBlenderFile{"ParentFilePath", blenderFileJson(blenderFrameJson("../other/train/render/render_0")),
                "frame 0: file_path \"../other/train/render/render_0\" leaves the dataset folder"},
        BadBlenderFile{"InnerParentFilePath", blenderFileJson(blenderFrameJson("train/render/../../../x/render/render_0")),
                "leaves the dataset folder"},
        BadBlenderFile{"MissingMatrix", blenderFileJson(blenderFrameJson("a") + R"(, {"file_path": "b"})"),
                "frame 1: transform_matrix is missing"},
        BadBlenderFile{"ThreeRows", blenderFileJson(blenderFrameJson("a") + "," + blenderFrameJson("b") + "," +
                                      blenderFrameJson("c", "[[1,0,0,0],[0,1,0,0],[0,0,1,0]]")),
                "frame 2: transform_matrix must be 4 rows of 4 numbers"},
        BadBlenderFile{"ShortRow", blenderFileJson(blenderFrameJson("a", "[[1,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]")),
                "frame 0: transform_matrix must be 4 rows of 4 numbers"},
        BadBlenderFile{"StringEntry", blenderFileJson(blenderFrameJson("a", "[[1,0,0,\"0\"],[0,1,0,0],[0,0,1,0],[0,0,0,1]]")),
                "must be 4 rows of 4 numbers"},
        BadBlenderFile{"NotAffine", blenderFileJson(blenderFrameJson("a", "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0.1,1]]")),
                "frame 0: transform_matrix must be affine: its last row must be 0 0 0 1"},
        BadBlenderFile{"Scaled", blenderFileJson(blenderFrameJson("a", "[[2,0,0,0],[0,2,0,0],[0,0,2,0],[0,0,0,1]]")),
                "frame 0: transform_matrix must be a rigid camera pose"},
        BadBlenderFile{"Sheared", blenderFileJson(blenderFrameJson("a", "[[1,0.1,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]")),
                "not a rotation"},
        BadBlenderFile{"Mirrored", blenderFileJson(blenderFrameJson("a", "[[-1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]")),
                "reflection (determinant -1)"},
        BadBlenderFile{"DuplicatePath", blenderFileJson(blenderFrameJson("./x/render/render_0.png") + "," + blenderFrameJson("x/render/render_0")),
                "two frames have the same file_path \"x/render/render_0\""}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(TransformsJson, WriterRoundTripsExactlyWithOneLinePerMatrixRow) {
  TransformsFile file;
  file.cameraAngleX = 0.6911112070083618;
  Mat4 pose = Mat4::rotation(0.9, 0.1, -0.3, 0.2) * Mat4::identity();
  pose.m[0][3] = 1.0 / 3.0, pose.m[1][3] = -4.000000000000001, pose.m[2][3] = 1e-17;
  file.frames.push_back({"test/render/render_0001", pose});
  file.frames.push_back({"test/render/render_0000", Mat4::identity()});

  test::TempFolder folder;
  writeTransformsJson(folder / "transforms_test.json", file);
  std::string text = test::readBytes(folder / "transforms_test.json");
  EXPECT_NE(text.find("\n        [1.0, 0.0, 0.0, 0.0],\n"), std::string::npos) << text;
  EXPECT_NE(text.find("\n  \"camera_angle_x\": 0.6911112070083618,\n"), std::string::npos) << text;

  TransformsFile read = readTransformsJson(folder / "transforms_test.json");
  EXPECT_EQ(read.cameraAngleX, file.cameraAngleX);
  ASSERT_EQ(read.frames.size(), 2u);
  // The reader sorts; the writer keeps the given order.
  EXPECT_EQ(read.frames[0].filePath, "test/render/render_0000");
  EXPECT_EQ(read.frames[1].filePath, "test/render/render_0001");
  EXPECT_EQ(read.frames[1].transformMatrix.m, pose.m);
  EXPECT_LT(text.find("render_0001"), text.find("render_0000"));

  TransformsFile empty;
  empty.cameraAngleX = 1.0;
  EXPECT_TRUE(parseTransformsJson(formatTransformsJson(empty), "x").frames.empty());
}

TEST(TransformsJson, MissingFileIsAnErrorNamingIt) {
  test::TempFolder folder;
  try {
    readTransformsJson(folder / "transforms_train.json");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("transforms_train.json: file not found"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace glint
