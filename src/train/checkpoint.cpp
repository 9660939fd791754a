// Checkpoint file: "GLINTCKP", a version, fixed-size header fields, the config text, then
// every array as raw little-endian floats, and an FNV-1a 64 checksum of all preceding bytes.
#include "train/checkpoint.h"

#include <cstring>
#include <fstream>
#include <type_traits>

#include "core/atomic_file.h"
#include "core/error.h"

namespace glint {

namespace {

constexpr char kMagic[8] = {'G', 'L', 'I', 'N', 'T', 'C', 'K', 'P'};
constexpr uint32_t kVersion = 1;

class Writer {
 public:
  void bytes(const void* p, size_t n) {
    const char* c = static_cast<const char*>(p);
    data_.insert(data_.end(), c, c + n);
  }
  template <typename T>
  void value(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes(&v, sizeof(T));
  }
  template <typename T>
  void array(const std::vector<T>& v) {
    value(uint64_t(v.size()));
    bytes(v.data(), v.size() * sizeof(T));
  }
  const std::vector<char>& data() const { return data_; }

 private:
  std::vector<char> data_;
};

class Reader {
 public:
  Reader(const std::vector<char>& data, size_t end, std::string file) : data_(data), end_(end), file_(std::move(file)) {}
  void bytes(void* p, size_t n) {
    if (n > end_ - pos_) throw Error(file_, "is truncated");
    std::memcpy(p, data_.data() + pos_, n);
    pos_ += n;
  }
  template <typename T>
  T value() {
    T v;
    bytes(&v, sizeof(T));
    return v;
  }
  template <typename T>
  void array(std::vector<T>* v, size_t expected) {
    uint64_t n = value<uint64_t>();
    if (n != expected) throw Error(file_, "is corrupt: an array has " + std::to_string(n) + " entries, expected " +
                                              std::to_string(expected));
    v->resize(n);
    bytes(v->data(), n * sizeof(T));
  }
  bool atEnd() const { return pos_ == end_; }

 private:
  const std::vector<char>& data_;
  size_t pos_ = 0, end_;
  std::string file_;
};

uint64_t fnv1a(const char* p, size_t n) {
  uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; ++i) h = (h ^ uint8_t(p[i])) * 0x100000001b3ull;
  return h;
}

// Scene may be const or not (writing and reading share the order).
template <typename Scene, typename Visit>
void forEachSceneArray(Scene& s, Visit&& visit) {
  visit(s.position), visit(s.rotation), visit(s.logScale), visit(s.opacityLogit);
  visit(s.diffuse), visit(s.normal), visit(s.roughness), visit(s.f0);
}
template <typename Moments, typename Visit>
void forEachMomentArray(Moments& g, Visit&& visit) {
  visit(g.position), visit(g.rotation), visit(g.logScale), visit(g.opacityLogit);
  visit(g.diffuse), visit(g.normal), visit(g.roughness), visit(g.f0);
}

}  // namespace

void writeCheckpoint(const std::filesystem::path& file, const TrainingState& state) {
  Writer w;
  w.bytes(kMagic, sizeof(kMagic));
  w.value(kVersion);
  w.value(state.step);
  w.value(state.adam.stepCount());
  w.value(state.sceneExtent);
  w.value(uint64_t(state.scene.size()));
  w.value(uint64_t(state.configJson.size()));
  w.bytes(state.configJson.data(), state.configJson.size());
  forEachSceneArray(state.scene, [&](const auto& a) { w.array(a); });
  forEachMomentArray(state.adam.firstMoment(), [&](const auto& a) { w.array(a); });
  forEachMomentArray(state.adam.secondMoment(), [&](const auto& a) { w.array(a); });
  w.array(state.pruneWeight);
  uint64_t checksum = fnv1a(w.data().data(), w.data().size());
  w.value(checksum);
  std::filesystem::create_directories(file.parent_path());
  writeAtomically(file, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary);
    out.write(w.data().data(), std::streamsize(w.data().size()));
    if (!out) throw Error(temp, "could not be written (disk full?)");
  });
}

TrainingState readCheckpoint(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string(), "cannot be opened (no checkpoint to resume from)");
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string name = file.string();
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
  if (version != kVersion)
    throw Error(name, "has checkpoint version " + std::to_string(version) + "; this Glint reads version " +
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
  state.scene.resize(n);
  forEachSceneArray(state.scene, [&](auto& a) { r.array(&a, n); });
  state.adam.reset(n);
  forEachMomentArray(state.adam.firstMoment(), [&](auto& a) { r.array(&a, n); });
  forEachMomentArray(state.adam.secondMoment(), [&](auto& a) { r.array(&a, n); });
  state.adam.setStepCount(adamStep);
  r.array(&state.pruneWeight, n);
  if (!r.atEnd()) throw Error(name, "is corrupt: unexpected bytes after the last array");
  return state;
}

}  // namespace glint
