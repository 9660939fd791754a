// Embree 3 implementation of the 3DGRT k-buffer tracer: the device and its error and memory
// callbacks, the Gaussian user geometry (bounds and intersect callbacks), and the per-ray
// traversal rounds.
#include "tracers/embree_tracer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <type_traits>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "raytrace/compositor.h"
#include "raytrace/gaussian_kernel.h"

namespace glint {

namespace {

constexpr int kBufferSize = EmbreeK16Tracer::kBufferSize;
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Slack between our kernel's float entry/exit distances and Embree's box tests, so a
// rounding difference never culls a box holding a hit that should be kept.
inline float slack(float t) { return 1e-5f * (1.0f + std::abs(t)); }

// Hits are ordered by (key, id): ties in key (e.g. several Gaussians containing the ray
// origin, all keyed at tMin) are broken by id, as in every other tracer.
inline bool before(float keyA, uint32_t idA, float keyB, uint32_t idB) {
  return keyA < keyB || (keyA == keyB && idA < idB);
}

const char* errorName(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE: return "no error";
    case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
    case RTC_ERROR_CANCELLED: return "cancelled";
    default: return "unknown error";
  }
}

// One entry of the sorted k-buffer; the hit itself lives in a fixed slot so that
// insertion only shifts these small entries.
struct BufferEntry {
  float key;
  uint32_t id;
  uint32_t slot;
};

}  // namespace

struct EmbreeK16Tracer::Impl {
  BvhMode mode;
  RTCDevice device = nullptr;
  RTCScene rtcScene = nullptr;
  RTCGeometry geometry = nullptr;  // our reference, kept for refit
  std::atomic<int64_t> embreeBytes{0};
  std::mutex errorMutex;
  std::string firstError;  // guarded by errorMutex

  const GaussianScene* scene = nullptr;
  TraceSettings settings;
  std::vector<GaussianFrame<float>> frames;  // per Gaussian
  std::vector<uint32_t> gaussianOfPrim;      // Embree primitive -> Gaussian (proxy radius > 0 only)

  // The state of one ray, handed to the intersect callback through the intersect
  // context (the Embree 3 way: the context is the first member, cast back in the callback).
  struct RayContext {
    RTCIntersectContext embree;
    const Impl* impl;
    Vec3f origin, direction;
    float tMin;
    // Only hits strictly after the last composited (key, id) are wanted.
    bool hasLast = false;
    float lastKey = 0;
    uint32_t lastId = 0;
    // The exact-tail pass multiplies every remaining hit into the compositor instead of
    // buffering it (order is irrelevant for a product).
    bool tailPass = false;
    Compositor<float>* compositor = nullptr;
    int count = 0;
    BufferEntry order[kBufferSize];
    KernelHit<float> slots[kBufferSize];
    int64_t evaluations = 0;
  };
  static_assert(std::is_standard_layout_v<RayContext>, "the Embree context must be the first member");

  explicit Impl(BvhMode m) : mode(m) {}

  // Embree reports errors through this callback; it records them (never throws through
  // Embree's C code) and the API functions below turn them into glint::Error.
  static void errorCallback(void* userPtr, RTCError code, const char* message) {
    auto* impl = static_cast<Impl*>(userPtr);
    std::lock_guard<std::mutex> lock(impl->errorMutex);
    if (impl->firstError.empty())
      impl->firstError = std::string(errorName(code)) + (message && *message ? std::string(" (") + message + ")" : "");
  }

  // Embree has no memory query; its allocations and frees are counted here.
  static bool memoryCallback(void* userPtr, ssize_t bytes, bool /*post*/) {
    static_cast<Impl*>(userPtr)->embreeBytes.fetch_add(int64_t(bytes), std::memory_order_relaxed);
    return true;
  }

  // The world AABB of the proxy ellipsoid: the half-extent along world axis k of the
  // ellipsoid x = R S u, |u| <= radius, is radius * |row k of R S| (the support function of
  // an ellipsoid, e.g. Ericson, "Real-Time Collision Detection", 4.7). Computed in double,
  // then padded outwards by a little more than float rounding.
  static void boundsCallback(const RTCBoundsFunctionArguments* args) {
    const auto* impl = static_cast<const Impl*>(args->geometryUserPtr);
    uint32_t id = impl->gaussianOfPrim[args->primID];
    const GaussianScene& scene = *impl->scene;
    const Quatf& q = scene.rotation[id];
    Mat3d r = quatToRotation(Quatd{q.w, q.x, q.y, q.z});
    const Vec3f& ls = scene.logScale[id];
    Vec3d s(std::exp(double(ls.x)), std::exp(double(ls.y)), std::exp(double(ls.z)));
    double radius = double(impl->frames[id].proxyRadius);
    Vec3d mean(scene.position[id]);
    float lower[3], upper[3];
    for (int k = 0; k < 3; ++k) {
      Vec3d row = r.m[k] * s;
      double half = radius * length(row);
      half += 1e-5 * half + 1e-6 * std::abs(mean[k]);
      lower[k] = float(mean[k] - half);
      upper[k] = float(mean[k] + half);
    }
    RTCBounds* b = args->bounds_o;
    b->lower_x = lower[0], b->lower_y = lower[1], b->lower_z = lower[2];
    b->upper_x = upper[0], b->upper_y = upper[1], b->upper_z = upper[2];
  }

  // Called for every proxy box the ray reaches. Evaluates the Gaussian and keeps the hit
  // in the sorted k-buffer (or, in the tail pass, multiplies it in), and always rejects so
  // that traversal continues. Once the buffer is full, the ray's tfar shrinks to its
  // farthest key so Embree culls boxes that cannot hold a nearer hit (3DGRT does the same
  // by accepting the hit at the buffer's end).
  static void intersectCallback(const RTCIntersectFunctionNArguments* args) {
    if (!args->valid[0]) return;
    auto* ray = reinterpret_cast<RayContext*>(args->context);
    const Impl& impl = *ray->impl;
    uint32_t id = impl.gaussianOfPrim[args->primID];
    ++ray->evaluations;
    KernelHit<float> hit;
    if (!evaluateGaussian(impl.frames[id], ray->origin, ray->direction, ray->tMin, impl.settings, &hit)) return;
    if (ray->hasLast && !before(ray->lastKey, ray->lastId, hit.key, id)) return;
    if (ray->tailPass) {
      ray->compositor->add(id, hit);
      return;
    }
    insert(*ray, id, hit);
    if (ray->count == kBufferSize) {
      // rtcIntersect1 passes a single RTCRayHit (N = 1).
      auto* rayHit = reinterpret_cast<RTCRayHit*>(args->rayhit);
      float key = ray->order[kBufferSize - 1].key;
      rayHit->ray.tfar = std::min(rayHit->ray.tfar, key + slack(key));
    }
  }

  static void insert(RayContext& ray, uint32_t id, const KernelHit<float>& hit) {
    int n = ray.count;
    if (n == kBufferSize && !before(hit.key, id, ray.order[n - 1].key, ray.order[n - 1].id)) return;
    int pos = n;
    while (pos > 0 && before(hit.key, id, ray.order[pos - 1].key, ray.order[pos - 1].id)) --pos;
    // The same primitive referenced twice (never for user geometry today) is kept once.
    if (pos > 0 && ray.order[pos - 1].key == hit.key && ray.order[pos - 1].id == id) return;
    uint32_t slot;
    if (n == kBufferSize) {
      slot = ray.order[n - 1].slot;  // the farthest hit makes room
      --n;
    } else {
      slot = uint32_t(n);
    }
    for (int i = n; i > pos; --i) ray.order[i] = ray.order[i - 1];
    ray.order[pos] = {hit.key, id, slot};
    ray.slots[slot] = hit;
    ray.count = n + 1;
  }

  // One traversal of the whole BVH for the segment [tNear, inf).
  void traverse(RayContext& ray, float tNear) const {
    RTCRayHit rayHit;
    rayHit.ray.org_x = ray.origin.x, rayHit.ray.org_y = ray.origin.y, rayHit.ray.org_z = ray.origin.z;
    rayHit.ray.dir_x = ray.direction.x, rayHit.ray.dir_y = ray.direction.y, rayHit.ray.dir_z = ray.direction.z;
    rayHit.ray.tnear = std::max(0.0f, tNear);
    rayHit.ray.tfar = kInfinity;
    rayHit.ray.mask = 0xFFFFFFFFu;
    rayHit.ray.flags = 0;
    rayHit.ray.time = 0;
    rayHit.ray.id = 0;
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    ray.count = 0;
    rtcIntersect1(rtcScene, &ray.embree, &rayHit);
  }

  void computeFrames() {
    frames.resize(scene->size());
    parallelFor(int64_t(frames.size()), 4096,
                [&](int64_t i) { frames[i] = makeGaussianFrame<float>(*scene, size_t(i), settings); });
  }

  std::vector<uint32_t> activeGaussians() const {
    std::vector<uint32_t> active;
    active.reserve(frames.size());
    for (size_t i = 0; i < frames.size(); ++i)
      if (frames[i].proxyRadius > 0) active.push_back(uint32_t(i));
    return active;
  }

  void releaseScene() {
    if (geometry) rtcReleaseGeometry(geometry);
    if (rtcScene) rtcReleaseScene(rtcScene);
    geometry = nullptr;
    rtcScene = nullptr;
  }

  // Turns an error Embree reported since the last call into glint::Error, leaving no
  // half-built scene behind.
  void throwIfFailed(const std::string& what) {
    std::string message;
    {
      std::lock_guard<std::mutex> lock(errorMutex);
      message.swap(firstError);
    }
    if (message.empty()) return;
    releaseScene();
    gaussianOfPrim.clear();
    throw Error("Embree could not " + what + ": " + message);
  }

  void createScene() {
    releaseScene();
    bool refitMode = mode == BvhMode::kRefit;
    rtcScene = rtcNewScene(device);
    // Robust traversal: conservative box tests, so grazing rays never skip a proxy (it
    // measured no slower). Embree refits only in a dynamic scene of quality LOW.
    rtcSetSceneFlags(rtcScene, refitMode ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC : RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(rtcScene, refitMode ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM);
    if (!gaussianOfPrim.empty()) {
      geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(geometry, unsigned(gaussianOfPrim.size()));
      rtcSetGeometryUserData(geometry, this);
      rtcSetGeometryBoundsFunction(geometry, boundsCallback, this);
      rtcSetGeometryIntersectFunction(geometry, intersectCallback);
      rtcSetGeometryBuildQuality(geometry, refitMode ? RTC_BUILD_QUALITY_REFIT : RTC_BUILD_QUALITY_MEDIUM);
      rtcCommitGeometry(geometry);
      rtcAttachGeometry(rtcScene, geometry);
    }
    rtcCommitScene(rtcScene);
    throwIfFailed("build the BVH of " + std::to_string(gaussianOfPrim.size()) + " Gaussians");
  }
};

EmbreeK16Tracer::EmbreeK16Tracer(BvhMode mode) : impl_(std::make_unique<Impl>(mode)) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device)
    throw Error(std::string("Embree could not create a device: ") + errorName(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(impl_->device, Impl::errorCallback, impl_.get());
  rtcSetDeviceMemoryMonitorFunction(impl_->device, Impl::memoryCallback, impl_.get());
}

EmbreeK16Tracer::~EmbreeK16Tracer() {
  impl_->releaseScene();
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

void EmbreeK16Tracer::build(const GaussianScene& scene, const TraceSettings& settings) {
  GLINT_CHECK(scene.consistent(), "the Gaussian scene's arrays differ in length");
  Impl& m = *impl_;
  m.scene = &scene;
  m.settings = settings;
  m.computeFrames();
  m.gaussianOfPrim = m.activeGaussians();
  m.createScene();
}

void EmbreeK16Tracer::refit() {
  Impl& m = *impl_;
  GLINT_CHECK(m.scene != nullptr, "refit before build");
  GLINT_CHECK(m.scene->size() == m.frames.size(), "refit after the Gaussian count changed; call build");
  m.computeFrames();
  std::vector<uint32_t> active = m.activeGaussians();
  if (active != m.gaussianOfPrim || !m.geometry) {
    m.gaussianOfPrim = std::move(active);
    m.createScene();
    return;
  }
  // Committing the geometry makes Embree query every bound again: a refit in kRefit mode,
  // a rebuild otherwise.
  rtcCommitGeometry(m.geometry);
  rtcCommitScene(m.rtcScene);
  m.throwIfFailed("update the BVH of " + std::to_string(m.gaussianOfPrim.size()) + " Gaussians");
}

RayResult EmbreeK16Tracer::trace(const TraceRay& ray, HitList* hits) const { return trace(ray, hits, nullptr); }

RayResult EmbreeK16Tracer::trace(const TraceRay& ray, HitList* hits, EmbreeTraceStats* stats) const {
  const Impl& m = *impl_;
  GLINT_CHECK(m.scene != nullptr, "trace before build");
  if (stats) *stats = EmbreeTraceStats{};
  Compositor<float> compositor(*m.scene, m.settings, hits);
  if (ray.backfaceSkip > 0) compositor.skipBackfacing(ray.direction, ray.backfaceSkip);
  if (!m.rtcScene || m.gaussianOfPrim.empty()) return compositor.finish();

  Impl::RayContext context;
  rtcInitIntersectContext(&context.embree);
  context.impl = &m;
  context.origin = ray.origin;
  context.direction = normalize(ray.direction);
  context.tMin = ray.tMin;
  context.compositor = &compositor;

  // Rounds: gather the 16 nearest hits after the last composited one, composite them in
  // order, and go again while the ray lives and the buffer was full (more hits may follow).
  float tNear = ray.tMin - slack(ray.tMin);
  int rounds = 0;
  for (;;) {
    m.traverse(context, tNear);
    ++rounds;
    for (int i = 0; i < context.count; ++i) {
      const BufferEntry& e = context.order[i];
      compositor.add(e.id, context.slots[e.slot]);
      context.hasLast = true;
      context.lastKey = e.key;
      context.lastId = e.id;
      if (compositor.terminated()) break;
    }
    if (compositor.terminated() || context.count < kBufferSize) break;
    tNear = context.lastKey - slack(context.lastKey);
  }

  // Exact tail: one more traversal multiplies in the alpha of every hit after the
  // terminating one.
  if (m.settings.exactTail && compositor.terminated()) {
    context.tailPass = true;
    m.traverse(context, context.lastKey - slack(context.lastKey));
  }
  if (stats) {
    stats->rounds = rounds;
    stats->evaluations = context.evaluations;
  }
  return compositor.finish();
}

size_t EmbreeK16Tracer::memoryBytes() const {
  const Impl& m = *impl_;
  return size_t(std::max<int64_t>(0, m.embreeBytes.load())) + m.frames.capacity() * sizeof(GaussianFrame<float>) +
         m.gaussianOfPrim.capacity() * sizeof(uint32_t);
}

}  // namespace glint
