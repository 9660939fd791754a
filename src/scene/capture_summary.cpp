// What `glint info` prints for a real capture: its cameras, which buffers its views have,
// the depth fits, a check of the declared normal space against the data, and the problems
// found by loading every buffer.
#include "scene/capture_summary.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <mutex>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"
#include "core/parallel.h"
#include "scene/capture_dataset.h"
#include "scene/normal_space_guess.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%.*f", digits, v);
  return buf;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

const char* depthName(CaptureDecoding::Depth d) {
  switch (d) {
    case CaptureDecoding::Depth::Distance:
      return "distance";
    case CaptureDecoding::Depth::ZDepth:
      return "z";
    case CaptureDecoding::Depth::Relative:
      return "relative";
    case CaptureDecoding::Depth::RelativeDisparity:
      return "relative_disparity";
  }
  return "?";
}

std::string cameraLine(const DatasetSplit& split) {
  if (split.views.empty()) return "  " + split.name + ": no views\n";
  int minW = 1 << 30, maxW = 0, minH = 1 << 30, maxH = 0;
  double minF = 1e300, maxF = 0;
  for (const DatasetView& v : split.views) {
    minW = std::min(minW, v.camera.width), maxW = std::max(maxW, v.camera.width);
    minH = std::min(minH, v.camera.height), maxH = std::max(maxH, v.camera.height);
    minF = std::min({minF, v.camera.fx, v.camera.fy}), maxF = std::max({maxF, v.camera.fx, v.camera.fy});
  }
  std::string size = std::to_string(minW) + "x" + std::to_string(minH);
  if (minW != maxW || minH != maxH) size += " to " + std::to_string(maxW) + "x" + std::to_string(maxH);
  return "  " + split.name + ": " + std::to_string(split.views.size()) + " views, " + size + ", focal lengths " +
         fixed(minF, 1) + (maxF > minF ? " to " + fixed(maxF, 1) : "") + " px\n";
}

// The symbolic links inside a capture, which Glint follows (docs/capture-format.md): said
// out loud, since they can lead to files outside the folder. The walk does not enter linked
// folders and stops after a bounded count of entries.
std::string linksFollowed(const fs::path& root) {
  constexpr int kMaxEntries = 200000, kExamples = 3;
  std::error_code ec;
  int entries = 0, links = 0;
  std::string examples;
  for (fs::recursive_directory_iterator it(root, ec), end; !ec && it != end && entries < kMaxEntries;
       it.increment(ec), ++entries) {
    if (!it->is_symlink(ec)) continue;
    if (links++ < kExamples) {
      std::error_code readError;
      const fs::path target = fs::read_symlink(it->path(), readError);
      examples += "\n  " + quotedPath(fs::relative(it->path(), root, readError)) + " -> " + quotedPath(target);
    }
  }
  if (links == 0) return "";
  return "\nsymbolic links followed: " + std::to_string(links) + (links > kExamples ? " (the first " + std::to_string(kExamples) + ")" : "") +
         examples + "\n";
}

}  // namespace

std::string normalSpaceCheck(const Dataset& dataset) {
  const DatasetSplit& split = dataset.train();
  std::vector<Image> normals, zDepths;
  std::vector<NormalSpaceView> views;
  normals.reserve(8), zDepths.reserve(8);
  for (size_t i = 0; i < split.views.size() && normals.size() < 8; i += std::max<size_t>(1, split.views.size() / 8)) {
    const DatasetView& view = split.views[i];
    if (view.files[int(Buffer::Normal)].empty()) continue;
    try {
      normals.push_back(readCameraNormalPrior(dataset.root(), *dataset.capture(), view));
    } catch (const Error&) {
      continue;  // the problem list reports it
    }
    NormalSpaceView v;
    v.normals = &normals.back();
    v.cameraToWorld = view.camera.rotation();
    v.intrinsics = {view.camera.fx, view.camera.fy, view.camera.cx, view.camera.cy};
    // The depth's surface separates camera axes that differ by a mirror (OpenGL, the paper's).
    if (!view.files[int(Buffer::Depth)].empty()) {
      try {
        zDepths.push_back(distanceToZDepth(dataset.loadBuffer(split, i, Buffer::Depth), v.intrinsics));
        v.zDepth = &zDepths.back();
      } catch (const Error&) {
      }
    }
    views.push_back(v);
  }
  if (views.empty()) return "";
  NormalSpaceGuess guess = guessNormalSpace(views);
  const CaptureDecoding& d = dataset.capture()->decoding;
  const bool declaredWorld = d.worldNormals;
  std::string line = "normal maps look like: " + guess.summary() + "\n";
  if (!declaredWorld && guess.space == NormalSpace::Camera && guess.axesConfidence > 0.5 && guess.axes != d.normalAxes)
    line += std::string("warning: capture.json declares \"normal_axes\": \"") +
            (d.normalAxes == CameraAxes::OpenGl   ? "opengl"
             : d.normalAxes == CameraAxes::OpenCv ? "opencv"
                                                  : "paper") +
            "\", but the normal maps agree better with the depth read in " + cameraAxesName(guess.axes) + " axes\n";
  if (guess.confidence > 0.5 && (guess.space == NormalSpace::World) != declaredWorld)
    line += "warning: capture.json declares \"normal_space\": \"" + std::string(declaredWorld ? "world" : "camera") +
            "\", but the normal maps read better as " + (guess.space == NormalSpace::World ? "world" : "camera") +
            " space\n";
  return line;
}

std::string describeCapture(const fs::path& root, int holdout, bool* clean) {
  std::ostringstream out;
  out << (isNerfSyntheticFolder(root) ? "dataset " : "capture ") << root.string() << "\n\n";
  std::optional<Dataset> opened;
  try {
    opened = Dataset::open(root, true, holdout);
  } catch (const Error& e) {
    if (clean) *clean = false;
    out << "problems: 1\n  " << e.what() << "\n";
    return out.str();
  }
  const Dataset& dataset = *opened;
  const CaptureSource& source = *dataset.capture();
  const CaptureDecoding& d = source.decoding;
  out << source.description << "\n";
  out << "cameras"
      << (!source.splitFiles.empty() ? " (" + source.splitFiles + ")"
          : source.priorTransforms   ? std::string(" (transforms_train.json, transforms_test.json)")
                                     : " (every " + std::to_string(holdout) + "th image from the first is a test view)")
      << "\n"
      << cameraLine(dataset.train()) << cameraLine(dataset.test());
  if (source.alphaBackground)  // the NeRF-synthetic layout has no capture.json
    out << "decoding: 8-bit images sRGB-decoded, alpha composited in linear values\n\n";
  else
    out << "decoding (capture.json): photo_transfer " << transferName(d.photoTransfer) << ", prior_transfer "
      << transferName(d.priorTransfer) << ", clamp_max " << d.clampMax << ", normals "
      << (d.worldNormals ? "world" : std::string("camera (") + cameraAxesName(d.normalAxes) + " axes)") << ", depth "
      << depthName(d.depth) << ", roughness " << (d.roughness == RoughnessKind::Alpha ? "alpha" : "perceptual")
      << ", priors "
      << (d.predictedPriors ? "predicted (glint train uses the real-capture setting unless --config is given)"
                            : "exact")
      << "\n\n";

  // Which buffers the views have.
  out << "buffers (views that have each, train / test)\n";
  for (Buffer b : kAllBuffers) {
    size_t counts[2] = {0, 0};
    for (int s = 0; s < 2; ++s)
      for (const DatasetView& v : (s == 0 ? dataset.train() : dataset.test()).views)
        counts[s] += v.files[int(b)].empty() ? 0 : 1;
    out << "  " << bufferName(b) << ": " << counts[0] << " / " << counts[1] << "\n";
  }

  // Load every buffer of every view: what training and evaluation will read.
  std::vector<DatasetProblem> problems;
  std::mutex problemsMutex;
  for (const DatasetSplit* split : {&dataset.train(), &dataset.test()})
    parallelFor(int64_t(split->views.size()), 1, [&](int64_t i) {
      for (Buffer b : kAllBuffers) {
        if (split->views[size_t(i)].files[int(b)].empty()) continue;
        try {
          dataset.loadBuffer(*split, size_t(i), b);
        } catch (const Error& e) {
          std::lock_guard<std::mutex> lock(problemsMutex);
          problems.push_back({split->views[size_t(i)].files[int(b)], e.what()});
        }
      }
    });

  std::map<std::string, DepthFit> fits = source.depthFits();
  if (!fits.empty()) {
    std::vector<double> inliers, before, after;
    for (const auto& [view, fit] : fits) {
      if (!fit.ok) continue;
      inliers.push_back(double(fit.inliers) / double(std::max(1, fit.pairsUsed)));
      before.push_back(fit.medianAbsResidualBefore);
      after.push_back(fit.medianAbsResidualAfter);
    }
    out << "\ndepth aligned to the sparse points in " << inliers.size() << " of " << fits.size()
        << " views: median inlier fraction " << fixed(median(inliers), 2) << ", median residual "
        << fixed(median(before), 4) << " before the fit, " << fixed(median(after), 4) << " after\n";
    for (const std::string& line : source.droppedDepths()) out << "warning: " << line << "\n";
  }
  const std::set<Buffer> withAlpha = source.buffersWithAlpha();
  if (!withAlpha.empty()) {
    out << "\nalpha channels read as coverage in:";
    for (Buffer b : withAlpha) out << " " << bufferName(b);
    out << " (normal and depth below " << kMinPriorCoverage << ": no surface; radiance: "
        << (source.alphaBackground ? "composited over the background" : "dropped") << "; roughness and F0: dropped)\n";
  }
  out << linksFollowed(dataset.root());
  out << "\n" << normalSpaceCheck(dataset);

  std::sort(problems.begin(), problems.end(),
            [](const DatasetProblem& a, const DatasetProblem& b) { return a.file < b.file; });
  if (clean) *clean = problems.empty();
  out << "\n";
  if (problems.empty()) {
    out << "problems: none\n";
  } else {
    out << "problems: " << problems.size() << "\n";
    for (const DatasetProblem& p : problems) out << "  " << p.message << "\n";
  }
  return out.str();
}

}  // namespace glint
