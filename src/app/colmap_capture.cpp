// glint capture's pipeline: COLMAP's steps run as subprocesses with progress, then the
// largest model, undistorted when its cameras are not pinholes, assembled into a capture.
#include "app/colmap_capture.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/activity.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/subprocess.h"
#include "io/colmap_camera_models.h"
#include "io/colmap_log.h"
#include "io/colmap_model.h"
#include "scene/capture_dataset.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// Written first into the work folder, so that a folder holding it is known to be ours:
// the only kind --force replaces and a leftover work folder may be removed.
constexpr const char* kMarkerName = ".glint-capture";

void say(const std::string& message) { std::fprintf(stderr, "glint capture: %s\n", message.c_str()); }

bool isOurs(const fs::path& folder) {
  std::error_code ignored;
  return fs::is_regular_file(folder / kMarkerName, ignored);
}

// The photographs COLMAP will see: PHOTOS/images when it holds any (a capture's layout),
// else PHOTOS itself. Only JPEG and PNG files directly inside are taken, sorted by name.
struct PhotoFolder {
  fs::path root;    // PHOTOS
  fs::path images;  // where the photographs are
  std::vector<fs::path> photos;
};

PhotoFolder findPhotographs(const fs::path& root) {
  std::error_code ignored;
  if (!fs::exists(root, ignored)) throw Error(root.string(), "no such folder");
  if (!fs::is_directory(root, ignored)) throw Error(root.string(), "is not a folder (give the folder of photographs)");
  PhotoFolder folder{root, root / "images", photographsIn(root / "images")};
  if (folder.photos.empty()) folder = {root, root, photographsIn(root)};
  if (folder.photos.empty())
    throw Error(root.string(), "holds no photographs: no JPEG or PNG file in it or in its images/ folder");
  if (folder.photos.size() < 3)
    throw Error(folder.images.string(), "holds " + std::to_string(folder.photos.size()) +
                                            " photograph(s); structure from motion needs at least 3 of one scene");
  return folder;
}

// OUTPUT must not hold what the user made, nor be or contain the photographs.
void checkOutput(const CaptureRequest& request, const PhotoFolder& photos) {
  std::error_code ignored;
  fs::path out = fs::weakly_canonical(fs::absolute(request.output), ignored);
  fs::path in = fs::weakly_canonical(fs::absolute(photos.root), ignored);
  if (out == in || std::mismatch(in.begin(), in.end(), out.begin(), out.end()).first == in.end())
    throw Error(request.output.string(), "is inside the photographs' folder " + photos.root.string() +
                                             "; write the capture somewhere else");
  if (std::mismatch(out.begin(), out.end(), in.begin(), in.end()).first == out.end())
    throw Error(request.output.string(), "holds the photographs' folder; write the capture somewhere else");
  if (!fs::exists(request.output, ignored)) return;
  if (!fs::is_directory(request.output, ignored))
    throw Error(request.output.string(), "exists and is not a folder");
  if (fs::is_empty(request.output, ignored)) return;
  if (!isOurs(request.output))
    throw Error(request.output.string(), "exists and was not written by glint capture; choose another folder");
  if (!request.force)
    throw Error(request.output.string(), "already holds a capture; pass --force to replace it");
}

// Hard links when the file system allows them (the photographs are not copied), else copies.
void linkOrCopy(const fs::path& from, const fs::path& to) {
  std::error_code error;
  fs::create_hard_link(from, to, error);
  if (error) fs::copy_file(from, to, fs::copy_options::overwrite_existing);
}

void linkTree(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(from)) {
    fs::path target = to / fs::relative(entry.path(), from);
    if (entry.is_directory()) fs::create_directories(target);
    else if (entry.is_regular_file()) linkOrCopy(entry.path(), target);
  }
}

// The work folder beside OUTPUT, removed when the run fails unless kept for its log.
class WorkFolder {
 public:
  explicit WorkFolder(const fs::path& output) {
    fs::path parent = output.parent_path().empty() ? fs::path(".") : output.parent_path();
    path_ = parent / ("." + output.filename().string() + ".glint-capture-partial");
    std::error_code ignored;
    if (fs::exists(path_, ignored)) {
      if (!isOurs(path_))
        throw Error(path_.string(), "is in the way of glint capture's work folder and was not written by it; "
                                    "remove it or choose another output");
      fs::remove_all(path_);
    }
    fs::create_directories(path_ / "colmap");
    writeTextAtomically(path_ / kMarkerName, "written by glint capture\n");
  }
  ~WorkFolder() {
    std::error_code ignored;
    if (!done_ && !keep_) fs::remove_all(path_, ignored);
  }
  WorkFolder(const WorkFolder&) = delete;
  WorkFolder& operator=(const WorkFolder&) = delete;

  const fs::path& path() const { return path_; }
  void keepForItsLog() { keep_ = true; }
  // Puts the work folder in OUTPUT's place (an earlier capture there is replaced).
  void moveTo(const fs::path& output) {
    std::error_code ignored;
    fs::path old = path_;
    old += ".old";
    fs::remove_all(old, ignored);
    if (fs::exists(output, ignored)) fs::rename(output, old);
    fs::rename(path_, output);
    fs::remove_all(old, ignored);
    done_ = true;
  }

 private:
  fs::path path_;
  bool done_ = false, keep_ = false;
};

// Runs one COLMAP tool with a progress bar, appending its output to the log. On failure
// prints the end of its output and throws.
class ColmapRunner {
 public:
  ColmapRunner(fs::path program, fs::path log, WorkFolder* work)
      : program_(std::move(program)), logPath_(std::move(log)), work_(work) {}

  std::string run(const std::string& step, const std::string& tool, const std::vector<std::string>& arguments,
                  long expectedTotal, const std::string& unit) {
    ActivityScope activity("running colmap " + tool);
    say(step + " (colmap " + tool + ")");
    std::ofstream log(logPath_, std::ios::app);
    log << "$ colmap " << tool;
    for (const std::string& a : arguments) log << ' ' << a;
    log << '\n';
    ProgramRun program{program_, {tool}, {{"QT_QPA_PLATFORM", "offscreen"}}};
    program.arguments.insert(program.arguments.end(), arguments.begin(), arguments.end());
    std::optional<ProgressBar> bar;
    if (expectedTotal > 0) bar.emplace("  " + tool, expectedTotal, unit);
    long shown = 0;
    std::deque<std::string> tail;
    std::string output;
    ProgramExit exit = runProgram(program, [&](std::string_view line) {
      log << line << '\n';
      output.append(line).push_back('\n');
      tail.emplace_back(line);
      if (tail.size() > 25) tail.pop_front();
      std::optional<ColmapProgress> progress = parseColmapProgress(line);
      if (!bar || !progress) return;
      long done = progress->total > 0 && progress->total != expectedTotal
                      ? long(std::lround(double(progress->done) / progress->total * expectedTotal))
                      : progress->done;
      done = std::min(done, expectedTotal);
      if (done > shown) bar->advance(done - shown), shown = done;
    });
    if (bar) bar->finish();
    log.flush();
    if (exit.interrupted) throw Error("interrupted while colmap " + tool + " ran; the capture was not written");
    if (!exit.ok()) {
      for (const std::string& line : tail) std::fprintf(stderr, "  | %s\n", line.c_str());
      work_->keepForItsLog();
      throw Error("colmap " + tool, describeExit(exit) + " (the end of its output is above; the whole log is " +
                                        logPath_.string() + ")");
    }
    return output;
  }

 private:
  fs::path program_;
  fs::path logPath_;
  WorkFolder* work_;
};

// PHOTOS/sparse/0's pinhole camera, shared by all its images (a synthesized capture's true
// intrinsics), or nothing when there is none to start from.
std::optional<PinholeIntrinsics> knownCamera(const PhotoFolder& photos) {
  fs::path folder = photos.root / "sparse" / "0";
  std::error_code ignored;
  if (!fs::is_directory(folder, ignored)) return std::nullopt;
  ColmapModel known;
  try {
    known = readColmapModel(folder);
  } catch (const Error& e) {
    say("not starting from the cameras of " + folder.string() + ": " + e.what());
    return std::nullopt;
  }
  if (known.cameras.empty()) return std::nullopt;
  const ColmapCamera& camera = known.cameras.front();
  for (const ColmapCamera& other : known.cameras)
    if (other.params != camera.params || other.width != camera.width || other.height != camera.height)
      return std::nullopt;
  return colmapPinholeIntrinsics(camera, folder.string(), "", folder);
}

// Whether a camera's pixels are square: fx and fy within 0.1% of each other.
bool squarePixels(const PinholeIntrinsics& k) { return std::abs(k.fx - k.fy) <= 1e-3 * std::max(k.fx, k.fy); }

// The camera model to estimate, and why.
std::string chooseCameraModel(const CaptureRequest& request, bool hasPriors,
                              const std::optional<PinholeIntrinsics>& known) {
  if (request.cameraModel != "auto") {
    if (!findColmapCameraModel(request.cameraModel))
      throw Error("--camera-model " + request.cameraModel +
                  ": not a COLMAP camera model (SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV, "
                  "OPENCV_FISHEYE, FULL_OPENCV, FOV, SIMPLE_RADIAL_FISHEYE, RADIAL_FISHEYE, THIN_PRISM_FISHEYE)");
    say("camera model: " + request.cameraModel + " (--camera-model)");
    return request.cameraModel;
  }
  if (hasPriors && known && !squarePixels(*known)) {
    say("camera model: PINHOLE (the photographs come with priors/, which undistortion would leave misaligned; "
        "sparse/0's pixels are not square)");
    return "PINHOLE";
  }
  if (hasPriors) {
    // One focal length: with fx and fy free, COLMAP 3.8's bundle adjustment let fy drift up
    // to 7% from fx on a ring of views (the gallery's 24), against 0.5% with one.
    say("camera model: SIMPLE_PINHOLE (square pixels, no distortion: the photographs come with priors/, which "
        "undistortion would leave misaligned)");
    return "SIMPLE_PINHOLE";
  }
  say("camera model: OPENCV (focal lengths, principal point and lens distortion; undistorted after mapping)");
  return "OPENCV";
}

// The known camera's intrinsics in the parameter order of `model`, as COLMAP's
// --ImageReader.camera_params wants them, or "" when there are none to use.
std::string knownIntrinsics(const std::optional<PinholeIntrinsics>& known, const PhotoFolder& photos,
                            const std::string& model) {
  if (!known) return "";
  const PinholeIntrinsics& k = *known;
  std::ostringstream s;
  s.precision(17);
  double f = 0.5 * (k.fx + k.fy);
  if (model == "SIMPLE_PINHOLE") s << f << ',' << k.cx << ',' << k.cy;
  else if (model == "SIMPLE_RADIAL") s << f << ',' << k.cx << ',' << k.cy << ",0";
  else if (model == "RADIAL") s << f << ',' << k.cx << ',' << k.cy << ",0,0";
  else if (model == "PINHOLE") s << k.fx << ',' << k.fy << ',' << k.cx << ',' << k.cy;
  else if (model == "OPENCV") s << k.fx << ',' << k.fy << ',' << k.cx << ',' << k.cy << ",0,0,0,0";
  else return "";
  say("starting from the intrinsics of " + (photos.root / "sparse" / "0").string() + " (" + s.str() +
      "); the mapper refines them");
  return s.str();
}

struct ChosenModel {
  fs::path folder;
  ColmapModel model;
  int count = 0;  // models COLMAP made
};

// The model that registered the most images (COLMAP splits a scene it cannot join).
ChosenModel largestModel(const fs::path& sparse, const std::string& log) {
  ChosenModel best;
  std::vector<fs::path> folders;
  std::error_code ignored;
  for (const fs::directory_entry& entry : fs::directory_iterator(sparse, ignored))
    if (entry.is_directory() && fs::exists(entry.path() / "images.bin", ignored)) folders.push_back(entry.path());
  std::sort(folders.begin(), folders.end());
  best.count = int(folders.size());
  for (const fs::path& folder : folders) {
    ColmapModel model = readColmapModelAnyCamera(folder);
    if (best.folder.empty() || model.images.size() > best.model.images.size())
      best = {folder, std::move(model), best.count};
  }
  if (best.folder.empty())
    throw Error("colmap mapper", "registered no photographs: they need more texture and more overlap between "
                                 "neighbouring views (log: " + log + ")");
  return best;
}

void copyModel(const fs::path& from, const fs::path& to) {
  fs::create_directories(to);
  for (const char* name : {"cameras.bin", "images.bin", "points3D.bin"})
    fs::copy_file(from / name, to / name, fs::copy_options::overwrite_existing);
}

std::vector<std::string> matcherArguments(const CaptureRequest& request, const fs::path& database,
                                          const std::string& threads, std::string* tool) {
  if (request.matcher == "exhaustive") *tool = "exhaustive_matcher";
  else if (request.matcher == "sequential") *tool = "sequential_matcher";
  else throw Error("--matcher " + request.matcher + ": expected exhaustive or sequential");
  return {"--database_path", database.string(), "--SiftMatching.use_gpu", "0", "--SiftMatching.num_threads", threads};
}

// Where a run keeps COLMAP's files inside the work folder.
struct ColmapPaths {
  fs::path folder, images, database, sparse, log;
  explicit ColmapPaths(const fs::path& work)
      : folder(work / "colmap"),
        images(folder / "images"),
        database(folder / "database.db"),
        sparse(folder / "sparse"),
        log(folder / "log.txt") {}
};

// Features, matches and the sparse models, each step a COLMAP tool with its progress.
void runStructureFromMotion(const CaptureRequest& request, const std::string& model, const std::string& intrinsics,
                            long photos, const ColmapPaths& paths, ColmapRunner* runner) {
  std::string threads = request.threads > 0 ? std::to_string(request.threads) : "-1";
  std::vector<std::string> extract = {"--database_path", paths.database.string(), "--image_path",
                                      paths.images.string(), "--ImageReader.camera_model", model,
                                      "--ImageReader.single_camera", request.cameraPerImage ? "0" : "1",
                                      "--SiftExtraction.use_gpu", "0", "--SiftExtraction.num_threads", threads};
  if (!intrinsics.empty()) extract.insert(extract.end(), {"--ImageReader.camera_params", intrinsics});
  runner->run("extracting SIFT features", "feature_extractor", extract, photos, "photos");

  std::string matcher;
  std::vector<std::string> match = matcherArguments(request, paths.database, threads, &matcher);
  bool exhaustive = request.matcher == "exhaustive";
  // The exhaustive matcher works in blocks of 50 x 50 photographs (its default block_size).
  long blocks = (photos + 49) / 50;
  runner->run(exhaustive ? "matching every pair of photographs" : "matching neighbouring photographs", matcher, match,
              exhaustive ? blocks * blocks : photos, exhaustive ? "blocks" : "photos");

  fs::create_directories(paths.sparse);
  runner->run("mapping: incremental structure from motion", "mapper",
              {"--database_path", paths.database.string(), "--image_path", paths.images.string(), "--output_path",
               paths.sparse.string(), "--Mapper.num_threads", threads},
              photos, "registered");
}

// images/, sparse/0, priors/ and capture.json of the capture, from the chosen model:
// undistorted by COLMAP when its cameras are not pinholes, else linked as they are.
void assembleCapture(const PhotoFolder& photos, bool hasPriors, const ChosenModel& chosen, const ColmapPaths& paths,
                     const fs::path& work, ColmapRunner* runner, CaptureResult* result) {
  result->undistorted = std::any_of(chosen.model.cameras.begin(), chosen.model.cameras.end(),
                                    [](const ColmapCamera& camera) { return hasLensDistortion(camera); });
  if (result->undistorted) {
    fs::path undistorted = paths.folder / "undistorted";
    runner->run("undistorting the photographs to pinhole cameras", "image_undistorter",
                {"--image_path", paths.images.string(), "--input_path", chosen.folder.string(), "--output_path",
                 undistorted.string(), "--output_type", "COLMAP"},
                result->registered, "photos");
    fs::rename(undistorted / "images", work / "images");
    copyModel(undistorted / "sparse", work / "sparse" / "0");
    fs::remove_all(undistorted);
  } else {
    fs::create_directories(work / "images");
    for (const fs::path& photo : photos.photos)
      linkOrCopy(paths.images / photo.filename(), work / "images" / photo.filename());
    copyModel(chosen.folder, work / "sparse" / "0");
  }
  if (hasPriors && !result->undistorted) {
    linkTree(photos.root / "priors", work / "priors");
    result->priorsKept = true;
  } else if (hasPriors) {
    say("warning: priors/ left out: the photographs were undistorted and the priors were not (--camera-model "
        "PINHOLE keeps them)");
  }
  std::error_code ignored;
  if (fs::is_regular_file(photos.root / "capture.json", ignored))
    fs::copy_file(photos.root / "capture.json", work / "capture.json");
}

// The kept model's figures from COLMAP's model_analyzer (the mean of the points' errors
// when its output is not understood). Reading the model also proves Glint can open it.
void measureModel(const fs::path& model, ColmapRunner* runner, CaptureResult* result) {
  std::string analysis = runner->run("measuring the model", "model_analyzer", {"--path", model.string()}, 0, "");
  ColmapModel kept = readColmapModel(model);
  result->points = long(kept.points.size());
  if (std::optional<ColmapModelStats> stats = parseColmapModelStats(analysis)) {
    result->meanTrackLength = stats->meanTrackLength;
    result->meanReprojectionError = stats->meanReprojectionError;
    return;
  }
  double sum = 0;
  for (const ColmapPoint& point : kept.points) sum += point.error;
  result->meanReprojectionError = kept.points.empty() ? 0 : sum / double(kept.points.size());
}

std::vector<std::string> photographsLeftOut(const PhotoFolder& photos, const ColmapModel& model) {
  std::vector<std::string> left;
  for (const fs::path& photo : photos.photos) {
    std::string name = photo.filename().string();
    if (std::none_of(model.images.begin(), model.images.end(),
                     [&](const ColmapImage& image) { return image.name == name; }))
      left.push_back(name);
  }
  return left;
}

}  // namespace

std::string colmapInstallAdvice() {
  return "COLMAP is not installed: install Debian's with `apt-get install colmap` (or scripts/install-deps.sh "
         "--colmap), or name the program with --colmap PATH";
}

CaptureResult reconstructCapture(const CaptureRequest& request) {
  auto start = std::chrono::steady_clock::now();
  PhotoFolder photos = findPhotographs(request.photos);
  checkOutput(request, photos);
  std::optional<fs::path> program = findProgram(request.colmap);
  if (!program) throw Error(request.colmap, colmapInstallAdvice());
  std::error_code ignored;
  bool hasPriors = photos.images != photos.root && fs::is_directory(photos.root / "priors", ignored);
  std::optional<PinholeIntrinsics> known = request.useKnownIntrinsics ? knownCamera(photos) : std::nullopt;
  std::string model = chooseCameraModel(request, hasPriors, known);
  std::string intrinsics = knownIntrinsics(known, photos, model);

  WorkFolder work(request.output);
  ColmapPaths paths(work.path());
  fs::create_directories(paths.images);
  for (const fs::path& photo : photos.photos) linkOrCopy(photo, paths.images / photo.filename());
  CaptureResult result;
  result.photographs = int(photos.photos.size());
  say(std::to_string(result.photographs) + " photographs in " + photos.images.string());

  ColmapRunner runner(*program, paths.log, &work);
  runStructureFromMotion(request, model, intrinsics, result.photographs, paths, &runner);
  ChosenModel chosen = largestModel(paths.sparse, paths.log.string());
  result.models = chosen.count;
  result.registered = int(chosen.model.images.size());
  result.cameraModel = chosen.model.cameras.empty() ? model : chosen.model.cameras.front().model;
  result.unregistered = photographsLeftOut(photos, chosen.model);
  assembleCapture(photos, hasPriors, chosen, paths, work.path(), &runner, &result);
  measureModel(work.path() / "sparse" / "0", &runner, &result);
  work.moveTo(request.output);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace glint
