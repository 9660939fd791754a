// validateDataset: reads every file of a dataset and collects every problem instead of
// stopping at the first, so that one run tells the user all that needs fixing.
#include "scene/dataset.h"

#include <array>
#include <cmath>
#include <exception>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"
#include "io/point_cloud.h"
#include "io/transforms_json.h"
#include "scene/buffer_codec.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// An Error's message without the "file: " prefix it carries.
DatasetProblem problemFrom(const Error& e, const fs::path& fallbackFile) {
  std::string file = e.file().empty() ? fallbackFile.string() : e.file();
  std::string message = e.what();
  if (!e.file().empty() && message.rfind(e.file() + ": ", 0) == 0) message.erase(0, e.file().size() + 2);
  return {file, message};
}

// What validation found for one buffer file of one view.
struct BufferCheck {
  std::string file;
  bool loaded = false;
  int width = 0, height = 0;
  std::vector<std::string> problems;  // about `file`
};

// Reads and checks the seven buffers of one view; everything except the split-wide size.
std::array<BufferCheck, kBufferCount> checkView(const fs::path& root, const std::string& filePath) {
  std::array<BufferCheck, kBufferCount> checks;
  std::array<Image, kBufferCount> images;
  for (Buffer b : kAllBuffers) {
    BufferCheck& check = checks[int(b)];
    fs::path base = root / bufferFilePath(filePath, b);
    check.file = base.string();
    try {
      std::optional<fs::path> path = findBufferFileAt(base);
      if (!path) throw Error(base.string(), missingBufferMessage(base, b));
      check.file = path->string();
      Image image = readBufferFile(*path, b);
      check.loaded = true;
      check.width = image.width;
      check.height = image.height;
      if (auto problem = findInvalidValue(image, b)) check.problems.push_back(*problem);
      if (b == Buffer::Depth || b == Buffer::Normal) images[int(b)] = std::move(image);
    } catch (const Error& e) {
      check.problems.push_back(problemFrom(e, check.file).message);
    } catch (const std::exception& e) {  // e.g. a filesystem error for an unreadable folder
      check.problems.push_back(e.what());
    }
  }
  const Image& depth = images[int(Buffer::Depth)];
  const Image& normal = images[int(Buffer::Normal)];
  if (!depth.empty() && !normal.empty() && depth.width == normal.width && depth.height == normal.height)
    if (auto problem = findNonUnitNormal(normal, depth)) checks[int(Buffer::Normal)].problems.push_back(*problem);
  return checks;
}

void validateSplit(const fs::path& root, const std::string& name, std::vector<DatasetProblem>& problems) {
  fs::path transformsPath = root / ("transforms_" + name + ".json");
  if (!fs::exists(transformsPath)) {
    problems.push_back({transformsPath.string(), "file not found"});
    return;
  }
  TransformsFile transforms;
  try {
    transforms = readTransformsJson(transformsPath);
  } catch (const Error& e) {
    problems.push_back(problemFrom(e, transformsPath));
    return;
  }
  if (transforms.frames.empty()) {
    problems.push_back({transformsPath.string(), "frames is empty: a split needs at least one view"});
    return;
  }

  std::vector<std::string> filePaths;
  for (const TransformsFrame& frame : transforms.frames) {
    if (isRenderFilePath(frame.filePath))
      filePaths.push_back(frame.filePath);
    else
      problems.push_back({transformsPath.string(), "file_path \"" + frame.filePath +
                                                       "\" does not name a render image (expected "
                                                       "SPLIT/render/render_NAME)"});
  }

  // Views are independent: read them in parallel, report in frame order.
  std::vector<std::array<BufferCheck, kBufferCount>> views(filePaths.size());
  parallelFor(int64_t(filePaths.size()), 1, [&](int64_t i) { views[i] = checkView(root, filePaths[i]); });

  // Every image of a split must have one size: the first one read sets it.
  const BufferCheck* reference = nullptr;
  for (const auto& view : views)
    for (const BufferCheck& check : view)
      if (!reference && check.loaded) reference = &check;

  for (const auto& view : views)
    for (const BufferCheck& check : view) {
      if (check.loaded && (check.width != reference->width || check.height != reference->height))
        problems.push_back({check.file, "image is " + std::to_string(check.width) + "x" +
                                            std::to_string(check.height) + " pixels, but the " + name +
                                            " split's images are " + std::to_string(reference->width) + "x" +
                                            std::to_string(reference->height) + " (the size of " +
                                            fs::path(reference->file).filename().string() + ")"});
      for (const std::string& message : check.problems) problems.push_back({check.file, message});
    }
}

void validatePointCloud(const fs::path& path, std::vector<DatasetProblem>& problems) {
  try {
    PointCloud cloud = readPointCloud(path);
    if (cloud.positions.empty()) problems.push_back({path.string(), "contains no points"});
    for (size_t i = 0; i < cloud.positions.size(); ++i)
      if (!isFinite(cloud.positions[i])) {
        problems.push_back({path.string(), "point " + std::to_string(i) + " has a non-finite position"});
        break;
      }
  } catch (const Error& e) {
    problems.push_back(problemFrom(e, path));
  } catch (const std::exception& e) {
    problems.push_back({path.string(), e.what()});
  }
}

}  // namespace

std::vector<DatasetProblem> validateDataset(const fs::path& root) {
  std::vector<DatasetProblem> problems;
  if (!fs::is_directory(root)) {
    problems.push_back({root.string(), fs::exists(root) ? "is not a folder" : "folder not found"});
    return problems;
  }
  // A dataset may hold one split only; it must hold one.
  const bool hasTrain = fs::exists(root / "transforms_train.json"), hasTest = fs::exists(root / "transforms_test.json");
  for (const char* split : {"train", "test"})
    if ((std::string(split) == "train" ? hasTrain : hasTest) || (!hasTrain && !hasTest))
      validateSplit(root, split, problems);
  fs::path cloud = root / "point_cloud_dense.ply";
  if (fs::exists(cloud)) validatePointCloud(cloud, problems);
  return problems;
}

}  // namespace glint
