// A capture of a known scene for tests: the floor z = 0 (a checker of two colours, a rough
// half and a smooth one, metal in one quadrant) seen from ten cameras with fx != fy and an
// off-centre principal point, written by writeCapture with its exact buffers.
#pragma once

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "math/rng.h"
#include "scene/capture_writer.h"

namespace glint::test {

// The floor z = 0: a checker of two colours, glossy dark tiles, metal in the quadrant x, y > 0.
struct Floor {
  static Rgb diffuse(const Vec3d& p) {
    const bool dark = (int(std::floor(p.x * 3.0)) + int(std::floor(p.y * 3.0))) % 2 != 0;
    return dark ? Rgb(0.08f, 0.06f, 0.05f) : Rgb(0.6f, 0.5f, 0.3f);
  }
  static float roughness(const Vec3d& p) { return p.x > 0 ? 0.2f : 0.7f; }
  static Rgb f0(const Vec3d& p) { return p.x > 0 && p.y > 0 ? Rgb(0.9f, 0.6f, 0.3f) : Rgb(0.04f); }
};

// A camera looking down at the floor, fx != fy and an off-centre principal point.
inline Camera floorCamera(int i, int width, int height) {
  const double a = 0.7 * i;
  Camera c;
  c.cameraToWorld = Mat4::lookAt(Vec3d(2.0 * std::cos(a), 2.0 * std::sin(a), 1.5 + 0.05 * i),
                                 Vec3d(0.1 * std::sin(a), 0.0, 0.0), Vec3d(0, 0, 1));
  c.width = width, c.height = height;
  c.fx = 0.9 * width, c.fy = 0.85 * width, c.cx = 0.48 * width, c.cy = 0.53 * height;
  return c;
}

inline ViewBuffers floorBuffers(const Camera& camera) {
  ViewBuffers b = ViewBuffers::allocate(camera.width, camera.height);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      Ray ray = camera.generateRay(x + 0.5, y + 0.5);
      GLINT_CHECK(ray.direction.z < 0.0, "every pixel must see the floor");
      const double t = -ray.origin.z / ray.direction.z;
      const Vec3d p = ray.origin + t * ray.direction;
      const Rgb specular(0.05f);
      b[Buffer::Diffuse].setRgb(x, y, Floor::diffuse(p));
      b[Buffer::Specular].setRgb(x, y, specular);
      b[Buffer::Render].setRgb(x, y, Floor::diffuse(p) + specular);
      b[Buffer::Depth].at(x, y) = float(t);
      b[Buffer::Normal].setRgb(x, y, Rgb(0.0f, 0.0f, 1.0f));
      b[Buffer::Roughness].at(x, y) = Floor::roughness(p);
      b[Buffer::F0].setRgb(x, y, Floor::f0(p));
    }
  return b;
}

struct WrittenCapture {
  std::vector<CaptureWriteView> views;
};

// 10 views (the last one smaller: views may differ in size) and 400 points on the floor.
inline WrittenCapture writeFloorCapture(const std::filesystem::path& root, const std::string& extension = ".png") {
  WrittenCapture w;
  for (int i = 0; i < 10; ++i) {
    CaptureWriteView v;
    char name[32];
    std::snprintf(name, sizeof(name), "view_%04d%s", i, extension.c_str());
    v.imageName = name;
    v.camera = i == 9 ? floorCamera(i, 40, 30) : floorCamera(i, 48, 36);
    v.buffers = floorBuffers(v.camera);
    w.views.push_back(std::move(v));
  }
  std::vector<Vec3d> points;
  std::vector<Rgb> colours;
  Rng rng(3);
  for (int i = 0; i < 400; ++i) {
    Vec3d p(rng.uniformDouble() * 3.0 - 1.5, rng.uniformDouble() * 3.0 - 1.5, 0.0);
    points.push_back(p);
    colours.push_back(Floor::diffuse(p));
  }
  writeCapture(root, w.views, points, colours);
  return w;
}

}  // namespace glint::test
