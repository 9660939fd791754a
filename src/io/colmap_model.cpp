// A COLMAP model folder: choosing the form, cross-file checks, and writing.
#include "io/colmap_model.h"

#include <unordered_set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/printable_text.h"
#include "io/colmap_binary.h"
#include "io/colmap_camera_models.h"
#include "io/colmap_text.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

const char* extension(ColmapFormat format) { return format == ColmapFormat::Binary ? ".bin" : ".txt"; }

std::string filePath(const std::string& folder, const char* stem, ColmapFormat format) {
  return (fs::path(folder) / (std::string(stem) + extension(format))).string();
}

}  // namespace

ColmapModel parseColmapModel(const ColmapFiles& files, ColmapFormat format, const std::string& folderName) {
  std::string camerasName = filePath(folderName, "cameras", format);
  std::string imagesName = filePath(folderName, "images", format);
  std::string pointsName = filePath(folderName, "points3D", format);
  ColmapModel model;
  model.format = format;
  if (format == ColmapFormat::Binary) {
    model.cameras = parseColmapCamerasBinary(files.cameras, camerasName);
    model.images = parseColmapImagesBinary(files.images, imagesName);
    model.points = parseColmapPointsBinary(files.points, pointsName);
  } else {
    model.cameras = parseColmapCamerasText(files.cameras, camerasName);
    model.images = parseColmapImagesText(files.images, imagesName);
    model.points = parseColmapPointsText(files.points, pointsName);
  }
  std::unordered_set<uint32_t> cameraIds;
  for (const ColmapCamera& camera : model.cameras) cameraIds.insert(camera.id);
  for (const ColmapImage& image : model.images)
    if (!cameraIds.count(image.cameraId))
      throw Error(imagesName, "image " + std::to_string(image.id) + " (\"" + printableText(image.name) +
                                  "\") refers to camera " + std::to_string(image.cameraId) + ", which " +
                                  fs::path(camerasName).filename().string() + " does not define");
  return model;
}

namespace {

// The model's files (binary when cameras.bin exists, as COLMAP prefers), read and parsed.
ColmapModel readModelFiles(const fs::path& folder, ColmapFiles* files) {
  std::error_code ignored;
  if (!fs::is_directory(folder, ignored)) throw Error(folder.string(), "COLMAP model folder not found");
  // COLMAP itself prefers the binary files when a folder holds both forms.
  ColmapFormat format = fs::exists(folder / "cameras.bin", ignored) ? ColmapFormat::Binary : ColmapFormat::Text;
  if (format == ColmapFormat::Text && !fs::exists(folder / "cameras.txt", ignored))
    throw Error(folder.string(), "not a COLMAP sparse model: it has neither cameras.bin nor cameras.txt (a model "
                                 "is the folder holding cameras, images and points3D, usually sparse/0)");
  const char* ext = extension(format);
  files->cameras = readTextFile(folder / (std::string("cameras") + ext));
  files->images = readTextFile(folder / (std::string("images") + ext));
  files->points = readTextFile(folder / (std::string("points3D") + ext));
  return parseColmapModel(*files, format, folder.string());
}

}  // namespace

ColmapModel readColmapModelAnyCamera(const fs::path& folder) {
  ColmapFiles files;
  return readModelFiles(folder, &files);
}

ColmapModel readColmapModel(const fs::path& folder) {
  ColmapFiles files;
  ColmapModel model = readModelFiles(folder, &files);
  ColmapFormat format = model.format;

  // Glint traces pinhole rays: a distorted camera is refused here, with the command that
  // undistorts it, rather than trained with a wrong projection.
  std::string camerasName = filePath(folder.string(), "cameras", format);
  std::vector<int> lines;
  if (format == ColmapFormat::Text) lines = colmapTextRecordLines(files.cameras);
  for (size_t i = 0; i < model.cameras.size(); ++i) {
    std::string where = format == ColmapFormat::Binary ? "record " + std::to_string(i) + ": "
                                                       : "line " + std::to_string(lines.at(i)) + ": ";
    colmapPinholeIntrinsics(model.cameras[i], camerasName, where, folder);
  }
  return model;
}

ColmapFiles formatColmapModel(const ColmapModel& model, ColmapFormat format) {
  ColmapFiles files;
  if (format == ColmapFormat::Binary) {
    files.cameras = formatColmapCamerasBinary(model.cameras);
    files.images = formatColmapImagesBinary(model.images);
    files.points = formatColmapPointsBinary(model.points);
  } else {
    files.cameras = formatColmapCamerasText(model.cameras);
    files.images = formatColmapImagesText(model.images);
    files.points = formatColmapPointsText(model.points);
  }
  return files;
}

namespace {

void writeColmapModel(const fs::path& folder, const ColmapModel& model, ColmapFormat format) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw Error(folder.string(), "cannot create folder: " + ec.message());
  ColmapFiles files = formatColmapModel(model, format);
  const char* ext = extension(format);
  writeTextAtomically(folder / (std::string("cameras") + ext), files.cameras);
  writeTextAtomically(folder / (std::string("images") + ext), files.images);
  writeTextAtomically(folder / (std::string("points3D") + ext), files.points);
}

}  // namespace

void writeColmapModelText(const fs::path& folder, const ColmapModel& model) {
  writeColmapModel(folder, model, ColmapFormat::Text);
}

void writeColmapModelBinary(const fs::path& folder, const ColmapModel& model) {
  writeColmapModel(folder, model, ColmapFormat::Binary);
}

}  // namespace glint
