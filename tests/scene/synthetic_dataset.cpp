// Deterministic synthetic datasets for the scene tests.
#include "scene/synthetic_dataset.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "io/point_cloud.h"

namespace glint::test {

ViewBuffers syntheticBuffers(int width, int height, int viewSeed) {
  ViewBuffers b = ViewBuffers::allocate(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float u = (x + 0.5f) / width, v = (y + 0.5f) / height, s = 0.1f * viewSeed;
      bool background = x == 0 || (x == width - 1 && y == 0);
      if (background) {
        // Rays that leave the scene see the environment: diffuse carries it, no G-buffer.
        b[Buffer::Diffuse].setRgb(x, y, Rgb(0.3f + u, 0.5f, 0.8f - 0.2f * v));
        b[Buffer::Render].setRgb(x, y, b[Buffer::Diffuse].rgb(x, y));
        b[Buffer::Depth].at(x, y) = x == 0 ? 0.0f : 1.0e10f;
        continue;
      }
      Rgb diffuse(2.5f * u + s, 1.5f * v, 0.2f + u * v);
      Rgb specular(0.9f * v, 0.4f * u + s, 0.05f);
      b[Buffer::Diffuse].setRgb(x, y, diffuse);
      b[Buffer::Specular].setRgb(x, y, specular);
      b[Buffer::Render].setRgb(x, y, diffuse + specular);
      b[Buffer::Depth].at(x, y) = 2.0f + u + 0.5f * v + s;
      b[Buffer::Normal].setRgb(x, y, normalize(Rgb(u - 0.5f, 0.3f - v, 0.8f)));
      b[Buffer::Roughness].at(x, y) = 0.05f + 0.9f * u * v;
      b[Buffer::F0].setRgb(x, y, Rgb(0.04f + 0.9f * u, 0.04f, 0.04f + 0.5f * v));
    }
  return b;
}

namespace {

DatasetSplit syntheticSplit(const std::string& name, int views, int seedOffset) {
  DatasetSplit split;
  split.name = name;
  split.width = kSyntheticWidth;
  split.height = kSyntheticHeight;
  for (int i = 0; i < views; ++i) {
    char file[64];
    std::snprintf(file, sizeof file, "%s/render/render_%04d", name.c_str(), i);
    double angle = 0.9 * (i + seedOffset);
    Vec3d eye(4.0 * std::cos(angle), 4.0 * std::sin(angle), 1.5 + 0.1 * i);
    split.views.push_back({file, Camera::fromFieldOfView(Mat4::lookAt(eye, Vec3d(0, 0, 0.5), Vec3d(0, 0, 1)), 0.7,
                                                         kSyntheticWidth, kSyntheticHeight),
                           {}});
  }
  return split;
}

}  // namespace

SyntheticDataset writeSyntheticDataset(const std::filesystem::path& root, ImageFormat format, int trainViews,
                                       int testViews, bool pointCloud) {
  SyntheticDataset data;
  data.train = syntheticSplit("train", trainViews, 0);
  data.test = syntheticSplit("test", testViews, 7);
  for (auto [split, buffers] : {std::pair{&data.train, &data.trainBuffers}, {&data.test, &data.testBuffers}}) {
    writeTransforms(root, *split);
    for (size_t i = 0; i < split->views.size(); ++i) {
      int seed = int(i) + (split == &data.test ? 10 : 0);
      buffers->push_back(syntheticBuffers(kSyntheticWidth, kSyntheticHeight, seed));
      writeViewBuffers(root, split->views[i], buffers->back(), format);
    }
  }
  if (pointCloud) {
    PointCloud cloud;
    for (int i = 0; i < 10; ++i) {
      cloud.positions.push_back(Vec3f(0.1f * i, -0.05f * i, 0.5f));
      cloud.colors.push_back(Rgb(0.1f * i, 0.5f, 1.0f - 0.1f * i));
    }
    writePointCloud(root / "point_cloud_dense.ply", cloud);
  }
  return data;
}

}  // namespace glint::test
