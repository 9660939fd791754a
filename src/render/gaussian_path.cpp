// Path segments through the Gaussians with GGX importance sampling.
#include "render/gaussian_path.h"

#include <algorithm>

#include "bsdf/cook_torrance.h"
#include "math/frame.h"
#include "math/owen_sobol.h"

namespace glint {

PathResult tracePath(const GaussianTracer& tracer, const TraceRay& primary, const PathSettings& settings,
                     uint64_t seed, uint64_t view, uint64_t pixel, uint64_t sample,
                     std::vector<PathSegment>* segments) {
  // Traces one segment, recording it when asked. Recorded segments reuse the entries (and
  // hit-list memory) of earlier paths: training records a path per ray.
  size_t recorded = 0;
  auto traceSegment = [&](const TraceRay& ray, const Rgb& throughput) {
    if (!segments) return tracer.trace(ray);
    if (recorded == segments->size()) segments->emplace_back();
    PathSegment& s = (*segments)[recorded++];
    s.ray = ray;
    s.throughput = throughput;
    s.hits.capacity = settings.hitListCapacity;
    s.result = tracer.trace(ray, &s.hits);
    return s.result;
  };
  PathResult path;
  path.first = traceSegment(primary, Rgb(1.0f));
  path.specular = Rgb(0.0f);
  RayResult current = path.first;
  TraceRay ray = primary;
  Rgb throughput(1.0f);
  for (int k = 1; k <= settings.bounces; ++k) {
    if (!(current.normalLength >= settings.invalidNormalLength)) break;
    Vec3f n = current.normal / current.normalLength;
    // Blended normals may face away from the incoming ray (Gaussians seen from behind);
    // the surface is then taken as seen from the ray's side.
    if (dot(n, ray.direction) > 0) n = -n;
    Frame<float> frame = Frame<float>::fromNormal(n);
    Vec3f wo = frame.toLocal(-ray.direction);
    float rho = std::max(std::clamp(current.roughness, 0.0f, 1.0f), settings.minRoughness);
    CookTorranceLobe lobe(current.f0, rho * rho);
    // Dimension k of the pixel's stratified stream: a pixel's samples spread their
    // directions of segment k evenly over the lobe, which at 64 samples leaves far less
    // noise on glossy surfaces than independent numbers.
    BsdfSample s = lobe.sample(wo, stratifiedSample2(hashKeys({seed, view, pixel, uint64_t(k)}), uint32_t(sample)));
    if (!s.valid) break;
    throughput = throughput * s.weight;
    TraceRay next;
    next.origin = ray.origin + ray.direction * current.depth + n * settings.normalOffset;
    next.direction = normalize(frame.toWorld(s.wi));
    next.tMin = 0.0f;
    next.backfaceSkip = settings.backfaceSkip;
    current = traceSegment(next, throughput);
    Rgb light = throughput * current.diffuse;
    path.specular += light;
    if (k <= kSeparateBounces) path.bounceLight[size_t(k - 1)] = light;
    ++path.segments;
    ray = next;
  }
  return path;
}

}  // namespace glint
