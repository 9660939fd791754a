// A small hand-written COLMAP model in text form, and field-by-field model comparison.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "io/colmap_model.h"

namespace glint::test {

// Two cameras (one of each accepted model), three images (one without 2D points, one
// named with a space), four points; comments, blank lines and CRLF line ends as COLMAP
// and hand edits leave them.
inline ColmapFiles smallColmapText() {
  ColmapFiles files;
  files.cameras =
      "# Camera list with one line of data per camera:\n"
      "#   CAMERA_ID, MODEL, WIDTH, HEIGHT, PARAMS[]\n"
      "\n"
      "7 PINHOLE 640 480 500.5 501.25 320.5 239.75\r\n"
      "  2 SIMPLE_PINHOLE 320 200 300 160 100\n";
  files.images =
      "# Image list with two lines of data per image:\n"
      "3 0.5 0.5 -0.5 0.5 1.5 -2 0.25 7 frames/b.png\n"
      "10.5 20.25 4 30 40 -1\n"
      "1 1 0 0 0 0 0 4 2 frames/a.png\n"
      "\n"
      "9 0.9238795325112867 0 0.3826834323650898 0 -1 0.5 3 7 frames/c d.png\n"
      "1 2 18446744073709551614\n";
  files.points =
      "# 3D point list with one line of data per point:\n"
      "4 1 2 3 255 128 0 0.5 3 0 1 1\n"
      "18446744073709551615 -1 -2 -3 0 0 0 -1\n"
      "5 0.125 0.25 0.5 10 20 30 1.25 9 0\n"
      "6 1e-3 -4.5e2 7 1 2 3 0\n";
  return files;
}

inline void expectSameModel(const ColmapModel& a, const ColmapModel& b) {
  ASSERT_EQ(a.cameras.size(), b.cameras.size());
  for (size_t i = 0; i < a.cameras.size(); ++i) {
    EXPECT_EQ(a.cameras[i].id, b.cameras[i].id);
    EXPECT_EQ(a.cameras[i].model, b.cameras[i].model);
    EXPECT_EQ(a.cameras[i].width, b.cameras[i].width);
    EXPECT_EQ(a.cameras[i].height, b.cameras[i].height);
    EXPECT_EQ(a.cameras[i].params, b.cameras[i].params);
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (size_t i = 0; i < a.images.size(); ++i) {
    const ColmapImage &x = a.images[i], &y = b.images[i];
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.qvec.w, y.qvec.w);
    EXPECT_EQ(x.qvec.x, y.qvec.x);
    EXPECT_EQ(x.qvec.y, y.qvec.y);
    EXPECT_EQ(x.qvec.z, y.qvec.z);
    EXPECT_EQ(x.tvec, y.tvec);
    EXPECT_EQ(x.cameraId, y.cameraId);
    EXPECT_EQ(x.name, y.name);
    ASSERT_EQ(x.points2D.size(), y.points2D.size()) << x.name;
    for (size_t k = 0; k < x.points2D.size(); ++k) {
      EXPECT_EQ(x.points2D[k].xy.x, y.points2D[k].xy.x);
      EXPECT_EQ(x.points2D[k].xy.y, y.points2D[k].xy.y);
      EXPECT_EQ(x.points2D[k].point3DId, y.points2D[k].point3DId);
    }
  }
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].id, b.points[i].id);
    EXPECT_EQ(a.points[i].xyz, b.points[i].xyz);
    EXPECT_EQ(a.points[i].rgb, b.points[i].rgb);
    EXPECT_EQ(a.points[i].error, b.points[i].error);
    ASSERT_EQ(a.points[i].track.size(), b.points[i].track.size()) << a.points[i].id;
    for (size_t k = 0; k < a.points[i].track.size(); ++k) {
      EXPECT_EQ(a.points[i].track[k].imageId, b.points[i].track[k].imageId);
      EXPECT_EQ(a.points[i].track[k].point2DIndex, b.points[i].track[k].point2DIndex);
    }
  }
}

}  // namespace glint::test
