// The viewer's camera: a dataset's view, off-centre principal point and fy != fx included,
// goes to the page and back to the same pinhole; bad fields are refused.
#include "app/viewer/viewer_camera.h"

#include <gtest/gtest.h>

#include "app/viewer/request_json.h"

namespace glint {
namespace {

TEST(ViewerCamera, ADatasetViewRoundTripsThroughThePage) {
  Camera view;
  view.cameraToWorld = Mat4::lookAt(Vec3d(1, -2, 0.5), Vec3d(0, 0, 0.2), Vec3d(0, 0, 1));
  view.width = 320, view.height = 240;
  view.fx = 300, view.fy = 280, view.cx = 150, view.cy = 131;
  const nlohmann::json sent = toJson(ViewerCamera::fromCamera(view));
  EXPECT_TRUE(sent.contains("principal_point"));
  Camera back = parseCameraRequest(sent).camera(320, 240);
  EXPECT_NEAR(back.fx, view.fx, 1e-9);
  EXPECT_NEAR(back.fy, view.fy, 1e-9);
  EXPECT_NEAR(back.cx, view.cx, 1e-9);
  EXPECT_NEAR(back.cy, view.cy, 1e-9);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(back.cameraToWorld.m[r][c], view.cameraToWorld.m[r][c], 1e-9);
  // At half the size the viewer renders the same view.
  Camera half = parseCameraRequest(sent).camera(160, 120);
  EXPECT_NEAR(half.fx, 150.0, 1e-9);
  EXPECT_NEAR(half.cy, 65.5, 1e-9);
}

TEST(ViewerCamera, CentredCamerasSendNoIntrinsicsAndBadOnesAreRefused) {
  const nlohmann::json centred = toJson(ViewerCamera{});
  EXPECT_FALSE(centred.contains("principal_point"));
  EXPECT_FALSE(centred.contains("pixel_aspect"));
  nlohmann::json bad = centred;
  bad["principal_point"] = {0.5};
  EXPECT_THROW(parseCameraRequest(bad), RequestError);
  bad["principal_point"] = {5.0, 0.5};
  EXPECT_THROW(parseCameraRequest(bad), RequestError);
  bad = centred;
  bad["pixel_aspect"] = 0.0;
  EXPECT_THROW(parseCameraRequest(bad), RequestError);
}

}  // namespace
}  // namespace glint
