// Which COLMAP cameras Glint accepts, and the undistortion command for the others.
#include "io/colmap_camera_models.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/error.h"
#include "io/colmap_model.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

ColmapCamera camera(const std::string& model, std::vector<double> params) {
  return ColmapCamera{1, model, 640, 480, std::move(params)};
}

std::string refusal(const ColmapCamera& c, const std::filesystem::path& folder = {}) {
  try {
    colmapPinholeIntrinsics(c, "sparse/0/cameras.txt", "", folder);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ColmapCameraModels, TableMatchesCOLMAPsIdsAndParameterCounts) {
  const char* names[] = {"SIMPLE_PINHOLE", "PINHOLE", "SIMPLE_RADIAL", "RADIAL", "OPENCV", "OPENCV_FISHEYE",
                         "FULL_OPENCV", "FOV", "SIMPLE_RADIAL_FISHEYE", "RADIAL_FISHEYE", "THIN_PRISM_FISHEYE"};
  const int counts[] = {3, 4, 4, 5, 8, 8, 12, 5, 4, 5, 12};
  for (int id = 0; id < 11; ++id) {
    const ColmapCameraModel* model = findColmapCameraModel(id);
    ASSERT_NE(model, nullptr) << id;
    EXPECT_STREQ(model->name, names[id]);
    EXPECT_EQ(model->numParams, counts[id]) << names[id];
    EXPECT_EQ(findColmapCameraModel(names[id]), model);
  }
  EXPECT_EQ(findColmapCameraModel(11), nullptr);
  EXPECT_EQ(findColmapCameraModel(-1), nullptr);
  EXPECT_EQ(findColmapCameraModel("pinhole"), nullptr);
}

TEST(ColmapCameraModels, PinholesAndZeroDistortionAreAccepted) {
  PinholeIntrinsics k = colmapPinholeIntrinsics(camera("PINHOLE", {500, 510, 320, 240}), "c", "");
  EXPECT_EQ(k.fx, 500);
  EXPECT_EQ(k.fy, 510);
  EXPECT_EQ(k.cx, 320);
  EXPECT_EQ(k.cy, 240);
  k = colmapPinholeIntrinsics(camera("SIMPLE_PINHOLE", {500, 321, 241}), "c", "");
  EXPECT_EQ(k.fx, 500);
  EXPECT_EQ(k.fy, 500);
  EXPECT_EQ(k.cx, 321);
  EXPECT_EQ(k.cy, 241);
  k = colmapPinholeIntrinsics(camera("SIMPLE_RADIAL", {400, 300, 200, 0}), "c", "");
  EXPECT_EQ(k.fy, 400);
  EXPECT_EQ(k.cx, 300);
  k = colmapPinholeIntrinsics(camera("OPENCV", {1, 2, 3, 4, 0, 0, 0, -0.0}), "c", "");
  EXPECT_EQ(k.fy, 2);
  EXPECT_EQ(k.cy, 4);
  EXPECT_EQ(colmapPinholeIntrinsics(camera("FULL_OPENCV", {1, 2, 3, 4, 0, 0, 0, 0, 0, 0, 0, 0}), "c", "").cx, 3);
  EXPECT_EQ(colmapPinholeIntrinsics(camera("RADIAL", {5, 3, 4, 0, 0}), "c", "").fx, 5);
}

TEST(ColmapCameraModels, DistortedModelsAreRefusedWithTheUndistortionCommand) {
  const ColmapCamera distorted[] = {
      camera("SIMPLE_RADIAL", {400, 300, 200, -0.02}),
      camera("RADIAL", {400, 300, 200, 0, 0.01}),
      camera("OPENCV", {400, 400, 300, 200, 0.1, 0, 0, 0}),
      camera("FULL_OPENCV", {400, 400, 300, 200, 0, 0, 0, 0, 0, 0, 0, 1e-9}),
      // Fisheye and FOV projections are not a pinhole's even with zero coefficients.
      camera("OPENCV_FISHEYE", {400, 400, 300, 200, 0, 0, 0, 0}),
      camera("FOV", {400, 400, 300, 200, 0}),
      camera("SIMPLE_RADIAL_FISHEYE", {400, 300, 200, 0}),
      camera("RADIAL_FISHEYE", {400, 300, 200, 0, 0}),
      camera("THIN_PRISM_FISHEYE", {400, 400, 300, 200, 0, 0, 0, 0, 0, 0, 0, 0}),
  };
  for (const ColmapCamera& c : distorted) {
    std::string message = refusal(c, "scan/sparse/0");
    EXPECT_EQ(message.rfind("sparse/0/cameras.txt: camera 1 uses the " + c.model + " model", 0), 0u) << message;
    EXPECT_NE(message.find("colmap image_undistorter --image_path <images folder> --input_path scan/sparse/0 "
                           "--output_path <new folder> --output_type COLMAP"),
              std::string::npos)
        << message;
  }
  EXPECT_NE(refusal(distorted[0]).find("(-0.02)"), std::string::npos);
  EXPECT_NE(refusal(distorted[2]).find("lens distortion (0.1, 0, 0, 0)"), std::string::npos) << refusal(distorted[2]);
  EXPECT_NE(refusal(camera("PINHOLE", {0, 1, 1, 1})).find("focal length that is not a positive"), std::string::npos);
}

TEST(ColmapCameraModels, CommandFillsInTheProjectsPaths) {
  test::TempFolder folder;
  std::filesystem::create_directories(folder / "project/images");
  std::filesystem::create_directories(folder / "project/sparse/0");
  std::string project = (folder / "project").string();
  std::string expected = "colmap image_undistorter --image_path " + project + "/images --input_path " + project +
                         "/sparse/0 --output_path " + project + "/undistorted --output_type COLMAP";
  EXPECT_EQ(undistortionCommand(folder / "project/sparse/0"), expected);
  EXPECT_EQ(undistortionCommand(folder / "project/sparse/0/"), expected);
  EXPECT_NE(undistortionCommand(folder / "project/sparse").find("--image_path " + project + "/images"),
            std::string::npos);
  EXPECT_EQ(undistortionCommand({}),
            "colmap image_undistorter --image_path <images folder> --input_path <model folder> --output_path "
            "<new folder> --output_type COLMAP");

  // readColmapModel refuses the distorted model with the filled-in command.
  ColmapModel model;
  model.cameras.push_back(camera("OPENCV", {400, 400, 300, 200, 0.1, 0.01, 0, 0}));
  writeColmapModelBinary(folder / "project/sparse/0", model);
  try {
    readColmapModel(folder / "project/sparse/0");
    FAIL() << "distorted model accepted";
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_EQ(message.rfind(project + "/sparse/0/cameras.bin: record 0: camera 1 uses the OPENCV model", 0), 0u)
        << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
  // glint capture reads COLMAP's own distorted output before undistorting it.
  ColmapModel asStored = readColmapModelAnyCamera(folder / "project/sparse/0");
  ASSERT_EQ(asStored.cameras.size(), 1u);
  EXPECT_EQ(asStored.cameras[0].model, "OPENCV");
  EXPECT_EQ(asStored.cameras[0].params[4], 0.1);
  // In text form the message names the camera's line.
  std::filesystem::remove(folder / "project/sparse/0/cameras.bin");
  writeColmapModelText(folder / "project/sparse/0", model);
  try {
    readColmapModel(folder / "project/sparse/0");
    FAIL() << "distorted model accepted";
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_EQ(message.rfind(project + "/sparse/0/cameras.txt: line 4: camera 1 uses the OPENCV model", 0), 0u)
        << message;
  }
}

}  // namespace
}  // namespace glint

namespace glint {
namespace {

TEST(ColmapCameraModels, LensDistortionIsAnyDistortionParameterOrAFisheye) {
  EXPECT_FALSE(hasLensDistortion(camera("PINHOLE", {500, 500, 320, 240})));
  EXPECT_FALSE(hasLensDistortion(camera("SIMPLE_PINHOLE", {500, 320, 240})));
  EXPECT_FALSE(hasLensDistortion(camera("OPENCV", {500, 500, 320, 240, 0, 0, 0, 0})));
  EXPECT_TRUE(hasLensDistortion(camera("OPENCV", {500, 500, 320, 240, 0, 0, 1e-9, 0})));
  EXPECT_TRUE(hasLensDistortion(camera("SIMPLE_RADIAL", {500, 320, 240, -0.05})));
  EXPECT_TRUE(hasLensDistortion(camera("OPENCV_FISHEYE", {500, 500, 320, 240, 0, 0, 0, 0})));
  EXPECT_TRUE(hasLensDistortion(camera("NO_SUCH_MODEL", {500, 500, 320, 240})));
  EXPECT_TRUE(hasLensDistortion(camera("PINHOLE", {500, 500, 320})));  // parameters missing
}

}  // namespace
}  // namespace glint
