// A small dataset on disk whose training cameras look down at the plane z = 0: depth is the
// exact ray-plane distance and the diffuse colour a known function of the hit point, so
// the tests of initialisation and culling know where every surface point lies.
#pragma once

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "scene/dataset.h"

namespace glint::test {

constexpr int kPlaneWidth = 16;
constexpr int kPlaneHeight = 12;

// Linear diffuse colour of the plane at (x, y): smooth, positive, distinct per channel.
inline Rgb planeColour(const Vec3d& p) {
  return Rgb(float(0.5 + 0.25 * std::sin(p.x)), float(0.4 + 0.2 * std::cos(p.y)), float(0.3 + 0.05 * p.x * p.y));
}

inline DatasetView planeView(const std::string& split, int index, const Vec3d& eye, const Vec3d& target) {
  char file[64];
  std::snprintf(file, sizeof file, "%s/render/render_%04d", split.c_str(), index);
  return {file, Camera::fromFieldOfView(Mat4::lookAt(eye, target, Vec3d(0, 1, 0)), 0.9, kPlaneWidth, kPlaneHeight), {}};
}

// Buffers of a camera seeing the plane z = 0: rays that miss it (or hit it behind the
// camera) have no surface (depth 0). When `noSurface` is set, every pixel misses.
inline ViewBuffers planeBuffers(const Camera& camera, bool noSurface = false) {
  ViewBuffers b = ViewBuffers::allocate(camera.width, camera.height);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      Ray ray = camera.generateRay(x + 0.5, y + 0.5);
      double t = -ray.origin.z / ray.direction.z;
      if (noSurface || !(t > 0.0)) {
        b[Buffer::Diffuse].setRgb(x, y, Rgb(0.2f));  // the environment
        b[Buffer::Render].setRgb(x, y, Rgb(0.2f));
        continue;
      }
      Rgb diffuse = planeColour(ray.origin + ray.direction * t);
      b[Buffer::Diffuse].setRgb(x, y, diffuse);
      b[Buffer::Render].setRgb(x, y, diffuse);
      b[Buffer::Depth].at(x, y) = float(t);
      b[Buffer::Normal].setRgb(x, y, Rgb(0, 0, 1));
      b[Buffer::Roughness].at(x, y) = 0.5f;
      b[Buffer::F0].setRgb(x, y, Rgb(0.04f));
    }
  return b;
}

struct PlaneDataset {
  DatasetSplit train;
  std::vector<ViewBuffers> trainBuffers;
};

// Writes training views from the given eyes (all looking at the origin; with
// noSurfaceView >= 0, that view sees nothing) and one test view, as EXR.
inline PlaneDataset writePlaneDataset(const std::filesystem::path& root, const std::vector<Vec3d>& eyes,
                                      int noSurfaceView = -1) {
  PlaneDataset data;
  data.train.name = "train";
  data.train.width = kPlaneWidth;
  data.train.height = kPlaneHeight;
  for (size_t i = 0; i < eyes.size(); ++i) {
    data.train.views.push_back(planeView("train", int(i), eyes[i], Vec3d(0.1 * double(i), 0, 0)));
    data.trainBuffers.push_back(planeBuffers(data.train.camera(i), int(i) == noSurfaceView));
    writeViewBuffers(root, data.train.views.back(), data.trainBuffers.back(), ImageFormat::Exr);
  }
  writeTransforms(root, data.train);
  DatasetSplit test = data.train;
  test.name = "test";
  test.views = {planeView("test", 0, Vec3d(1, 1, 3), Vec3d(0, 0, 0))};
  writeViewBuffers(root, test.views[0], planeBuffers(test.camera(0)), ImageFormat::Exr);
  writeTransforms(root, test);
  return data;
}

// Eyes on a ring above the plane, all seeing it.
inline std::vector<Vec3d> ringOfEyes(int count, double radius = 1.5, double height = 3.0) {
  std::vector<Vec3d> eyes;
  for (int i = 0; i < count; ++i) {
    double angle = 2.0 * 3.14159265358979 * i / count;
    eyes.push_back(Vec3d(radius * std::cos(angle), radius * std::sin(angle), height + 0.1 * i));
  }
  return eyes;
}

}  // namespace glint::test
