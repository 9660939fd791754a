// Opening a dataset folder, loading its buffers on demand, and writing cameras and buffers.
#include "scene/dataset.h"

#include <cmath>
#include <system_error>

#include "core/error.h"
#include "core/printable_text.h"
#include "io/transforms_json.h"
#include "scene/buffer_codec.h"
#include "scene/downscale.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

fs::path transformsPath(const fs::path& root, const std::string& split) {
  return root / ("transforms_" + split + ".json");
}

// A split whose transforms file is absent stays empty: a dataset may hold one split only.
DatasetSplit openSplit(const fs::path& root, const std::string& name, bool requireBuffers) {
  fs::path path = transformsPath(root, name);
  if (!fs::exists(path)) return DatasetSplit{name, 0, 0, {}};
  TransformsFile transforms = readTransformsJson(path);
  if (transforms.frames.empty()) throw Error(path.string(), "frames is empty: a split needs at least one view");

  DatasetSplit split;
  split.name = name;
  for (TransformsFrame& frame : transforms.frames) {
    if (requireBuffers && !isRenderFilePath(frame.filePath))
      throw Error(path.string(), "file_path \"" + printableText(frame.filePath) +
                                     "\" does not name a render image (expected SPLIT/render/render_NAME)");
    // 1x1 until the image size is known (Dataset::open sets it).
    split.views.push_back(
        {std::move(frame.filePath), Camera::fromFieldOfView(frame.transformMatrix, transforms.cameraAngleX, 1, 1), {}});
  }
  return split;
}

// Gives every view of the split the size of its images; the layout has one size per split.
void setSplitSize(DatasetSplit* split, int width, int height) {
  split->width = width;
  split->height = height;
  for (DatasetView& view : split->views) view.camera = view.camera.resized(width, height);
}

}  // namespace

const Camera& DatasetSplit::camera(size_t index) const {
  GLINT_CHECK(index < views.size(), "view index out of range");
  return views[index].camera;
}

Dataset Dataset::open(const fs::path& root, bool requireBuffers, int holdout) {
  DatasetReading reading;
  reading.requireBuffers = requireBuffers;
  reading.holdout = holdout;
  return open(root, reading);
}

Dataset Dataset::open(const fs::path& root, const DatasetReading& reading) {
  Dataset dataset;
  dataset.root_ = root;
  if (!fs::is_directory(root)) throw Error(root.string(), "is not a folder (a dataset is a folder)");
  dataset.openLayout(reading);
  if (reading.downscale > 1) {
    dataset.downscale_ = reading.downscale;
    dataset.downscaleSplits();
  }
  return dataset;
}

void Dataset::openLayout(const DatasetReading& reading) {
  const fs::path& root = root_;
  if (isCaptureFolder(root)) {
    auto source = std::make_shared<CaptureSource>();
    openCapture(root, reading.holdout, &train_, &test_, source.get());
    capture_ = std::move(source);
    return;
  }
  if (!fs::exists(transformsPath(root, "train")) && !fs::exists(transformsPath(root, "test")) &&
      !fs::exists(transformsPath(root, "val"))) {
    // Photographs without cameras are what most people start from: say how to get cameras.
    if (!photographsIn(root).empty() || !photographsIn(root / "images").empty())
      throw Error(root.string(),
                  "holds photographs but no cameras; get them with COLMAP: glint capture " + root.string() +
                      " -o CAPTURE, then train on CAPTURE (README, \"Train on your own photos\")");
    throw Error(transformsPath(root, "train").string(),
                "file not found (a dataset needs transforms_train.json, transforms_test.json or both; or a capture's "
                "COLMAP model or transforms.json)");
  }
  if (isNerfSyntheticFolder(root)) {
    auto source = std::make_shared<CaptureSource>();
    openNerfSynthetic(root, reading.background, reading.requireBuffers, &train_, &test_, source.get());
    capture_ = std::move(source);
    return;
  }
  train_ = openSplit(root, "train", reading.requireBuffers);
  test_ = openSplit(root, "test", reading.requireBuffers);
  if (isPriorTransformsFolder(root)) {
    // The paper's synthetic scenes with predicted buffers: sizes from the render images,
    // buffers decoded like a capture's priors.
    auto source = std::make_shared<CaptureSource>();
    attachPriorTransforms(root, &train_, &test_, source.get());
    for (DatasetSplit* split : {&train_, &test_}) {
      if (split->views.empty()) continue;
      Image first = readImage(root / split->views[0].files[int(Buffer::Render)]);
      setSplitSize(split, first.width, first.height);
    }
    capture_ = std::move(source);
    return;
  }
  // The first view's render image sets the split's size; loadBuffer holds every other
  // buffer to it. Without requireBuffers a split whose images are absent keeps no size.
  for (DatasetSplit* split : {&train_, &test_}) {
    if (split->views.empty()) continue;
    if (!reading.requireBuffers && !findBufferFile(split->views[0], Buffer::Render)) continue;
    Image first = loadBuffer(*split, 0, Buffer::Render);
    setSplitSize(split, first.width, first.height);
  }
}

void Dataset::downscaleSplits() {
  fullTrain_ = train_, fullTest_ = test_;
  const int n = downscale_;
  for (DatasetSplit* split : {&train_, &test_}) {
    for (DatasetView& view : split->views) {
      const Camera& c = view.camera;
      if (split->width <= 0) break;  // cameras only, of no size yet: resized by their user
      if (c.width < n || c.height < n)
        throw Error(root_.string(), "--downscale " + std::to_string(n) + " is larger than the " +
                                        std::to_string(c.width) + "x" + std::to_string(c.height) + " image of view " +
                                        view.filePath);
      view.camera = downscaleCamera(c, n);
    }
    if (split->width > 0) split->width /= n, split->height /= n;
  }
}

const DatasetSplit& Dataset::split(const std::string& name) const {
  if (name != "train" && name != "test")
    throw Error(root_.string(), "unknown split \"" + name + "\" (expected train or test)");
  const DatasetSplit& s = name == "train" ? train_ : test_;
  // A capture's splits come from its holdout; the transforms layouts' from their files.
  const bool splitByFiles = !capture_ || capture_->alphaBackground || capture_->priorTransforms;
  const bool valCounts = name == "test" && capture_ && capture_->alphaBackground;  // NeRF-synthetic's val
  if (s.views.empty() && splitByFiles)
    throw Error(transformsPath(root_, name).string(),
                std::string("file not found") + (valCounts ? " (nor transforms_val.json)" : "") +
                    ": this dataset holds the " + (name == "train" ? "test" : "train") + " split only");
  return s;
}

std::optional<fs::path> Dataset::findBufferFile(const DatasetView& view, Buffer buffer) const {
  if (capture_) {
    const std::string& file = view.files[int(buffer)];
    return file.empty() ? std::nullopt : std::optional<fs::path>(root_ / file);
  }
  return findBufferFileAt(root_ / bufferFilePath(view.filePath, buffer));
}

Image Dataset::loadBuffer(const DatasetSplit& split, size_t index, Buffer buffer) const {
  if (downscale_ == 1) return loadFullResolution(split, index, buffer);
  // The file is checked against the full-resolution camera, then shrunk like the camera was.
  const DatasetSplit& full = split.name == "train" ? fullTrain_ : fullTest_;
  return downscaleBuffer(loadFullResolution(full, index, buffer), buffer, downscale_);
}

Image Dataset::loadFullResolution(const DatasetSplit& split, size_t index, Buffer buffer) const {
  GLINT_CHECK(index < split.views.size(), "view index out of range");
  const DatasetView& view = split.views[index];
  if (capture_) {
    if (view.files[int(buffer)].empty() && capture_->alphaBackground)
      throw Error(root_.string(), "is in the NeRF-synthetic layout, whose views hold final images only: view " +
                                      view.filePath + " has no " + bufferName(buffer) + " buffer");
    if (view.files[int(buffer)].empty())
      throw Error((root_ / "priors" / bufferName(buffer)).string(),
                  "has no " + std::string(bufferName(buffer)) + " buffer for view " + view.filePath);
    return loadCaptureBuffer(root_, *capture_, view, buffer);
  }
  std::optional<fs::path> path = findBufferFile(view, buffer);
  if (!path) {
    fs::path base = root_ / bufferFilePath(view.filePath, buffer);
    throw Error(base.string(), missingBufferMessage(base, buffer));
  }
  Image image = readBufferFile(*path, buffer);
  // A split opened without buffers has no size yet: the first image read sets none either.
  if (split.width > 0 && (image.width != split.width || image.height != split.height))
    throw Error(path->string(), "image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                                    " pixels, but the " + split.name + " split's images are " +
                                    std::to_string(split.width) + "x" + std::to_string(split.height));
  if (std::optional<std::string> problem = findInvalidValue(image, buffer)) throw Error(path->string(), *problem);
  return image;
}

ViewBuffers Dataset::loadView(const DatasetSplit& split, size_t index) const {
  ViewBuffers buffers;
  for (Buffer b : kAllBuffers) buffers[b] = loadBuffer(split, index, b);
  return buffers;
}

std::optional<fs::path> Dataset::pointCloudPath() const {
  fs::path path = root_ / "point_cloud_dense.ply";
  if (fs::is_regular_file(path)) return path;
  return std::nullopt;
}

void writeTransforms(const fs::path& root, const DatasetSplit& split) {
  GLINT_CHECK(!split.name.empty(), "a split needs a name to be written");
  GLINT_CHECK(!split.views.empty(), "a split needs views to be written");
  TransformsFile transforms;
  transforms.cameraAngleX = split.views[0].camera.fieldOfViewX();
  for (const DatasetView& view : split.views) {
    const Camera& c = view.camera;
    GLINT_CHECK(std::abs(c.fx - c.fy) <= 1e-9 * c.fx && std::abs(c.cx - 0.5 * c.width) <= 1e-9 * c.width &&
                    std::abs(c.cy - 0.5 * c.height) <= 1e-9 * c.height &&
                    std::abs(c.fieldOfViewX() - transforms.cameraAngleX) <= 1e-12,
                "transforms files store one centred field of view per split");
    transforms.frames.push_back({view.filePath, c.cameraToWorld});
  }
  writeTransformsJson(transformsPath(root, split.name), transforms);
}

void writeViewBuffers(const fs::path& root, const DatasetView& view, const ViewBuffers& buffers, ImageFormat format) {
  const Image& render = buffers[Buffer::Render];
  for (Buffer b : kAllBuffers) {
    const Image& image = buffers[b];
    GLINT_CHECK(image.width == render.width && image.height == render.height, "a view's buffers differ in size");
    GLINT_CHECK(image.channels == bufferChannels(b), "buffer has the wrong channel count");

    ImageFormat stored = bufferStorageFormat(b, format);
    fs::path base = root / bufferFilePath(view.filePath, b);
    fs::path path = base;
    path += imageFormatExtension(stored);
    writeImage(path, encodeBuffer(image, b, stored));
    // The loader prefers .exr over .tiff over .png: a stale file of another format from an
    // earlier run would shadow the one just written.
    for (ImageFormat other : {ImageFormat::Exr, ImageFormat::Tiff, ImageFormat::Png}) {
      if (other == stored) continue;
      fs::path stale = base;
      stale += imageFormatExtension(other);
      std::error_code ignored;
      fs::remove(stale, ignored);
    }
  }
}

bool isRenderFilePath(const std::string& filePath) {
  fs::path path(filePath);
  return path.parent_path().filename() == "render" && path.filename().string().rfind("render", 0) == 0;
}

std::string bufferFilePath(const std::string& renderFilePath, Buffer buffer) {
  if (!isRenderFilePath(renderFilePath))
    throw Error(renderFilePath, "does not name a render image (expected SPLIT/render/render_NAME), so its " +
                                    std::string(bufferName(buffer)) + " buffer cannot be found");
  if (buffer == Buffer::Render) return renderFilePath;
  fs::path path(renderFilePath);
  std::string name = bufferName(buffer);
  std::string suffix = path.filename().string().substr(std::string("render").size());
  return (path.parent_path().parent_path() / name / (name + suffix)).generic_string();
}

}  // namespace glint
