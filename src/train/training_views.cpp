// Loading the training targets and drawing ray batches.
#include "train/training_views.h"

#include <algorithm>
#include <numeric>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "math/rng.h"
#include "scene/buffer_codec.h"

namespace glint {

namespace {
constexpr uint64_t kBatchStream = 0x62617463682d7279;  // "batch-ry": keys batch draws apart from other streams
}

TrainingViews TrainingViews::load(const Dataset& dataset, const DatasetSplit& split, ColourTarget colour) {
  if (split.views.empty()) throw Error(dataset.root().string(), "has no " + split.name + " views to train on");
  TrainingViews tv;
  tv.width_ = split.width;
  tv.height_ = split.height;
  if (tv.width_ <= 0 || tv.height_ <= 0)
    throw Error(dataset.root().string(), "has no " + split.name + " images (the image size is unknown)");
  const size_t pixels = tv.pixelsPerView();
  tv.cameras_.resize(split.views.size());
  tv.targets_.resize(split.views.size() * pixels);
  bool haveSpecular = dataset.findBufferFile(split.views[0], Buffer::Specular).has_value();
  ProgressBar progress("load " + split.name + " views", int64_t(split.views.size()), "views");
  // Views load in parallel: decoding EXR dominates and is independent per file.
  parallelFor(int64_t(split.views.size()), 1, [&](int64_t v) {
    tv.cameras_[v] = split.camera(size_t(v));
    Image diffuse =
        dataset.loadBuffer(split, size_t(v), colour == ColourTarget::Render ? Buffer::Render : Buffer::Diffuse);
    Image depth = dataset.loadBuffer(split, size_t(v), Buffer::Depth);
    Image normal = dataset.loadBuffer(split, size_t(v), Buffer::Normal);
    Image roughness = dataset.loadBuffer(split, size_t(v), Buffer::Roughness);
    Image f0 = dataset.loadBuffer(split, size_t(v), Buffer::F0);
    Image specular = haveSpecular ? dataset.loadBuffer(split, size_t(v), Buffer::Specular) : Image();
    // Training reads neither the render buffer (beside the RGB baseline) nor unit normals
    // alone, but it refuses every view `glint info` refuses: a broken file is a broken
    // dataset, and a run trained on one would be scored against it.
    if (colour != ColourTarget::Render) dataset.loadBuffer(split, size_t(v), Buffer::Render);
    if (std::optional<std::string> problem = findNonUnitNormal(normal, depth)) {
      std::optional<std::filesystem::path> file = dataset.findBufferFile(split.views[v], Buffer::Normal);
      throw Error(file ? file->string() : split.views[v].filePath, *problem);
    }
    for (const Image* image : {&diffuse, &depth, &normal, &roughness, &f0})
      if (image->width != tv.width_ || image->height != tv.height_)
        throw Error(dataset.root().string(), "view " + split.views[v].filePath + " has buffers of size " +
                                                 std::to_string(image->width) + "x" + std::to_string(image->height) +
                                                 ", expected " + std::to_string(tv.width_) + "x" +
                                                 std::to_string(tv.height_));
    PixelTarget* out = tv.targets_.data() + size_t(v) * pixels;
    for (size_t p = 0; p < pixels; ++p) {
      int x = int(p % size_t(tv.width_)), y = int(p / size_t(tv.width_));
      PixelTarget& t = out[p];
      t.diffuse = diffuse.rgb(x, y);
      if (haveSpecular) t.specular = specular.rgb(x, y);
      t.depth = depth.at(x, y);
      t.normal = normal.rgb(x, y);
      t.roughness = roughness.at(x, y);
      t.f0 = f0.rgb(x, y);
      t.surface = hasSurface(t.depth);
    }
    progress.advance();
  });
  return tv;
}

TraceRay TrainingViews::pixelRay(size_t view, size_t pixel) const {
  Ray r = cameras_[view].generateRay(double(pixel % size_t(width_)) + 0.5, double(pixel / size_t(width_)) + 0.5);
  TraceRay t;
  t.origin = Vec3f(r.origin);
  t.direction = Vec3f(r.direction);
  t.tMin = 0.0f;
  return t;
}

void TrainingViews::drawBatch(uint64_t seed, int64_t step, int rays, int views, std::vector<BatchRay>* batch) const {
  Rng rng = Rng::forKeys({seed, kBatchStream, uint64_t(step)});
  const size_t viewTotal = viewCount();
  const size_t chosen = std::min(size_t(views), viewTotal);
  // A partial Fisher-Yates shuffle picks `chosen` distinct views.
  std::vector<uint32_t> order(viewTotal);
  std::iota(order.begin(), order.end(), 0u);
  for (size_t i = 0; i < chosen; ++i) std::swap(order[i], order[i + rng.uniformInt(uint32_t(viewTotal - i))]);
  batch->clear();
  batch->reserve(size_t(rays));
  const uint32_t pixels = uint32_t(pixelsPerView());
  for (size_t k = 0; k < chosen; ++k) {
    size_t share = size_t(rays) / chosen + (k < size_t(rays) % chosen ? 1 : 0);
    size_t first = batch->size();
    for (size_t r = 0; r < share; ++r) batch->push_back({TraceRay{}, order[k], rng.uniformInt(pixels)});
    std::sort(batch->begin() + first, batch->end(),
              [](const BatchRay& a, const BatchRay& b) { return a.pixel < b.pixel; });
  }
  for (BatchRay& b : *batch) b.ray = pixelRay(b.view, b.pixel);
}

}  // namespace glint
