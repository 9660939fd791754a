// Path tracing with the diffuse/specular split at the first vertex (paper equation 2).
#include "synth/path_tracer.h"

#include <cmath>
#include <limits>

#include "bsdf/cook_torrance.h"
#include "bsdf/lambert.h"
#include "bsdf/principled.h"
#include "math/frame.h"

namespace glint {

namespace {
constexpr float kInfinity = std::numeric_limits<float>::infinity();
}

// A shading point: local frame, outgoing direction and BRDF.
struct PathTracer::Vertex {
  SurfaceHit hit;
  Framef frame;
  Vec3f wo;  // local, towards where the ray came from
  SurfaceMaterial material;
  PrincipledBrdf brdf;
};

PathTracer::PathTracer(const MeshScene& scene, const RayCaster& caster, const LightSampler& lights,
                       PathTracerSettings settings)
    : scene_(scene), caster_(caster), lights_(lights), settings_(settings) {}

PathTracer::Vertex PathTracer::makeVertex(const SurfaceHit& hit, const Vec3f& dir) const {
  Vertex v;
  v.hit = hit;
  v.frame = Framef::fromNormal(hit.shadingNormal);
  v.wo = v.frame.toLocal(-dir);
  // Interpolated normals can leave wo just under the shading horizon at silhouettes;
  // nudge it up so the BRDF stays defined (the geometric side is already correct).
  if (v.wo.z <= 1e-4f) v.wo = normalize(Vec3f(v.wo.x, v.wo.y, 1e-4f));
  v.material = scene_.surfaceMaterial(hit.material, hit.uv);
  v.brdf = PrincipledBrdf{v.material.diffuse, v.material.F0, PrincipledBrdf::alphaFromRoughness(v.material.roughness)};
  return v;
}

FirstHit PathTracer::firstHit(const Vec3f& origin, const Vec3f& dir) const {
  FirstHit result;
  SurfaceHit hit;
  if (!caster_.intersect(origin, dir, 0.0f, kInfinity, &hit)) return result;
  SurfaceMaterial m = scene_.surfaceMaterial(hit.material, hit.uv);
  result.hit = true;
  result.depth = hit.t;
  result.normal = hit.shadingNormal;
  result.roughness = m.roughness;
  result.F0 = m.F0;
  return result;
}

// Next-event estimation at a vertex for one BRDF (a lobe or the whole BRDF): a light
// sample weighted against the chance that BSDF sampling would have found the same light.
template <typename Brdf>
static Rgb estimateDirect(const Brdf& brdf, const Framef& frame, const Vec3f& wo, const SurfaceHit& hit,
                          const LightSampler& lights, const RayCaster& caster, Rng& rng) {
  if (lights.empty()) return Rgb(0.0f);
  float uLight = rng.uniform();
  Vec2f uPoint = rng.uniform2();
  LightSample ls = lights.sample(hit.position, uLight, uPoint);
  if (ls.pdf <= 0 || maxComponent(ls.radiance) <= 0) return Rgb(0.0f);
  if (dot(ls.wi, hit.geometricNormal) <= 0) return Rgb(0.0f);  // light behind the surface
  Vec3f wi = frame.toLocal(ls.wi);
  Rgb f = brdf.eval(wo, wi);  // includes cos(theta_i)
  if (maxComponent(f) <= 0) return Rgb(0.0f);
  Vec3f origin = offsetRayOrigin(hit.position, hit.geometricNormal, ls.wi);
  if (std::isinf(ls.distance)) {
    if (caster.occluded(origin, ls.wi, 0.0f, kInfinity)) return Rgb(0.0f);
  } else {
    // Aim the shadow ray from the offset origin at the light point itself, and stop just
    // short of it, so that the emitter's own surface never counts as an occluder.
    Vec3f toLight = hit.position + ls.wi * ls.distance - origin;
    float distance = length(toLight);
    if (caster.occluded(origin, toLight / distance, 0.0f, distance * (1.0f - 1e-4f))) return Rgb(0.0f);
  }
  float weight = ls.isDelta ? 1.0f : powerHeuristic(ls.pdf, brdf.pdf(wo, wi));
  return f * ls.radiance * (weight / ls.pdf);
}

// Emission found by a BSDF-sampled ray, weighted against light sampling.
static float emitterMisWeight(const LightSampler& lights, const Vec3f& from, const SurfaceHit& hit, float bsdfPdf) {
  float lightPdf = lights.emitterPdf(from, hit.position, hit.geometricNormal, hit.mesh, hit.triangle);
  return lightPdf > 0 ? powerHeuristic(bsdfPdf, lightPdf) : 1.0f;
}

RadianceSample PathTracer::trace(const Vec3f& origin, const Vec3f& dir, Rng& rng) const {
  RadianceSample result;
  SurfaceHit hit;
  if (!caster_.intersect(origin, dir, 0.0f, kInfinity, &hit)) {
    // Escaped rays see the environment; it counts as diffuse (docs/data-format.md).
    result.diffuse = lights_.environmentRadiance(dir);
    return result;
  }
  Vertex v = makeVertex(hit, dir);
  // Emission seen directly is view-independent light, so it joins the diffuse buffer,
  // keeping render = diffuse + specular exact.
  result.diffuse = v.material.emission;
  if (settings_.maxBounces < 1) return result;

  // Equation 2: the same light transport, split by the lobe that leaves the first vertex.
  // Each lobe gets its own light sample and its own continuation path.
  auto throughLobe = [&](const auto& lobe) {
    Rgb radiance = estimateDirect(lobe, v.frame, v.wo, v.hit, lights_, caster_, rng);
    BsdfSample s = lobe.sample(v.wo, rng.uniform2());
    if (!s.valid || maxComponent(s.weight) <= 0) return radiance;
    Vec3f wi = v.frame.toWorld(s.wi);
    if (dot(wi, v.hit.geometricNormal) <= 0) return radiance;
    return radiance + s.weight * continuePath(offsetRayOrigin(v.hit.position, v.hit.geometricNormal, wi), wi, s.pdf, 1, rng);
  };
  // A lobe with zero albedo / zero F0 is absent. (Schlick's Fresnel with F0 = 0 would still
  // reflect at grazing angles; a material with no specular level is treated as purely
  // diffuse, which is what a white-furnace sphere of albedo 1 needs to stay at 1.)
  if (maxComponent(v.brdf.diffuseLobe().albedo) > 0) result.diffuse += throughLobe(v.brdf.diffuseLobe());
  if (maxComponent(v.brdf.specularLobe().F0) > 0) result.specular = throughLobe(v.brdf.specularLobe());
  return result;
}

Rgb PathTracer::continuePath(Vec3f origin, Vec3f dir, float bsdfPdf, int depth, Rng& rng) const {
  Rgb radiance(0.0f);
  Rgb beta(1.0f);
  for (;;) {
    SurfaceHit hit;
    if (!caster_.intersect(origin, dir, 0.0f, kInfinity, &hit)) {
      float lightPdf = lights_.environmentPdf(dir);
      float weight = lightPdf > 0 ? powerHeuristic(bsdfPdf, lightPdf) : 1.0f;
      radiance += beta * lights_.environmentRadiance(dir) * weight;
      break;
    }
    Vertex v = makeVertex(hit, dir);
    if (maxComponent(v.material.emission) > 0)
      radiance += beta * v.material.emission * emitterMisWeight(lights_, origin, hit, bsdfPdf);
    if (++depth >= settings_.maxBounces) break;

    radiance += beta * estimateDirect(v.brdf, v.frame, v.wo, v.hit, lights_, caster_, rng);

    BsdfSample s = v.brdf.sample(v.wo, rng.uniform2());
    if (!s.valid || maxComponent(s.weight) <= 0) break;
    Vec3f wi = v.frame.toWorld(s.wi);
    if (dot(wi, hit.geometricNormal) <= 0) break;
    beta *= s.weight;
    bsdfPdf = s.pdf;
    origin = offsetRayOrigin(hit.position, hit.geometricNormal, wi);
    dir = wi;

    // Russian roulette (pbrt-v4 PathIntegrator): survive with probability ~ throughput.
    if (depth >= settings_.rouletteStart) {
      float survive = std::min(1.0f, maxComponent(beta));
      if (survive <= 0 || rng.uniform() >= survive) break;
      beta /= survive;
    }
  }
  return radiance;
}

}  // namespace glint
