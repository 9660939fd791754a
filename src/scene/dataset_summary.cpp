// The `glint info` report: camera and buffer statistics per split, then validation problems.
#include "scene/dataset_summary.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"
#include "io/point_cloud.h"
#include "io/transforms_json.h"
#include "scene/buffer_codec.h"

namespace glint {

namespace fs = std::filesystem;

namespace {

// A plain-text table: a header row, then rows; numeric columns are right-aligned.
struct Table {
  std::vector<std::string> header;
  std::vector<bool> rightAligned;
  std::vector<std::vector<std::string>> rows;
};

std::string formatTable(const Table& table) {
  std::vector<size_t> widths(table.header.size(), 0);
  auto measure = [&](const std::vector<std::string>& row) {
    for (size_t c = 0; c < row.size(); ++c) widths[c] = std::max(widths[c], row[c].size());
  };
  measure(table.header);
  for (const auto& row : table.rows) measure(row);

  std::string out;
  auto emit = [&](const std::vector<std::string>& row) {
    std::string line = "  ";
    for (size_t c = 0; c < row.size(); ++c) {
      std::string pad(widths[c] - row[c].size(), ' ');
      line += table.rightAligned[c] ? pad + row[c] : row[c] + pad;
      if (c + 1 < row.size()) line += "  ";
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  };
  emit(table.header);
  for (const auto& row : table.rows) emit(row);
  return out;
}

std::string number(double v, const char* format = "%.4g") {
  char text[64];
  std::snprintf(text, sizeof text, format, v);
  return text;
}

std::string point(const Vec3d& p) {
  char text[128];
  std::snprintf(text, sizeof text, "(%.3f, %.3f, %.3f)", p.x, p.y, p.z);
  return text;
}

// One split's transforms file, if it parses.
struct SplitInfo {
  std::string name;
  std::optional<TransformsFile> transforms;
  int width = 0, height = 0;  // of the first view's render image; 0 when unreadable
};

SplitInfo readSplit(const fs::path& root, const std::string& name) {
  SplitInfo info;
  info.name = name;
  try {
    info.transforms = readTransformsJson(root / ("transforms_" + name + ".json"));
    if (!info.transforms->frames.empty()) {
      fs::path base = root / bufferFilePath(info.transforms->frames.front().filePath, Buffer::Render);
      if (std::optional<fs::path> path = findBufferFileAt(base)) {
        Image render = readBufferFile(*path, Buffer::Render);
        info.width = render.width;
        info.height = render.height;
      }
    }
  } catch (const std::exception&) {
    // Reported by validateDataset in the problem list.
  }
  return info;
}

std::vector<std::string> cameraRow(const SplitInfo& split) {
  const TransformsFile& t = *split.transforms;
  std::string resolution = split.width > 0 ? std::to_string(split.width) + "x" + std::to_string(split.height) : "?";
  std::string fov = number(t.cameraAngleX * 180.0 / std::numbers::pi, "%.2f");
  if (t.frames.empty()) return {split.name, "0", resolution, fov, "-", "-", "-"};

  Vec3d lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity()), sum;
  for (const TransformsFrame& f : t.frames) {
    Vec3d p = f.transformMatrix.column(3);
    lo = min(lo, p), hi = max(hi, p), sum += p;
  }
  Vec3d centroid = sum / double(t.frames.size());
  double dMin = std::numeric_limits<double>::infinity(), dMax = 0, dSum = 0;
  for (const TransformsFrame& f : t.frames) {
    double d = length(f.transformMatrix.column(3) - centroid);
    dMin = std::min(dMin, d), dMax = std::max(dMax, d), dSum += d;
  }
  std::string distances = number(dMin, "%.3f") + " / " + number(dSum / t.frames.size(), "%.3f") + " / " +
                          number(dMax, "%.3f");
  return {split.name, std::to_string(t.frames.size()), resolution, fov, point(lo), point(hi), distances};
}

// Running statistics of one buffer over the sampled views.
struct BufferStats {
  std::array<double, 3> lo{}, hi{}, sum{};
  std::array<size_t, 3> count{};
  size_t pixels = 0, noSurface = 0;
  int viewsFailed = 0;

  BufferStats() {
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
  }
  // Depth and the G-buffers (normal, roughness, f0) count only pixels where depth has a
  // surface (surfaceDepth: that view's depth, or null when unreadable); radiance counts all.
  // A G-buffer whose view has no usable depth is left out.
  void add(const Image& image, Buffer buffer, const Image* surfaceDepth) {
    bool masked = buffer == Buffer::Depth || !isRadianceBuffer(buffer);
    if (masked && buffer != Buffer::Depth &&
        !(surfaceDepth && surfaceDepth->width == image.width && surfaceDepth->height == image.height))
      return;
    if (buffer == Buffer::Depth) surfaceDepth = &image;
    for (size_t i = 0; i < image.pixels.size(); ++i) {
      float v = image.pixels[i];
      int c = int(i % image.channels);
      if (masked) {
        bool surface = hasSurface(surfaceDepth->pixels[i / image.channels]);
        if (buffer == Buffer::Depth) pixels++, noSurface += surface ? 0 : 1;
        if (!surface) continue;
      }
      if (!std::isfinite(v)) continue;  // a validation problem; keep the statistics meaningful
      lo[c] = std::min(lo[c], double(v)), hi[c] = std::max(hi[c], double(v)), sum[c] += v, ++count[c];
    }
  }
  void merge(const BufferStats& o) {
    for (int c = 0; c < 3; ++c)
      lo[c] = std::min(lo[c], o.lo[c]), hi[c] = std::max(hi[c], o.hi[c]), sum[c] += o.sum[c], count[c] += o.count[c];
    pixels += o.pixels, noSurface += o.noSurface, viewsFailed += o.viewsFailed;
  }
};

std::vector<size_t> sampleViews(size_t count) {
  std::vector<size_t> indices;
  if (count <= size_t(kSummaryMaxViews)) {
    for (size_t i = 0; i < count; ++i) indices.push_back(i);
  } else {
    for (int i = 0; i < kSummaryMaxViews; ++i)
      indices.push_back(size_t(std::llround(double(i) * double(count - 1) / (kSummaryMaxViews - 1))));
  }
  return indices;
}

std::string bufferSection(const fs::path& root, const SplitInfo& split) {
  const auto& frames = split.transforms->frames;
  std::vector<size_t> sample = sampleViews(frames.size());
  std::vector<std::array<BufferStats, kBufferCount>> perView(sample.size());
  parallelFor(int64_t(sample.size()), 1, [&](int64_t s) {
    const std::string& filePath = frames[sample[s]].filePath;
    // Depth first: it masks the G-buffers' statistics.
    Image depth;
    for (Buffer b : {Buffer::Depth, Buffer::Render, Buffer::Diffuse, Buffer::Specular, Buffer::Normal,
                     Buffer::Roughness, Buffer::F0}) {
      BufferStats& stats = perView[s][int(b)];
      try {
        std::optional<fs::path> path = findBufferFileAt(root / bufferFilePath(filePath, b));
        if (!path) throw Error("missing");
        Image image = readBufferFile(*path, b);
        stats.add(image, b, depth.empty() ? nullptr : &depth);
        if (b == Buffer::Depth) depth = std::move(image);
      } catch (const std::exception&) {
        ++stats.viewsFailed;  // the problem list says why
      }
    }
  });
  std::array<BufferStats, kBufferCount> total;
  for (const auto& view : perView)
    for (int b = 0; b < kBufferCount; ++b) total[b].merge(view[b]);

  std::string out = split.name + " buffers, over " +
                    (sample.size() == frames.size()
                         ? "all " + std::to_string(frames.size()) + (frames.size() == 1 ? " view" : " views")
                         : std::to_string(sample.size()) + " of " + std::to_string(frames.size()) +
                               " views (evenly spaced)") +
                    "\n";
  Table table{{"buffer", "channel", "min", "max", "mean", "note"}, {false, false, true, true, true, false}, {}};
  for (Buffer b : kAllBuffers) {
    const BufferStats& stats = total[int(b)];
    int channels = bufferChannels(b);
    const char* labels = b == Buffer::Normal ? "xyz" : "RGB";
    for (int c = 0; c < channels; ++c) {
      std::vector<std::string> row{c == 0 ? bufferName(b) : "", channels == 1 ? "-" : std::string(1, labels[c])};
      if (stats.count[c] > 0)
        row.insert(row.end(), {number(stats.lo[c]), number(stats.hi[c]), number(stats.sum[c] / stats.count[c])});
      else
        row.insert(row.end(), {"-", "-", "-"});
      std::string note;
      if (c == 0 && b == Buffer::Depth && stats.pixels > 0)
        note = "surface pixels only; no surface in " + number(100.0 * stats.noSurface / stats.pixels, "%.1f") + "%";
      if (c == 0 && !isRadianceBuffer(b) && b != Buffer::Depth) note = "surface pixels only";
      if (c == 0 && stats.viewsFailed > 0)
        note += (note.empty() ? "" : "; ") + std::to_string(stats.viewsFailed) + " unreadable (see problems)";
      row.push_back(note);
      table.rows.push_back(row);
    }
  }
  return out + formatTable(table);
}

std::string pointCloudLine(const fs::path& root) {
  fs::path path = root / "point_cloud_dense.ply";
  if (!fs::exists(path)) return "point cloud: none (no point_cloud_dense.ply)\n";
  try {
    PointCloud cloud = readPointCloud(path);
    return "point cloud: point_cloud_dense.ply, " + std::to_string(cloud.positions.size()) + " points" +
           (cloud.colors.empty() ? " (no colours)" : "") + "\n";
  } catch (const std::exception&) {
    return "point cloud: point_cloud_dense.ply is unreadable (see problems)\n";
  }
}

}  // namespace

std::string formatProblem(const DatasetProblem& problem, const fs::path& root) {
  std::string file = problem.file;
  std::string prefix = root.string();
  if (!prefix.empty() && prefix.back() != '/') prefix += '/';
  if (file.rfind(prefix, 0) == 0) file.erase(0, prefix.size());
  return file + ": " + problem.message;
}

std::string describeDataset(const fs::path& root, bool* clean) {
  std::ostringstream out;
  out << "dataset " << root.string() << "\n\n";

  std::vector<SplitInfo> splits = {readSplit(root, "train"), readSplit(root, "test")};
  Table cameras{{"split", "views", "resolution", "fov x (deg)", "position min", "position max",
                 "distance to centroid (min / mean / max)"},
                {false, true, true, true, false, false, false},
                {}};
  for (const SplitInfo& split : splits)
    cameras.rows.push_back(split.transforms ? cameraRow(split)
                                            : std::vector<std::string>{split.name, "-", "-", "-", "-", "-",
                                                                       fs::exists(root / ("transforms_" + split.name +
                                                                                          ".json"))
                                                                           ? "transforms file unreadable (see problems)"
                                                                           : "no transforms file: no such split"});
  out << "cameras\n" << formatTable(cameras);

  for (const SplitInfo& split : splits)
    if (split.transforms && !split.transforms->frames.empty()) out << "\n" << bufferSection(root, split);

  out << "\n" << pointCloudLine(root) << "\n";

  std::vector<DatasetProblem> problems = validateDataset(root);
  if (clean) *clean = problems.empty();
  if (problems.empty()) {
    out << "problems: none\n";
  } else {
    out << "problems: " << problems.size() << "\n";
    size_t shown = std::min(problems.size(), size_t(kSummaryMaxProblems));
    for (size_t i = 0; i < shown; ++i) out << "  " << formatProblem(problems[i], root) << "\n";
    if (problems.size() > shown) out << "  ... and " << problems.size() - shown << " more\n";
  }
  return out.str();
}

}  // namespace glint
