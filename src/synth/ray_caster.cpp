// Embree 3 scene setup (one triangle geometry per mesh, one sphere-point geometry for all
// spheres) and hit post-processing into SurfaceHit.
#include "synth/ray_caster.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "math/sampling.h"

namespace glint {

struct RayCaster::Impl {
  const MeshScene& scene;
  RTCDevice device = nullptr;
  RTCScene rtcScene = nullptr;
  // Geometry id -> mesh index, or -1 for the sphere geometry.
  std::vector<int> geometryToMesh;
  // Per-thread ray counters, each on its own cache line so counting costs no sharing.
  struct alignas(64) Counter {
    uint64_t rays = 0;
  };
  mutable std::vector<Counter> counters;

  explicit Impl(const MeshScene& s) : scene(s) {}
};

namespace {

void embreeErrorCallback(void*, RTCError code, const char* message) {
  // Embree errors at scene build time are programming or resource errors; surface them.
  throw Error(std::string("Embree error ") + std::to_string(int(code)) + ": " + (message ? message : ""));
}

}  // namespace

RayCaster::RayCaster(const MeshScene& scene) : impl_(std::make_unique<Impl>(scene)) {
  impl_->counters.resize(size_t(threadSlotCount()));
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw Error("cannot create an Embree device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
  rtcSetDeviceErrorFunction(impl_->device, embreeErrorCallback, nullptr);
  impl_->rtcScene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->rtcScene, RTC_BUILD_QUALITY_HIGH);

  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const TriangleMesh& mesh = scene.meshes[m];
    if (mesh.triangleCount() == 0) continue;
    RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), mesh.positions.size()));
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      vertices[3 * i + 0] = mesh.positions[i].x;
      vertices[3 * i + 1] = mesh.positions[i].y;
      vertices[3 * i + 2] = mesh.positions[i].z;
    }
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), mesh.triangleCount()));
    std::memcpy(indices, mesh.indices.data(), mesh.indices.size() * sizeof(unsigned));
    rtcCommitGeometry(geometry);
    unsigned id = rtcAttachGeometry(impl_->rtcScene, geometry);
    rtcReleaseGeometry(geometry);
    if (impl_->geometryToMesh.size() <= id) impl_->geometryToMesh.resize(id + 1, -2);
    impl_->geometryToMesh[id] = int(m);
  }

  if (!scene.spheres.empty()) {
    RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* points = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4,
                                                               4 * sizeof(float), scene.spheres.size()));
    for (size_t i = 0; i < scene.spheres.size(); ++i) {
      points[4 * i + 0] = scene.spheres[i].center.x;
      points[4 * i + 1] = scene.spheres[i].center.y;
      points[4 * i + 2] = scene.spheres[i].center.z;
      points[4 * i + 3] = scene.spheres[i].radius;
    }
    rtcCommitGeometry(geometry);
    unsigned id = rtcAttachGeometry(impl_->rtcScene, geometry);
    rtcReleaseGeometry(geometry);
    if (impl_->geometryToMesh.size() <= id) impl_->geometryToMesh.resize(id + 1, -2);
    impl_->geometryToMesh[id] = -1;
  }
  rtcCommitScene(impl_->rtcScene);
}

RayCaster::~RayCaster() {
  if (impl_->rtcScene) rtcReleaseScene(impl_->rtcScene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

bool RayCaster::intersect(const Vec3f& origin, const Vec3f& dir, float tMin, float tMax, SurfaceHit* hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = origin.x, rh.ray.org_y = origin.y, rh.ray.org_z = origin.z;
  rh.ray.dir_x = dir.x, rh.ray.dir_y = dir.y, rh.ray.dir_z = dir.z;
  rh.ray.tnear = tMin;
  rh.ray.tfar = tMax;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.flags = 0;
  rh.ray.time = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  impl_->counters[threadIndex()].rays++;
  rtcIntersect1(impl_->rtcScene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

  const MeshScene& scene = impl_->scene;
  int meshIndex = impl_->geometryToMesh[rh.hit.geomID];
  hit->t = rh.ray.tfar;
  Vec3f ownNormal;  // the surface's own orientation (outward for spheres, winding for triangles)
  if (meshIndex < 0) {
    const Sphere& sphere = scene.spheres[rh.hit.primID];
    // Recompute the hit point from the centre for precision: project onto the sphere.
    Vec3f p = origin + dir * hit->t;
    ownNormal = normalize(p - sphere.center);
    hit->position = sphere.center + ownNormal * sphere.radius;
    hit->shadingNormal = ownNormal;
    // Equirectangular texture coordinates around +Y.
    float phi = std::atan2(ownNormal.z, ownNormal.x);
    hit->uv = {0.5f + phi / (2 * kPi), std::acos(std::clamp(ownNormal.y, -1.0f, 1.0f)) / kPi};
    hit->material = sphere.material;
    hit->mesh = -1;
    hit->triangle = int(rh.hit.primID);
  } else {
    const TriangleMesh& mesh = scene.meshes[meshIndex];
    unsigned tri = rh.hit.primID;
    uint32_t i0 = mesh.indices[3 * tri], i1 = mesh.indices[3 * tri + 1], i2 = mesh.indices[3 * tri + 2];
    float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1.0f - b1 - b2;
    const Vec3f &p0 = mesh.positions[i0], &p1 = mesh.positions[i1], &p2 = mesh.positions[i2];
    hit->position = p0 * b0 + p1 * b1 + p2 * b2;
    ownNormal = normalize(cross(p1 - p0, p2 - p0));
    if (!mesh.normals.empty()) {
      Vec3f n = normalize(mesh.normals[i0] * b0 + mesh.normals[i1] * b1 + mesh.normals[i2] * b2);
      hit->shadingNormal = length(n) > 0 ? n : ownNormal;
    } else {
      hit->shadingNormal = ownNormal;
    }
    hit->uv = mesh.uvs.empty() ? Vec2f(b1, b2) : mesh.uvs[i0] * b0 + mesh.uvs[i1] * b1 + mesh.uvs[i2] * b2;
    hit->material = mesh.material;
    hit->mesh = meshIndex;
    hit->triangle = int(tri);
  }
  // Surfaces are two-sided: orient both normals towards the incoming ray. The shading
  // normal follows the geometric one so that interpolation never flips the hemisphere.
  hit->frontFacing = dot(ownNormal, dir) < 0;
  hit->geometricNormal = hit->frontFacing ? ownNormal : -ownNormal;
  if (dot(hit->shadingNormal, hit->geometricNormal) < 0) hit->shadingNormal = -hit->shadingNormal;
  return true;
}

bool RayCaster::occluded(const Vec3f& origin, const Vec3f& dir, float tMin, float tMax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  ray.org_x = origin.x, ray.org_y = origin.y, ray.org_z = origin.z;
  ray.dir_x = dir.x, ray.dir_y = dir.y, ray.dir_z = dir.z;
  ray.tnear = tMin;
  ray.tfar = tMax;
  ray.mask = 0xFFFFFFFFu;
  ray.flags = 0;
  ray.time = 0;
  impl_->counters[threadIndex()].rays++;
  rtcOccluded1(impl_->rtcScene, &context, &ray);
  return ray.tfar < 0;  // Embree sets tfar to -inf on a hit
}

uint64_t RayCaster::rayCount() const {
  uint64_t total = 0;
  for (const auto& c : impl_->counters) total += c.rays;
  return total;
}

void RayCaster::resetRayCount() {
  for (auto& c : impl_->counters) c.rays = 0;
}

}  // namespace glint
