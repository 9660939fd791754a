// nerfstudio's transforms.json: global and per-frame intrinsics, the accepted variations,
// one clear error per kind of mistake, and a lossless writer.
#include "io/nerfstudio_transforms.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

const char* kIdentityRows = "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]";

std::string frameJson(const std::string& filePath, const std::string& extra = "") {
  return R"({"file_path": ")" + filePath + R"(", "transform_matrix": )" + kIdentityRows + extra + "}";
}

// A file with pinhole intrinsics at the top level unless `globals` replaces them.
std::string fileJson(const std::string& frames,
                     const std::string& globals = R"("w": 640, "h": 480, "fl_x": 500, "fl_y": 510, "cx": 320, "cy": 240)") {
  return "{" + globals + (globals.empty() ? "" : ", ") + R"("frames": [)" + frames + "]}";
}

std::string parseError(const std::string& text) {
  try {
    parseNerfstudioTransforms(text, "transforms.json");
  } catch (const Error& e) {
    EXPECT_EQ(e.file(), "transforms.json");
    return e.what();
  }
  return "";
}

TEST(NerfstudioTransforms, ParsesWhatNsProcessDataWrites) {
  // The layout of ns-process-data's output for a PINHOLE COLMAP camera (OPENCV, k = 0).
  std::string text = R"({
    "w": 960, "h": 540, "fl_x": 800.5, "fl_y": 801.5, "cx": 480.25, "cy": 270.75,
    "k1": 0.0, "k2": 0.0, "p1": 0.0, "p2": 0.0, "camera_model": "OPENCV",
    "frames": [
      {"file_path": "images/frame_00002.png", "colmap_im_id": 2,
       "transform_matrix": [[0, -1, 0, 2.5], [1, 0, 0, -1], [0, 0, 1, 4], [0, 0, 0, 1]],
       "depth_file_path": "depths/frame_00002.png", "mask_path": "./masks/frame_00002.png"},
      {"file_path": "./images/frame_00001.png", "colmap_im_id": 1,
       "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}
    ],
    "applied_transform": [[1, 0, 0, 0], [0, 0, 1, 0], [-0, -1, -0, -0]],
    "ply_file_path": "sparse_pc.ply"
  })";
  NerfstudioTransforms file = parseNerfstudioTransforms(text, "transforms.json");
  ASSERT_EQ(file.frames.size(), 2u);
  // Sorted by file_path, "./" dropped, extensions kept.
  EXPECT_EQ(file.frames[0].filePath, "images/frame_00001.png");
  EXPECT_EQ(file.frames[1].filePath, "images/frame_00002.png");
  const NerfstudioFrame& f = file.frames[1];
  EXPECT_EQ(f.width, 960);
  EXPECT_EQ(f.height, 540);
  EXPECT_EQ(f.fx, 800.5);
  EXPECT_EQ(f.fy, 801.5);
  EXPECT_EQ(f.cx, 480.25);
  EXPECT_EQ(f.cy, 270.75);
  EXPECT_EQ(f.transformMatrix.m[0][1], -1.0);
  EXPECT_EQ(f.transformMatrix.m[2][3], 4.0);
  EXPECT_EQ(f.depthFilePath, "depths/frame_00002.png");
  EXPECT_EQ(f.maskPath, "masks/frame_00002.png");
  EXPECT_EQ(file.frames[0].depthFilePath, "");
  EXPECT_TRUE(file.hasAppliedTransform);
  EXPECT_EQ(file.appliedTransform.m[1][2], 1.0);
  EXPECT_EQ(file.appliedTransform.m[2][1], -1.0);
  EXPECT_EQ(file.appliedTransform.m[3][3], 1.0);
  EXPECT_EQ(file.plyFilePath, "sparse_pc.ply");
}

TEST(NerfstudioTransforms, FramesOverrideGlobalsAndAnglesAndCentresFillIn) {
  std::string frames = frameJson("a.png", R"(, "fl_x": 100, "w": 200, "h": 100, "cx": 99.5)") + "," +
                       frameJson("b.png", R"(, "camera_angle_x": 1.5)") + "," + frameJson("c.png");
  NerfstudioTransforms file =
      parseNerfstudioTransforms(fileJson(frames, R"("w": 640, "h": 480, "camera_angle_x": 0.9)"), "t.json");
  ASSERT_EQ(file.frames.size(), 3u);
  const NerfstudioFrame &a = file.frames[0], &b = file.frames[1], &c = file.frames[2];
  EXPECT_EQ(a.width, 200);
  EXPECT_EQ(a.fx, 100);
  EXPECT_EQ(a.fy, 100);  // fl_y defaults to fl_x
  EXPECT_EQ(a.cx, 99.5);
  EXPECT_EQ(a.cy, 50);   // the image centre
  EXPECT_DOUBLE_EQ(b.fx, 320 / std::tan(0.75));
  EXPECT_DOUBLE_EQ(c.fx, 320 / std::tan(0.45));
  EXPECT_EQ(c.cx, 320);
  EXPECT_EQ(c.cy, 240);
  EXPECT_FALSE(file.hasAppliedTransform);
  EXPECT_EQ(file.appliedTransform.m, Mat4::identity().m);

  file = parseNerfstudioTransforms(fileJson(frameJson("d"), R"("w": 64, "h": 32, "fl_x": 50, "camera_angle_y": 1.0)"),
                                   "t.json");
  EXPECT_DOUBLE_EQ(file.frames[0].fy, 16 / std::tan(0.5));
  EXPECT_TRUE(parseNerfstudioTransforms(fileJson(""), "t.json").frames.empty());
}

struct BadFile {
  const char* name;
  std::string text;
  const char* expected;  // part of the message
};

void PrintTo(const BadFile& file, std::ostream* out) { *out << file.name; }

class NerfstudioTransformsErrors : public testing::TestWithParam<BadFile> {};

TEST_P(NerfstudioTransformsErrors, NameTheFileFrameAndKey) {
  std::string message = parseError(GetParam().text);
  EXPECT_EQ(message.rfind("transforms.json: ", 0), 0u) << message;
  EXPECT_NE(message.find(GetParam().expected), std::string::npos) << message;
}

const std::string kTwoFrames = frameJson("a") + ",";

INSTANTIATE_TEST_SUITE_P(
    Mistakes, NerfstudioTransformsErrors,
    testing::Values(
        BadFile{"Syntax", R"({"frames": [})", "is not valid JSON at byte"},
        BadFile{"Overflow", fileJson("", R"("w": 1e999)"), "must be finite"},
        BadFile{"NotAnObject", "[]", "must hold a JSON object"},
        BadFile{"MissingFrames", R"({"w": 4})", "frames is missing"},
        BadFile{"MissingWidth", fileJson(frameJson("a"), R"("h": 4, "fl_x": 4)"), "frame 0: w is missing"},
        BadFile{"FractionalHeight", fileJson(frameJson("a"), R"("w": 4, "h": 4.5, "fl_x": 4)"),
                "h is 4.5, but must be a whole number of pixels"},
        BadFile{"FrameHeight", fileJson(kTwoFrames + frameJson("b", R"(, "h": 0)")),
                "frame 1: h is 0, but must be a whole number"},
        BadFile{"MissingFocal", fileJson(frameJson("a"), R"("w": 4, "h": 4)"), "frame 0: fl_x is missing"},
        BadFile{"NegativeFocal", fileJson(kTwoFrames + frameJson("b", R"(, "fl_y": -3)")),
                "frame 1: fl_y is -3, but must be a positive number"},
        BadFile{"FocalString", fileJson(frameJson("a", R"(, "fl_x": "500")")), "frame 0: fl_x must be a number"},
        BadFile{"AngleInDegrees", fileJson(frameJson("a"), R"("w": 4, "h": 4, "camera_angle_x": 50)"),
                "camera_angle_x is 50, but must lie in (0, pi) radians"},
        BadFile{"GlobalDistortion", fileJson(frameJson("a"), R"("w": 4, "h": 4, "fl_x": 4, "k1": -0.05)"),
                "k1 is -0.05: the images have lens distortion"},
        BadFile{"FrameDistortion", fileJson(kTwoFrames + frameJson("b", R"(, "p2": 0.001)")),
                "frame 1: p2 is 0.001: the images have lens distortion"},
        BadFile{"FisheyeDistortion", fileJson(frameJson("a", R"(, "k4": 1e-6)")), "frame 0: k4 is 1e-06"},
        BadFile{"DistortionSuggestsUndistorting", fileJson(frameJson("a", R"(, "k3": 0.2)")),
                "colmap image_undistorter"},
        BadFile{"FisheyeModel", fileJson(frameJson("a"), R"("w": 4, "h": 4, "fl_x": 4, "camera_model": "OPENCV_FISHEYE")"),
                "camera_model is \"OPENCV_FISHEYE\", but Glint traces pinhole cameras only"},
        BadFile{"FrameModel", fileJson(frameJson("a", R"(, "camera_model": "EQUIRECTANGULAR")")),
                "frame 0: camera_model is \"EQUIRECTANGULAR\""},
        BadFile{"MissingPath", fileJson(R"({"transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})"),
                "frame 0: file_path is missing"},
        BadFile{"AbsolutePath", fileJson(frameJson("/data/a.png")), "frame 0: file_path \"/data/a.png\" must be relative"},
        BadFile{"ParentPath", fileJson(frameJson("images/../../a.png")), "frame 0: file_path \"images/../../a.png\" leaves"},
        BadFile{"ParentMask", fileJson(frameJson("a", R"(, "mask_path": "../m.png")")),
                "frame 0: mask_path \"../m.png\" leaves"},
        BadFile{"DepthNotString", fileJson(frameJson("a", R"(, "depth_file_path": 3)")),
                "frame 0: depth_file_path must be a string"},
        BadFile{"MissingMatrix", fileJson(kTwoFrames + R"({"file_path": "b"})"), "frame 1: transform_matrix is missing"},
        BadFile{"ThreeRowPose", fileJson(R"({"file_path": "a", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0]]})"),
                "frame 0: transform_matrix must be 4 rows of 4 numbers"},
        BadFile{"ScaledPose",
                fileJson(R"({"file_path": "a", "transform_matrix": [[2,0,0,0],[0,2,0,0],[0,0,2,0],[0,0,0,1]]})"),
                "frame 0: transform_matrix must be a rigid camera pose"},
        BadFile{"MirroredPose",
                fileJson(R"({"file_path": "a", "transform_matrix": [[-1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]})"),
                "reflection"},
        BadFile{"NotAffine",
                fileJson(R"({"file_path": "a", "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,1,1]]})"),
                "transform_matrix must be affine"},
        BadFile{"AppliedShape", fileJson("", R"("applied_transform": [[1,0,0],[0,1,0],[0,0,1]])"),
                "applied_transform must be 3 or 4 rows of 4 numbers"},
        BadFile{"AppliedSingular", fileJson("", R"("applied_transform": [[1,0,0,0],[0,0,0,0],[0,0,1,0]])"),
                "applied_transform must be invertible"},
        BadFile{"DuplicatePath", fileJson(frameJson("./images/a.png") + "," + frameJson("images/a.png")),
                "two frames have the same file_path \"images/a.png\""}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(NerfstudioTransforms, WriterRoundTripsExactly) {
  NerfstudioTransforms file;
  NerfstudioFrame frame;
  frame.filePath = "images/b.png";
  frame.width = 1920, frame.height = 1080;
  frame.fx = 1500.0 / 3.0, frame.fy = 1501.1, frame.cx = 960.3, frame.cy = 0.1 + 0.2;
  frame.transformMatrix = Mat4::rotation(0.9, 0.1, -0.3, 0.2);
  frame.transformMatrix.m[0][3] = 1.0 / 3.0;
  frame.depthFilePath = "depths/b.png";
  file.frames.push_back(frame);
  frame.filePath = "images/a.png";
  frame.depthFilePath.clear();
  frame.maskPath = "masks/a.png";
  frame.width = 960;
  file.frames.push_back(frame);
  file.hasAppliedTransform = true;
  file.appliedTransform = Mat4::rotation(0.5, 0.5, 0.5, 0.5);
  file.plyFilePath = "sparse_pc.ply";

  test::TempFolder folder;
  writeNerfstudioTransforms(folder / "transforms.json", file);
  NerfstudioTransforms read = readNerfstudioTransforms(folder / "transforms.json");
  ASSERT_EQ(read.frames.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    const NerfstudioFrame &x = read.frames[i], &y = file.frames[1 - i];  // the reader sorts
    EXPECT_EQ(x.filePath, y.filePath);
    EXPECT_EQ(x.width, y.width);
    EXPECT_EQ(x.height, y.height);
    EXPECT_EQ(x.fx, y.fx);
    EXPECT_EQ(x.fy, y.fy);
    EXPECT_EQ(x.cx, y.cx);
    EXPECT_EQ(x.cy, y.cy);
    EXPECT_EQ(x.transformMatrix.m, y.transformMatrix.m);
    EXPECT_EQ(x.depthFilePath, y.depthFilePath);
    EXPECT_EQ(x.maskPath, y.maskPath);
  }
  EXPECT_TRUE(read.hasAppliedTransform);
  EXPECT_EQ(read.appliedTransform.m, file.appliedTransform.m);
  EXPECT_EQ(read.plyFilePath, "sparse_pc.ply");
}

TEST(NerfstudioTransforms, MissingFileIsAnErrorNamingIt) {
  test::TempFolder folder;
  try {
    readNerfstudioTransforms(folder / "transforms.json");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("transforms.json: file not found"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace glint
