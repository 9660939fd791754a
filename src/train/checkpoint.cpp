// Checkpoint file: "GLINTCKP", a version, fixed-size header fields, the config text, then
// every array as raw little-endian floats, and an FNV-1a 64 checksum of all preceding bytes.
#include "train/checkpoint.h"

#include <cstring>
#include <span>
#include <fstream>
#include <type_traits>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/input_file.h"
#include "scene/gaussian_parameters.h"

namespace glint {

namespace {

constexpr char kMagic[8] = {'G', 'L', 'I', 'N', 'T', 'C', 'K', 'P'};
// Version 2 added the densification score after the prune weight, version 3 the roughness
// shift after it, version 4 the refined camera poses after that; older files are read with a
// zero score (they come from runs that did not densify), a zero shift (the shift-invariant
// roughness loss did not exist) and no poses (nor did camera refinement).
constexpr uint32_t kVersion = 4;

class Writer {
 public:
  explicit Writer(size_t capacity) { data_.reserve(capacity); }
  void bytes(const void* p, size_t n) {
    const char* c = static_cast<const char*>(p);
    data_.insert(data_.end(), c, c + n);
  }
  template <typename T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof(T));
  }
  // An array of `count` entries of `entrySize` bytes each, preceded by its count.
  void array(const void* entries, size_t count, size_t entrySize) {
    value(uint64_t(count));
    bytes(entries, count * entrySize);
  }
  const std::vector<char>& data() const { return data_; }
  std::vector<char> take() { return std::move(data_); }

 private:
  std::vector<char> data_;
};

class Reader {
 public:
  Reader(std::span<const char> data, size_t end, std::string file) : data_(data), end_(end), file_(std::move(file)) {}
  void bytes(void* p, size_t n) {
    if (n > end_ - pos_) throw Error(file_, "is truncated");
    if (n > 0) std::memcpy(p, data_.data() + pos_, n);  // p may be null for an empty array
    pos_ += n;
  }
  template <typename T>
  T value() {
    T v;
    bytes(&v, sizeof(T));
    return v;
  }
  // An array written by Writer::array, into `entries` (room for `expected` of them).
  void array(void* entries, size_t expected, size_t entrySize) {
    uint64_t n = value<uint64_t>();
    if (n != expected) throw Error(file_, "is corrupt: an array has " + std::to_string(n) + " entries, expected " +
                                              std::to_string(expected));
    bytes(entries, n * entrySize);
  }
  bool atEnd() const { return pos_ == end_; }

 private:
  std::span<const char> data_;
  size_t pos_ = 0, end_;
  std::string file_;
};

uint64_t fnv1a(const char* p, size_t n) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; ++i) h = (h ^ uint8_t(p[i])) * 0x100000001b3ull;
  return h;
}

// The arrays of a checkpoint, in the parameter table's order: the scene's values, then the
// first and the second moments. An entry is one Gaussian's value of the parameter; a
// moment's floats are in the order of the value's components, so both are the bytes the
// structure-of-arrays layout of version 1 wrote. Scene and Moments may be const or not.
template <typename Scene, typename Moments, typename Visit>
void forEachStateArray(Scene& scene, Moments& first, Moments& second, Visit&& visit) {
  forEachParameter([&](const auto& p) { visit((scene.*p.values).data(), sizeof((scene.*p.values)[0])); });
  for (Moments* moments : {&first, &second})
    forEachParameter([&](const auto& p) { visit(moments->values[p.index].data(), p.components * sizeof(float)); });
}

}  // namespace

std::vector<char> encodeCheckpoint(const TrainingState& state) {
  // The whole file is reserved at once: the header, the config, each array's count and
  // floats (the values and both moments of every parameter, the prune weight and the
  // densification score), the roughness shift, the checksum.
  const size_t n = state.scene.size();
  size_t floatsPerGaussian = 2;
  forEachParameter([&](const auto& p) { floatsPerGaussian += 3 * p.components; });
  Writer w(128 + state.configJson.size() + state.cameraPoses.size() * sizeof(Mat4) + (3 * kGaussianParameterCount + 2) * sizeof(uint64_t) +
           n * floatsPerGaussian * sizeof(float));
  w.bytes(kMagic, sizeof(kMagic));
  w.value(kVersion);
  w.value(state.step);
  w.value(state.adam.stepCount());
  w.value(state.sceneExtent);
  w.value(uint64_t(state.scene.size()));
  w.value(uint64_t(state.configJson.size()));
  w.bytes(state.configJson.data(), state.configJson.size());
  GLINT_CHECK(state.scene.consistent() && state.adam.firstMoment().size() == n &&
                  state.adam.secondMoment().size() == n && state.pruneWeight.size() == n && state.densifyScore.size() == n,
              "writeCheckpoint: every array must have one entry per Gaussian");
  forEachStateArray(state.scene, state.adam.firstMoment(), state.adam.secondMoment(),
                    [&](const void* entries, size_t entrySize) { w.array(entries, n, entrySize); });
  w.array(state.pruneWeight.data(), state.pruneWeight.size(), sizeof(float));
  w.array(state.densifyScore.data(), state.densifyScore.size(), sizeof(float));
  w.value(state.roughnessShift);
  w.value(uint64_t(state.cameraPoses.size()));
  for (const Mat4& pose : state.cameraPoses)
    for (const auto& row : pose.m) w.bytes(row.data(), row.size() * sizeof(double));
  uint64_t checksum = fnv1a(w.data().data(), w.data().size());
  w.value(checksum);
  return w.take();
}

void writeCheckpoint(const std::filesystem::path& file, const TrainingState& state) {
  const std::vector<char> bytes = encodeCheckpoint(state);
  std::filesystem::create_directories(file.parent_path());
  writeAtomically(file, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    if (!out) throw Error(temp, "could not be written (disk full?)");
  });
}

TrainingState readCheckpoint(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw Error(file.string(), "not found (no checkpoint to resume from)");
  const std::string bytes = readInputFile(file, kMaxBinaryInputFileBytes);
  return decodeCheckpoint(bytes, file.string());
}

TrainingState decodeCheckpoint(std::span<const char> data, const std::string& name) {
  if (data.size() < sizeof(kMagic) + sizeof(uint64_t) || std::memcmp(data.data(), kMagic, sizeof(kMagic)) != 0)
    throw Error(name, "is not a Glint checkpoint");
  size_t body = data.size() - sizeof(uint64_t);
  uint64_t stored;
  std::memcpy(&stored, data.data() + body, sizeof(stored));
  if (stored != fnv1a(data.data(), body)) throw Error(name, "is corrupt or truncated (checksum mismatch)");

  Reader r(data, body, name);
  char magic[sizeof(kMagic)];
  r.bytes(magic, sizeof(magic));
  uint32_t version = r.value<uint32_t>();
  if (version < 1 || version > kVersion)
    throw Error(name, "has checkpoint version " + std::to_string(version) + "; this Glint reads versions 1 to " +
                          std::to_string(kVersion));
  TrainingState state;
  state.step = r.value<int64_t>();
  int64_t adamStep = r.value<int64_t>();
  state.sceneExtent = r.value<float>();
  uint64_t n = r.value<uint64_t>();
  uint64_t configLength = r.value<uint64_t>();
  if (configLength > body) throw Error(name, "is corrupt: bad config length");
  state.configJson.resize(configLength);
  r.bytes(state.configJson.data(), configLength);
  if (n > body) throw Error(name, "is corrupt: bad Gaussian count");  // before sizing arrays by it
  state.scene.resize(n);
  state.adam.reset(n);
  forEachStateArray(state.scene, state.adam.firstMoment(), state.adam.secondMoment(),
                    [&](void* entries, size_t entrySize) { r.array(entries, n, entrySize); });
  state.adam.setStepCount(adamStep);
  state.pruneWeight.resize(n);
  r.array(state.pruneWeight.data(), n, sizeof(float));
  state.densifyScore.assign(n, 0.0f);
  if (version >= 2) r.array(state.densifyScore.data(), n, sizeof(float));
  if (version >= 3) state.roughnessShift = r.value<float>();
  if (version >= 4) {
    const uint64_t poses = r.value<uint64_t>();
    if (poses > body / sizeof(Mat4)) throw Error(name, "is corrupt: bad camera pose count");
    state.cameraPoses.resize(poses);
    for (Mat4& pose : state.cameraPoses)
      for (auto& row : pose.m) r.bytes(row.data(), row.size() * sizeof(double));
  }
  if (!r.atEnd()) throw Error(name, "is corrupt: unexpected bytes after the last array");
  return state;
}

}  // namespace glint
