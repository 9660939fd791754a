// Opening the NeRF-synthetic layout: its transforms files, its image files, and the
// compositing of their alpha.
#include "scene/nerf_synthetic.h"

#include <set>

#include "core/error.h"
#include "core/input_file.h"
#include "core/printable_text.h"
#include "io/json_file.h"
#include "io/transforms_json.h"
#include "scene/capture_dataset.h"
#include "scene/dataset.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// Extensions tried for a file_path given without one; the layout's own is .png.
constexpr const char* kImageExtensions[] = {".png", ".exr", ".tiff", ".tif", ".jpg", ".jpeg", ".PNG", ".JPG"};

// The image a frame names, relative to root, or "" when none exists. The transforms reader
// strips .png/.exr/.tif(f) from file_path, so the extension is found again here.
std::string findImage(const fs::path& root, const std::string& filePath) {
  // Presence, not a regular file: a FIFO or a device there is refused by name when read.
  for (const char* ext : kImageExtensions)
    if (pathPresent(root / (filePath + ext))) return filePath + ext;
  if (pathPresent(root / filePath)) return filePath;  // a .jpg named in full
  return "";
}

// "train/r_0" -> "r_0": the name a view's renders and metrics carry. Frames in subfolders
// keep them, joined by '_', so that names stay unique.
std::string viewName(const std::string& filePath) {
  std::string name = filePath;
  if (size_t slash = name.find('/'); slash != std::string::npos) name.erase(0, slash + 1);
  for (char& c : name)
    if (c == '/') c = '_';
  return name;
}

DatasetSplit readSplit(const fs::path& root, const fs::path& file, const std::string& name, bool requireImages) {
  DatasetSplit split;
  split.name = name;
  if (!fs::exists(file)) return split;
  TransformsFile transforms = readTransformsJson(file);
  if (transforms.frames.empty()) throw Error(file.string(), "frames is empty: a split needs at least one view");
  std::set<std::string> names;
  for (const TransformsFrame& frame : transforms.frames) {
    DatasetView view;
    const std::string stem = viewName(frame.filePath);
    if (!names.insert(stem).second)
      throw Error(file.string(), "two frames have the image name \"" + printableText(stem) + "\" (" +
                                     printableText(frame.filePath) + ")");
    // Where renders and evaluations of the view are written, as for every layout.
    view.filePath = name + "/render/render_" + stem;
    view.files[int(Buffer::Render)] = findImage(root, frame.filePath);
    if (view.files[int(Buffer::Render)].empty() && requireImages)
      throw Error(quotedPath(root / (frame.filePath + ".png")),
                  "not found: " + file.filename().string() + " names this image");
    view.camera = Camera::fromFieldOfView(frame.transformMatrix, transforms.cameraAngleX, 1, 1);
    split.views.push_back(std::move(view));
  }
  // One size per split, from its first image (loadCaptureBuffer holds every image to it).
  const std::string& first = split.views[0].files[int(Buffer::Render)];
  if (first.empty()) return split;
  const Image image = readImage(root / first);
  split.width = image.width;
  split.height = image.height;
  for (DatasetView& view : split.views) view.camera = view.camera.resized(image.width, image.height);
  return split;
}

}  // namespace

Rgb backgroundRadiance(AlphaBackground background) {
  return Rgb(background == AlphaBackground::White ? 1.0f : 0.0f);
}

bool isNerfSyntheticFolder(const fs::path& root) {
  if (fs::is_directory(root / "sparse")) return false;  // the paper's layout with predicted buffers
  for (const char* split : {"train", "test", "val"}) {
    const fs::path file = root / ("transforms_" + std::string(split) + ".json");
    if (!fs::is_regular_file(file)) continue;
    // Decided by the first frame's file_path alone, so that a file with another problem (a
    // bad camera_angle_x) is read by its own layout's reader, which reports that problem
    // once, instead of by the paper layout's, which would also refuse every file_path.
    try {
      const nlohmann::json j = readJsonFile(file);
      const nlohmann::json* frames = j.is_object() && j.contains("frames") ? &j["frames"] : nullptr;
      if (!frames || !frames->is_array() || frames->empty() || !(*frames)[0].is_object()) return false;
      const nlohmann::json& path = (*frames)[0].value("file_path", nlohmann::json());
      return path.is_string() && !isRenderFilePath(path.get<std::string>());
    } catch (const Error&) {
      return false;  // opened as the paper's layout, whose reader reports the problem
    }
  }
  return false;
}

void openNerfSynthetic(const fs::path& root, AlphaBackground background, bool requireImages, DatasetSplit* train,
                       DatasetSplit* test, CaptureSource* source) {
  const fs::path testFile = root / "transforms_test.json", valFile = root / "transforms_val.json";
  const bool valAsTest = !fs::exists(testFile) && fs::exists(valFile);
  *train = readSplit(root, root / "transforms_train.json", "train", requireImages);
  *test = readSplit(root, valAsTest ? valFile : testFile, "test", requireImages);
  source->alphaBackground = backgroundRadiance(background);
  source->splitFiles = fs::exists(root / "transforms_train.json") ? "transforms_train.json" : "";
  if (!test->views.empty())
    source->splitFiles += std::string(source->splitFiles.empty() ? "" : ", ") +
                          (valAsTest ? "transforms_val.json as the test split" : "transforms_test.json");
  source->description = "NeRF-synthetic layout: " + std::to_string(train->views.size()) + " train and " +
                        std::to_string(test->views.size()) + " test views, final images only, composited over " +
                        (background == AlphaBackground::White ? "white" : "black");
}

Image compositeOverBackground(const Image& linearRgb, const Image& alpha, Rgb background) {
  GLINT_CHECK(linearRgb.channels == 3 && alpha.channels == 1 && linearRgb.width == alpha.width &&
                  linearRgb.height == alpha.height,
              "compositeOverBackground: an RGB image and its alpha of one size expected");
  Image out = linearRgb;
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const float a = alpha.at(x, y);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = a * linearRgb.at(x, y, c) + (1.0f - a) * background[c];
    }
  return out;
}

}  // namespace glint
