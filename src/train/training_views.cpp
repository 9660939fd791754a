// Loading the training targets and drawing ray batches.
#include "train/training_views.h"

#include <algorithm>
#include <numeric>

#include "core/error.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "math/rng.h"
#include "scene/buffer_codec.h"
#include "scene/capture_dataset.h"
#include "scene/predicted_buffers.h"

namespace glint {

namespace fs = std::filesystem;

namespace {
constexpr uint64_t kBatchStream = 0x62617463682d7279;  // "batch-ry": keys batch draws apart from other streams
constexpr uint64_t kEpochStream = 0x65706f63682d6f72;  // "epoch-or": the order of whole views in an epoch
}

std::string SupervisedBuffers::list(bool present) const {
  std::string out;
  for (auto [has, name] : {std::pair{specular, "specular"}, {depth, "depth"}, {normal, "normal"},
                           {roughness, "roughness"}, {f0, "f0"}})
    if (has == present) out += (out.empty() ? "" : ", ") + std::string(name);
  return out;
}

TrainingViews TrainingViews::load(const Dataset& dataset, const DatasetSplit& split, ColourTarget colour,
                                  bool metalnessTrainsBrightness, float tintPrior, bool photograph) {
  if (split.views.empty()) throw Error(dataset.root().string(), "has no " + split.name + " views to train on");
  TrainingViews tv;
  // The first view decides which buffer kinds are trained; every other view must have them.
  const DatasetView& first = split.views[0];
  auto present = [&](Buffer b) { return dataset.findBufferFile(first, b).has_value(); };
  SupervisedBuffers& s = tv.supervised_;
  s.finalColour = colour == ColourTarget::Render || !present(Buffer::Diffuse);
  const Buffer colourBuffer = s.finalColour ? Buffer::Render : Buffer::Diffuse;
  if (!present(colourBuffer)) {
    fs::path base = dataset.root() / bufferFilePath(first.filePath, colourBuffer);
    throw Error(base.string(),
                "not found: training needs the " + std::string(bufferName(colourBuffer)) + " image of every view");
  }
  s.specular = !s.finalColour && present(Buffer::Specular);
  s.depth = present(Buffer::Depth);
  s.normal = present(Buffer::Normal);
  s.roughness = present(Buffer::Roughness);
  s.f0 = present(Buffer::F0);
  s.f0BrightnessOnly = s.f0 && metalnessTrainsBrightness && isMetalnessPrior(*dataset.findBufferFile(first, Buffer::F0));
  s.f0TintPrior = s.f0BrightnessOnly ? tintPrior : 0;
  // Every layout Glint trains on has its photographs (a view's size comes from them), so a
  // missing one is Dataset::loadBuffer's error, naming the file.
  s.photograph = photograph && !s.finalColour;

  // Sizes come from each view's camera; a view's buffers must match it.
  tv.cameras_.resize(split.views.size());
  tv.firstPixel_.assign(split.views.size() + 1, 0);
  for (size_t v = 0; v < split.views.size(); ++v) {
    tv.cameras_[v] = split.camera(v);
    const Camera& c = tv.cameras_[v];
    if (c.width <= 0 || c.height <= 0)
      throw Error(dataset.root().string(), "has no " + split.name + " images (the image size is unknown)");
    tv.firstPixel_[v + 1] = tv.firstPixel_[v] + size_t(c.width) * size_t(c.height);
  }
  tv.targets_.resize(tv.firstPixel_.back());
  if (s.photograph) tv.photographs_.resize(tv.firstPixel_.back());

  ProgressBar progress("load " + split.name + " views", int64_t(split.views.size()), "views");
  // Views load in parallel: decoding dominates and is independent per file.
  parallelFor(int64_t(split.views.size()), 1, [&](int64_t v) {
    const Camera& camera = tv.cameras_[size_t(v)];
    auto load = [&](bool wanted, Buffer b) { return wanted ? dataset.loadBuffer(split, size_t(v), b) : Image(); };
    Image colourImage = load(true, colourBuffer);
    Image specular = load(s.specular, Buffer::Specular), depth = load(s.depth, Buffer::Depth);
    Image normal = load(s.normal, Buffer::Normal), roughness = load(s.roughness, Buffer::Roughness);
    Image f0 = load(s.f0, Buffer::F0);
    // The render buffer beside the diffuse one is held only for the photograph term (whose
    // load names a missing file), but it is read either way: training refuses every view
    // `glint info` refuses, since a broken file is a broken dataset and a run trained on one
    // would be scored against it.
    Image photographImage;
    if (colourBuffer != Buffer::Render && (s.photograph || present(Buffer::Render)))
      photographImage = load(true, Buffer::Render);
    if (!s.photograph) photographImage = Image();  // checked, not held
    const std::string& name = split.views[size_t(v)].filePath;
    for (const Image* image : {&colourImage, &specular, &depth, &normal, &roughness, &f0, &photographImage})
      if (!image->empty() && (image->width != camera.width || image->height != camera.height))
        throw Error(dataset.root().string(), "view " + name + " has buffers of size " + std::to_string(image->width) +
                                                 "x" + std::to_string(image->height) + ", expected " +
                                                 std::to_string(camera.width) + "x" + std::to_string(camera.height));
    if (s.normal) {
      // Without depth every pixel counts as a surface (photographs rarely show the void).
      const Image surfaces = s.depth ? Image() : Image(camera.width, camera.height, 1, 1.0f);
      if (std::optional<std::string> problem = findNonUnitNormal(normal, s.depth ? depth : surfaces)) {
        std::optional<fs::path> file = dataset.findBufferFile(split.views[size_t(v)], Buffer::Normal);
        throw Error(file ? file->string() : name, *problem);
      }
    }
    PackedTarget* out = tv.targets_.data() + tv.firstPixel_[size_t(v)];
    uint32_t* photographOut = s.photograph ? tv.photographs_.data() + tv.firstPixel_[size_t(v)] : nullptr;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        if (photographOut) *photographOut++ = packSharedExponent(photographImage.rgb(x, y));
        PackedTarget& t = *out++;
        t.diffuse = packSharedExponent(colourImage.rgb(x, y));
        if (s.specular) t.specular = packSharedExponent(specular.rgb(x, y));
        const bool surface = !s.depth || hasSurface(depth.at(x, y));
        t.depth = s.depth ? packDepth(depth.at(x, y), surface) : packDepth(1.0f, true);
        if (s.normal) t.normal = packOctahedral(normal.rgb(x, y));
        if (s.roughness) t.roughness = packUnorm8(roughness.at(x, y));
        if (s.f0) {
          const Rgb c = f0.rgb(x, y);
          t.f0[0] = packUnorm8(c.x), t.f0[1] = packUnorm8(c.y), t.f0[2] = packUnorm8(c.z);
        }
      }
    progress.advance();
  });
  return tv;
}

PixelTarget TrainingViews::target(size_t view, size_t pixel) const {
  const PackedTarget& p = targets_[firstPixel_[view] + pixel];
  PixelTarget t;
  t.diffuse = unpackSharedExponent(p.diffuse);
  t.specular = unpackSharedExponent(p.specular);
  t.depth = unpackDepth(p.depth);
  t.surface = p.depth != 0;
  t.normal = unpackOctahedral(p.normal);
  if (!normalTurn_.empty()) t.normal = normalTurn_[view] * t.normal;
  t.roughness = unpackUnorm8(p.roughness);
  t.f0 = Rgb(unpackUnorm8(p.f0[0]), unpackUnorm8(p.f0[1]), unpackUnorm8(p.f0[2]));
  t.hasSpecular = supervised_.specular;
  t.hasDepth = depthTrusted(view, pixel);
  t.hasNormal = supervised_.normal;
  t.hasRoughness = supervised_.roughness;
  t.hasF0 = supervised_.f0;
  t.finalColour = supervised_.finalColour;
  // A metal's tint is left to L_r; a dielectric's F0 is achromatic, so every channel of it
  // is kept (left free, L_r's noisy gradient tinted the walls' reflections).
  t.f0BrightnessOnly = supervised_.f0BrightnessOnly && greyF0IsMetal(t.f0);
  t.f0TintPrior = supervised_.f0TintPrior;
  if (!photographs_.empty()) {
    t.photograph = unpackSharedExponent(photographs_[firstPixel_[view] + pixel]);
    t.hasPhotograph = true;
  }
  return t;
}

void TrainingViews::setCamera(size_t view, const Camera& camera, bool normalsFromCamera) {
  GLINT_CHECK(view < viewCount() && camera.width == cameras_[view].width && camera.height == cameras_[view].height,
              "TrainingViews::setCamera: a view's camera keeps its size");
  if (loadedCameras_.empty()) loadedCameras_ = cameras_;
  cameras_[view] = camera;
  if (!normalsFromCamera || !supervised_.normal) return;
  if (normalTurn_.empty()) normalTurn_.resize(viewCount());  // identity
  const Mat3d turn = camera.rotation() * loadedCameras_[view].rotation().transposed();
  for (int i = 0; i < 3; ++i) normalTurn_[view].m[i] = Vec3f(turn.m[i]);
}

size_t TrainingViews::memoryBytes() const {
  return targets_.capacity() * sizeof(PackedTarget) + photographs_.capacity() * sizeof(uint32_t) +
         cameras_.capacity() * sizeof(Camera) +
         firstPixel_.capacity() * sizeof(size_t) + depthTrusted_.capacity() +
         loadedCameras_.capacity() * sizeof(Camera) + normalTurn_.capacity() * sizeof(Mat3f);
}

TraceRay TrainingViews::pixelRay(size_t view, size_t pixel) const {
  const Camera& camera = cameras_[view];
  const size_t width = size_t(camera.width);
  Ray r = camera.generateRay(double(pixel % width) + 0.5, double(pixel / width) + 0.5);
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
  for (size_t k = 0; k < chosen; ++k) {
    const uint32_t pixels = uint32_t(pixelCount(order[k]));
    size_t share = size_t(rays) / chosen + (k < size_t(rays) % chosen ? 1 : 0);
    size_t first = batch->size();
    for (size_t r = 0; r < share; ++r) batch->push_back({TraceRay{}, order[k], rng.uniformInt(pixels)});
    std::sort(batch->begin() + first, batch->end(),
              [](const BatchRay& a, const BatchRay& b) { return a.pixel < b.pixel; });
  }
  for (BatchRay& b : *batch) b.ray = pixelRay(b.view, b.pixel);
}

uint32_t TrainingViews::epochView(uint64_t seed, int64_t position) const {
  const uint64_t total = viewCount();
  const uint64_t epoch = uint64_t(position) / total;
  // The epoch's order: a Fisher-Yates shuffle keyed by (seed, epoch), drawn in full (a few
  // thousand views at most, a microsecond each), so each position depends on nothing else.
  Rng rng = Rng::forKeys({seed, kEpochStream, epoch});
  std::vector<uint32_t> order(total);
  std::iota(order.begin(), order.end(), 0u);
  for (size_t i = 0; i + 1 < order.size(); ++i)
    std::swap(order[i], order[i + rng.uniformInt(uint32_t(order.size() - i))]);
  return order[size_t(uint64_t(position) % total)];
}

void TrainingViews::drawWholeImages(uint64_t seed, int64_t step, int images, std::vector<BatchRay>* batch) const {
  batch->clear();
  const int64_t perStep = std::min<int64_t>(images, int64_t(viewCount()));
  std::vector<uint32_t> views(static_cast<size_t>(perStep));
  size_t rays = 0;
  for (int64_t k = 0; k < perStep; ++k) {
    views[size_t(k)] = epochView(seed, step * perStep + k);
    rays += pixelCount(views[size_t(k)]);
  }
  batch->reserve(rays);
  for (uint32_t view : views) {
    const uint32_t pixels = uint32_t(pixelCount(view));
    for (uint32_t p = 0; p < pixels; ++p) batch->push_back({pixelRay(view, p), view, p});
  }
}

DepthConsistency TrainingViews::keepConsistentDepth(const DepthConsistencyOptions& options) {
  auto depth = [this](size_t view, size_t pixel) {
    const uint16_t packed = targets_[firstPixel_[view] + pixel].depth;
    return packed == 0 ? 0.0f : unpackDepth(packed);
  };
  // Without depth buffers every pixel is packed as a surface at depth 1 (load): nothing to check.
  if (!supervised_.depth) return {};
  DepthConsistency found = checkDepthConsistency(cameras_, depth, options);
  depthTrusted_.assign(targets_.size(), 1);
  for (size_t v = 0; v < viewCount(); ++v)
    for (size_t pixel = 0; pixel < pixelCount(v); ++pixel)
      if (targets_[firstPixel_[v] + pixel].depth != 0 && found.agreeing[v][pixel] < options.minAgreeing)
        depthTrusted_[firstPixel_[v] + pixel] = 0;
  return found;
}

}  // namespace glint
