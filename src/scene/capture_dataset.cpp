// Opening real captures (COLMAP or nerfstudio cameras, photographs, predicted buffers) and
// decoding their buffers to Glint's definitions.
#include "scene/capture_dataset.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/input_file.h"
#include "core/printable_text.h"
#include "io/colmap_model.h"
#include "io/json_file.h"
#include "io/nerfstudio_transforms.h"
#include "io/point_cloud.h"
#include "scene/buffer_codec.h"
#include "scene/camera_conventions.h"
#include "scene/dataset.h"
#include "scene/nerf_synthetic.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// The COLMAP model folder of a capture: sparse/0 (COLMAP's mapper output) or sparse/.
std::optional<fs::path> colmapModelFolder(const fs::path& root) {
  for (const fs::path& folder : {root / "sparse" / "0", root / "sparse"})
    for (const char* file : {"cameras.bin", "cameras.txt"})
      // Presence, not a regular file, decides the layout: a broken cameras.txt is reported
      // as itself, not as a missing transforms file of another layout.
      if (pathPresent(folder / file)) return folder;
  return std::nullopt;
}

std::string lowerExtension(const fs::path& path) {
  std::string e = path.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}

// folder/<name>/<name>_<stem> with any extension Glint reads, or "".
std::string findPrior(const fs::path& root, const std::string& name, const std::string& stem,
                      const fs::path& folder = "priors") {
  for (const char* ext : {".png", ".exr", ".tiff", ".tif", ".jpg", ".jpeg"}) {
    fs::path relative = folder / name / (name + "_" + stem + ext);
    // Whatever has the name is the prior: a FIFO or a folder there is refused by name when
    // read, not mistaken for a missing prior (which would drop the buffer from training).
    if (pathPresent(root / relative)) return relative.generic_string();
  }
  return "";
}

// Sparse points with their sRGB colours made linear (a point without colour is grey).
void appendSparsePoints(const PointCloud& cloud, CaptureSource* source) {
  for (size_t i = 0; i < cloud.positions.size(); ++i) {
    source->points.push_back(Vec3d(cloud.positions[i]));
    const Rgb c = i < cloud.colors.size() ? cloud.colors[i] : Rgb(0.5f);
    source->pointColours.push_back(
        {toLinear(Transfer::Srgb, c.x), toLinear(Transfer::Srgb, c.y), toLinear(Transfer::Srgb, c.z)});
  }
}

// The sparse points of a COLMAP model, with linear colours, and its cameras. When observed
// is given, it receives the indices into source->points that each image's tracks name, by
// image name (nothing for a model without tracks).
void readSparsePoints(const fs::path& folder, CaptureSource* source, CaptureScene* scene,
                      std::unordered_map<std::string, std::vector<uint32_t>>* observed = nullptr) {
  ColmapModel colmap = readColmapModel(folder);
  *scene = captureFromColmap(colmap);
  if (observed) {
    std::unordered_map<uint32_t, const std::string*> names;
    for (const ColmapImage& image : colmap.images) names[image.id] = &image.name;
    const size_t first = source->points.size();
    for (size_t i = 0; i < colmap.points.size(); ++i)
      for (const ColmapTrackElement& e : colmap.points[i].track) {
        auto name = names.find(e.imageId);
        if (name == names.end()) continue;  // an image the model does not hold: nothing to pair with
        std::vector<uint32_t>& points = (*observed)[*name->second];
        // A track may name an image twice (two keypoints on one point): pair it once.
        if (points.empty() || points.back() != uint32_t(first + i)) points.push_back(uint32_t(first + i));
      }
  }
  appendSparsePoints(scene->points, source);
  source->description = "COLMAP " + std::string(colmap.format == ColmapFormat::Binary ? "binary" : "text") + " model " +
                        (folder.filename() == "0" ? "sparse/0" : "sparse") + ", " +
                        std::to_string(scene->cameras.size()) + " images, " + std::to_string(source->points.size()) +
                        " points";
}

// A view's files: the photograph, and whichever priors exist.
DatasetView captureView(const fs::path& root, const CaptureCamera& c, const fs::path& image) {
  std::error_code ec;
  if (!fs::is_regular_file(root / image, ec))
    throw Error(quotedPath(root / image), ec.value() == ENAMETOOLONG
                                              ? "the camera model names this image, and the name is too long for "
                                                "the file system"
                                              : "not found: the camera model names this image");
  const std::string stem = fs::path(c.imageName).stem().string();
  DatasetView view;
  view.filePath = "train/render/render_" + stem;  // splitViews sets the split
  view.camera = toCamera(c);
  auto& files = view.files;
  const std::string priorRender = findPrior(root, "render", stem);
  files[int(Buffer::Render)] = priorRender.empty() ? image.generic_string() : priorRender;
  for (Buffer b : {Buffer::Diffuse, Buffer::Specular, Buffer::Depth, Buffer::Normal, Buffer::Roughness, Buffer::F0})
    files[int(b)] = findPrior(root, bufferName(b), stem);
  if (files[int(Buffer::F0)].empty()) files[int(Buffer::F0)] = findPrior(root, "metalness", stem);
  return view;
}

void splitViews(std::vector<DatasetView> views, int holdout, DatasetSplit* train, DatasetSplit* test) {
  train->name = "train", test->name = "test";
  for (size_t i = 0; i < views.size(); ++i) {
    DatasetView& view = views[i];
    const bool isTest = i % size_t(holdout) == 0;
    // The render folder names the split the view landed in.
    view.filePath = (isTest ? "test" : "train") + view.filePath.substr(view.filePath.find('/'));
    (isTest ? test : train)->views.push_back(std::move(view));
  }
  for (DatasetSplit* split : {train, test})
    if (!split->views.empty()) {
      // A split's size is its first view's; views may differ (each camera has its own).
      split->width = split->views[0].camera.width;
      split->height = split->views[0].camera.height;
    }
}

template <typename Enum>
Enum readChoice(const nlohmann::json& j, const char* key, std::initializer_list<std::pair<const char*, Enum>> choices,
                Enum fallback, const fs::path& file) {
  if (!j.contains(key)) return fallback;
  std::string names;
  if (j[key].is_string())
    for (const auto& [name, value] : choices)
      if (j[key].get<std::string>() == name) return value;
  for (const auto& [name, value] : choices) names += (names.empty() ? "\"" : ", \"") + std::string(name) + "\"";
  throw Error(file.string(), std::string("\"") + key + "\" must be one of " + names + ", found " + printableText(j[key].dump()));
}

// The predicted depth of a view aligned to its sparse points: z = a d + b (or 1/z) fitted
// robustly to the z-depths of the points the view observed (its COLMAP tracks), or, for a
// model without tracks, of those that land in the view, nearest per pixel, hidden points
// dropped; all 0 (no depth) when no fit holds.
Image alignedZDepth(const Image& predicted, const CaptureSource& source, const DatasetView& view,
                    const fs::path& file) {
  const Camera& camera = view.camera;
  const Mat4 worldToCamera = camera.cameraToWorld.inverse();
  std::vector<Vec3d> cameraPoints;
  auto observed = source.observedPoints.find(view.files[int(Buffer::Render)]);
  const bool tracked = observed != source.observedPoints.end();
  if (tracked) {
    cameraPoints.reserve(observed->second.size());
    for (uint32_t i : observed->second) cameraPoints.push_back(worldToCamera.transformPoint(source.points[i]));
  } else {
    cameraPoints.reserve(source.points.size());
    for (const Vec3d& p : source.points) cameraPoints.push_back(worldToCamera.transformPoint(p));
  }
  const RayIntrinsics k{camera.fx, camera.fy, camera.cx, camera.cy};
  // A tracked point was seen by this view: no point behind it is to be guessed at.
  std::vector<DepthPair> pairs =
      depthPairsFromPoints(predicted, cameraPoints, k, tracked ? HiddenPoints::Keep : HiddenPoints::Drop);
  DepthFitOptions options;
  options.space = source.decoding.depth == CaptureDecoding::Depth::RelativeDisparity ? DepthFitSpace::Disparity
                                                                                     : DepthFitSpace::Depth;
  DepthFit fit = fitDepthAffine(pairs, options);
  source.recordDepthFit(file.string(), fit);
  // A view whose depth cannot be aligned keeps its colour and drops its depth: 0, "no
  // surface", so that its pixels take no depth (and no G-buffer) loss. A small or sparse
  // capture must still train; `glint info` and `glint train` list such views as warnings.
  if (!fit.ok) return Image(predicted.width, predicted.height, 1, 0.0f);
  Image z = alignDepth(predicted, fit);
  // A predicted 0 is "unknown" (the background of a synthetic capture, a predictor's mask).
  for (size_t i = 0; i < z.pixels.size(); ++i)
    if (predicted.pixels[i] == 0.0f) z.pixels[i] = 0.0f;
  return z;
}

const char* layoutName(int channels) {
  switch (channels) {
    case 1: return "grey";
    case 2: return "grey and alpha";
    case 3: return "RGB";
    case 4: return "RGBA";
  }
  return "unknown layout";
}

// A prior read with the channels its file stores, split into the buffer's channels and its
// alpha (coverage) when it has one more, or refused naming the layout it has.
struct PriorImage {
  Image image;
  Image alpha;  // empty without an alpha channel
};

PriorImage readPriorImage(const fs::path& path, int channels, const std::string& what) {
  Image stored = readImageAsStored(path);
  PriorImage prior;
  if (stored.channels == channels + 1) {
    prior.image = Image(stored.width, stored.height, channels);
    prior.alpha = Image(stored.width, stored.height, 1);
    const size_t pixels = size_t(stored.width) * size_t(stored.height);
    for (size_t p = 0; p < pixels; ++p) {
      for (int c = 0; c < channels; ++c)
        prior.image.pixels[p * size_t(channels) + size_t(c)] = stored.pixels[p * size_t(stored.channels) + size_t(c)];
      prior.alpha.pixels[p] = stored.pixels[p * size_t(stored.channels) + size_t(channels)];
    }
  } else {
    prior.image = std::move(stored);
  }
  if (prior.image.channels != channels) {
    const int found = prior.alpha.empty() ? prior.image.channels : prior.image.channels + 1;
    throw Error(quotedPath(path), "a " + what + " buffer needs " + std::to_string(channels) +
                                      (channels == 1 ? " channel (grey)" : " channels (RGB)") + ", found " +
                                      std::to_string(found) + " (" + layoutName(found) + ")");
  }
  return prior;
}

// Where a prior's alpha is below one half its pixel is "no surface" (0): the predictor's mask.
void maskByAlpha(Image* image, const Image& alpha) {
  if (alpha.empty()) return;
  for (size_t p = 0; p < alpha.pixels.size(); ++p)
    if (alpha.pixels[p] < kMinPriorCoverage)
      for (int c = 0; c < image->channels; ++c) image->pixels[p * size_t(image->channels) + size_t(c)] = 0.0f;
}

Image decodeRadiance(Image image, Transfer transfer, float clampMax) {
  image = toLinear(transfer, std::move(image));
  if (clampMax > 0.0f)
    for (float& v : image.pixels) v = std::min(v, clampMax);
  return image;
}

}  // namespace

bool isMetalnessPrior(const fs::path& path) { return path.filename().string().rfind("metalness_", 0) == 0; }

bool isDisplayReferred(const fs::path& path) {
  const std::string e = lowerExtension(path);
  return e == ".png" || e == ".jpg" || e == ".jpeg";
}

std::vector<fs::path> photographsIn(const fs::path& folder) {
  std::vector<fs::path> photos;
  std::error_code error;
  if (!fs::is_directory(folder, error)) return photos;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error))
    if (entry.is_regular_file(error) && isDisplayReferred(entry.path())) photos.push_back(entry.path());
  std::sort(photos.begin(), photos.end());
  return photos;
}

void CaptureSource::recordDepthFit(const std::string& view, const DepthFit& fit) const {
  std::lock_guard<std::mutex> lock(fitsMutex_);
  fits_[view] = fit;
}

std::map<std::string, DepthFit> CaptureSource::depthFits() const {
  std::lock_guard<std::mutex> lock(fitsMutex_);
  return fits_;
}

std::vector<std::string> CaptureSource::droppedDepths() const {
  std::vector<std::string> lines;
  for (const auto& [file, fit] : depthFits())
    if (!fit.ok)
      lines.push_back(file + ": relative depth cannot be aligned to the sparse points of this view (" + fit.problem +
                      "); its depth is dropped, so its pixels take no depth or G-buffer loss (set \"depth\" in "
                      "capture.json if the depth is metric)");
  return lines;
}

void CaptureSource::recordAlpha(Buffer buffer) const {
  std::lock_guard<std::mutex> lock(fitsMutex_);
  withAlpha_.insert(buffer);
}

std::set<Buffer> CaptureSource::buffersWithAlpha() const {
  std::lock_guard<std::mutex> lock(fitsMutex_);
  return withAlpha_;
}

CaptureDecoding readCaptureDecoding(const fs::path& file) {
  CaptureDecoding d;
  if (!pathPresent(file)) return d;  // a broken link is read, and refused by name
  nlohmann::json j = readJsonFile(file);
  if (!j.is_object()) throw Error(file.string(), "must hold a JSON object");
  static const char* known[] = {"photo_transfer", "prior_transfer", "clamp_max", "normal_space",
                                "normal_axes",    "depth",          "roughness",    "priors"};
  for (const auto& [key, value] : j.items())
    if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return key == k; }) == std::end(known))
      throw Error(file.string(), "unknown key \"" + printableText(key) + "\" (docs/capture-format.md lists the keys)");
  const std::initializer_list<std::pair<const char*, Transfer>> transfers = {
      {"srgb", Transfer::Srgb}, {"filmic", Transfer::Filmic}, {"linear", Transfer::Linear}};
  d.photoTransfer = readChoice(j, "photo_transfer", transfers, d.photoTransfer, file);
  d.priorTransfer = readChoice(j, "prior_transfer", transfers, d.priorTransfer, file);
  if (j.contains("clamp_max")) {
    if (!j["clamp_max"].is_number() || !(j["clamp_max"].get<double>() >= 0.0))
      throw Error(file.string(), "\"clamp_max\" must be a number >= 0 (0: no clamp), found " + printableText(j["clamp_max"].dump()));
    d.clampMax = j["clamp_max"].get<float>();
  }
  d.worldNormals = readChoice(j, "normal_space", {{"camera", false}, {"world", true}}, d.worldNormals, file);
  d.normalAxes =
      readChoice(j, "normal_axes",
                 {{"opengl", CameraAxes::OpenGl}, {"opencv", CameraAxes::OpenCv}, {"paper", CameraAxes::PaperPrior}},
                 d.normalAxes, file);
  d.depth = readChoice(j, "depth",
                       {{"distance", CaptureDecoding::Depth::Distance},
                        {"z", CaptureDecoding::Depth::ZDepth},
                        {"relative", CaptureDecoding::Depth::Relative},
                        {"relative_disparity", CaptureDecoding::Depth::RelativeDisparity}},
                       d.depth, file);
  d.predictedPriors = readChoice(j, "priors", {{"predicted", true}, {"exact", false}}, d.predictedPriors, file);
  d.roughness = readChoice(j, "roughness", {{"perceptual", RoughnessKind::Perceptual}, {"alpha", RoughnessKind::Alpha}},
                           d.roughness, file);
  return d;
}

bool isPriorTransformsFolder(const fs::path& root) {
  return fs::exists(root / "transforms_train.json") && colmapModelFolder(root).has_value();
}

void attachPriorTransforms(const fs::path& root, DatasetSplit* train, DatasetSplit* test, CaptureSource* source) {
  source->decoding = readCaptureDecoding(root / "capture.json");
  source->priorTransforms = true;
  CaptureScene scene;
  readSparsePoints(*colmapModelFolder(root), source, &scene);
  source->description = "transforms files with predicted buffers; " + source->description;
  for (DatasetSplit* split : {train, test})
    for (DatasetView& view : split->views) {
      // "train/render/render_0007": the split folder, and the ID after the last '_'.
      const fs::path renderPath(view.filePath);
      const fs::path splitFolder = renderPath.parent_path().parent_path();
      const std::string stem = renderPath.filename().string();
      const std::string id = stem.substr(stem.rfind('_') + 1);
      for (Buffer b : kAllBuffers) view.files[int(b)] = findPrior(root, bufferName(b), id, splitFolder);
      if (view.files[int(Buffer::F0)].empty())
        view.files[int(Buffer::F0)] = findPrior(root, "metalness", id, splitFolder);
      if (view.files[int(Buffer::Render)].empty())
        throw Error((root / view.filePath).string() + ".png", "not found: every view needs its render image");
    }
}

bool isCaptureFolder(const fs::path& root) {
  if (fs::exists(root / "transforms_train.json")) return false;
  return colmapModelFolder(root).has_value() || pathPresent(root / "transforms.json");
}

void openCapture(const fs::path& root, int holdout, DatasetSplit* train, DatasetSplit* test, CaptureSource* source) {
  if (holdout < 2)
    throw Error("--holdout", "must be 2 or more (every N-th image is a test view), found " + std::to_string(holdout));
  source->decoding = readCaptureDecoding(root / "capture.json");
  std::vector<DatasetView> views;
  if (std::optional<fs::path> model = colmapModelFolder(root)) {
    CaptureScene scene;
    std::unordered_map<std::string, std::vector<uint32_t>> observed;
    readSparsePoints(*model, source, &scene, &observed);
    if (scene.cameras.empty()) throw Error(model->string(), "the model has no images");
    for (const CaptureCamera& c : scene.cameras) {
      views.push_back(captureView(root, c, fs::path("images") / c.imageName));
      auto seen = observed.find(c.imageName);
      if (seen != observed.end())
        source->observedPoints[views.back().files[int(Buffer::Render)]] = std::move(seen->second);
    }
  } else {
    const fs::path file = root / "transforms.json";
    NerfstudioTransforms transforms = readNerfstudioTransforms(file);
    std::vector<CaptureCamera> cameras = captureFromNerfstudio(transforms);
    if (cameras.empty()) throw Error(file.string(), "frames is empty: a capture needs at least one view");
    for (const CaptureCamera& c : cameras) views.push_back(captureView(root, c, fs::path(c.imageName)));
    // ply_file_path: the sparse points, already in the file's world (ns-process-data writes
    // them with applied_transform applied).
    if (!transforms.plyFilePath.empty()) {
      appendSparsePoints(readPointCloud(root / transforms.plyFilePath), source);
    }
    source->description = "nerfstudio transforms.json, " + std::to_string(views.size()) + " images, " +
                          std::to_string(source->points.size()) + " points";
  }
  splitViews(std::move(views), holdout, train, test);
  if (train->views.empty())
    throw Error(root.string(), "has too few images for a training split with --holdout " + std::to_string(holdout));
}

namespace {

// F0 given as a predictor's metalness (priors/metalness/metalness_*): one channel.
bool isMetalnessFile(const fs::path& path, Buffer buffer) { return buffer == Buffer::F0 && isMetalnessPrior(path); }

// A normal prior's vectors in its file's own axes: n = 2v - 1 from integer codes, the stored
// values of EXR and TIFF, each renormalised (0: no surface).
Image decodeNormalPrior(const Image& image, bool displayReferred) {
  return displayReferred ? decodeNormalMap(image) : renormalizeNormals(image);
}

// A view's buffer file as stored: its layout checked (channels, alpha as coverage), its size
// checked against the camera's, its stored values checked (finite; roughness, metalness
// and F0 in [0, 1]), normals and depth masked by alpha. The alpha is returned for
// compositing radiance over the source's background, when it has one.
Image readStoredPrior(const fs::path& path, const CaptureSource& source, const DatasetView& view, Buffer buffer,
                      Image* alpha) {
  const bool metalness = isMetalnessFile(path, buffer);
  const int channels = metalness ? 1 : bufferChannels(buffer);
  // Alpha is coverage (predictors write RGBA PNGs): radiance is composited over the
  // source's background where it has one, normals and depth are masked, the rest drop it.
  PriorImage prior = readPriorImage(path, channels, metalness ? "metalness" : bufferName(buffer));
  Image image = std::move(prior.image);
  if (!prior.alpha.empty()) source.recordAlpha(buffer);
  const Camera& camera = view.camera;
  if (image.width != camera.width || image.height != camera.height)
    throw Error(path.string(), "image is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                                   " pixels, but its camera's image is " + std::to_string(camera.width) + "x" +
                                   std::to_string(camera.height));
  // The stored values, before any decoding: a conversion below clamps (roughness, metalness)
  // or renormalises (normals), which would hide a NaN or a roughness of -5.
  const Buffer rawKind = buffer == Buffer::Roughness || buffer == Buffer::F0 ? Buffer::F0 : Buffer::Render;
  if (std::optional<std::string> problem = findInvalidValue(image, rawKind))
    throw Error(path.string(), "stored values: " + *problem);
  if (buffer == Buffer::Normal || buffer == Buffer::Depth) maskByAlpha(&image, prior.alpha);
  if (source.alphaBackground) *alpha = std::move(prior.alpha);
  return image;
}

}  // namespace

Image readCameraNormalPrior(const fs::path& root, const CaptureSource& source, const DatasetView& view) {
  const fs::path path = root / view.files[int(Buffer::Normal)];
  Image alpha;
  return decodeNormalPrior(readStoredPrior(path, source, view, Buffer::Normal, &alpha), isDisplayReferred(path));
}

Image loadCaptureBuffer(const fs::path& root, const CaptureSource& source, const DatasetView& view, Buffer buffer) {
  const std::string& relative = view.files[int(buffer)];
  GLINT_CHECK(!relative.empty(), "loadCaptureBuffer needs a view that has the buffer");
  const fs::path path = root / relative;
  const CaptureDecoding& d = source.decoding;
  const bool metalness = isMetalnessFile(path, buffer);
  Image alpha;  // coverage, for compositing over the source's background
  Image image = readStoredPrior(path, source, view, buffer, &alpha);
  const Camera& camera = view.camera;
  const bool display = isDisplayReferred(path);
  const RayIntrinsics k{camera.fx, camera.fy, camera.cx, camera.cy};
  switch (buffer) {
    case Buffer::Render:
    case Buffer::Diffuse:
    case Buffer::Specular:
      if (display) {
        const bool photo = !source.priorTransforms && relative.rfind("priors/", 0) != 0;
        image = decodeRadiance(std::move(image), photo ? d.photoTransfer : d.priorTransfer, d.clampMax);
      }
      // After decoding: coverage mixes light, which adds in linear values, not in sRGB codes.
      if (!alpha.empty()) image = compositeOverBackground(image, alpha, *source.alphaBackground);
      break;
    case Buffer::Normal: {
      image = decodeNormalPrior(image, display);  // readCameraNormalPrior's vectors
      if (!d.worldNormals) {
        image = cameraNormalsToWorld(image, d.normalAxes, camera.rotation());
      }
      break;
    }
    case Buffer::Depth:
      switch (d.depth) {
        case CaptureDecoding::Depth::Distance:
          break;
        case CaptureDecoding::Depth::ZDepth:
          image = zDepthToDistance(image, k);
          break;
        case CaptureDecoding::Depth::Relative:
        case CaptureDecoding::Depth::RelativeDisparity:
          image = zDepthToDistance(alignedZDepth(image, source, view, path), k);
          break;
      }
      break;
    case Buffer::Roughness:
      image = toPerceptualRoughness(image, d.roughness);
      break;
    case Buffer::F0:
      if (metalness) image = f0FromMetalness(Image(), image);
      break;
  }
  if (std::optional<std::string> problem = findInvalidValue(image, buffer)) throw Error(path.string(), *problem);
  return image;
}

}  // namespace glint
