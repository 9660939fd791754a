// Light selection proportional to estimated power, area sampling of emissive triangles,
// punctual lights, and importance sampling of equirectangular environments.
#include "synth/light_sampler.h"

#include <cmath>
#include <limits>

namespace glint {

namespace {
constexpr float kInfinity = std::numeric_limits<float>::infinity();

// KHR_lights_punctual's recommended spot attenuation: a linear ramp in cos(angle) between
// the outer and inner cone, clamped to [0, 1], then squared.
float spotAttenuation(float cosAngle, float cosOuter, float cosInner) {
  float scale = 1.0f / std::max(0.001f, cosInner - cosOuter);
  float t = std::clamp((cosAngle - cosOuter) * scale, 0.0f, 1.0f);
  return t * t;
}
}  // namespace

Vec2f directionToEquirect(const Vec3f& dir, float rotationY) {
  float phi = std::atan2(dir.z, dir.x) - rotationY;
  float u = phi / (2 * kPi);
  u -= std::floor(u);  // may round up to 1 for azimuths a hair below the seam: clamped below
  // atan2 rather than acos(dir.y): acos loses most of its digits near the poles, where the
  // solid-angle density divides by sin(theta).
  float v = std::atan2(std::sqrt(dir.x * dir.x + dir.z * dir.z), dir.y) / kPi;
  return {std::min(u, 0x1.fffffep-1f), std::min(v, 0x1.fffffep-1f)};
}

Vec3f equirectToDirection(Vec2f uv, float rotationY) {
  float phi = uv.x * 2 * kPi + rotationY;
  float theta = uv.y * kPi;
  float s = std::sin(theta);
  return {s * std::cos(phi), std::cos(theta), s * std::sin(phi)};
}

LightSampler::LightSampler(const MeshScene& scene) : scene_(scene) {
  Vec3f lower, upper;
  scene.bounds(&lower, &upper);
  sceneRadius_ = std::max(1e-3f, 0.5f * length(upper - lower));

  // Emissive triangles, weighted by emitted power (luminance x area; textures averaged out).
  std::vector<float> weights;
  emitterLookup_.assign(scene.meshes.size(), -1);
  for (size_t m = 0; m < scene.meshes.size(); ++m) {
    const TriangleMesh& mesh = scene.meshes[m];
    const Material& material = scene.materials[mesh.material];
    if (maxComponent(material.emission) <= 0) continue;
    emitterLookup_[m] = int(emitters_.size());
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      const Vec3f& p0 = mesh.positions[mesh.indices[3 * t]];
      const Vec3f& p1 = mesh.positions[mesh.indices[3 * t + 1]];
      const Vec3f& p2 = mesh.positions[mesh.indices[3 * t + 2]];
      float area = 0.5f * length(cross(p1 - p0, p2 - p0));
      emitters_.push_back({int(m), int(t), area});
      weights.push_back(area * luminance(material.emission));
    }
  }
  std::vector<float> choiceWeights;
  if (!emitters_.empty()) {
    emitterDistribution_ = Distribution1D(weights);
    choices_.push_back({Kind::Emitters, 0});
    // Two-sided Lambertian emitters radiate 2 pi L A.
    choiceWeights.push_back(2 * kPi * emitterDistribution_.total());
  }
  // Punctual lights: a point light radiates 4 pi I; a directional light's power over the
  // scene is E x its cross-section.
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const PunctualLight& light = scene.lights[i];
    float power = luminance(light.intensity);
    if (light.type == PunctualLight::Type::Directional) power *= kPi * sceneRadius_ * sceneRadius_;
    else power *= 4 * kPi;
    if (power <= 0) continue;
    choices_.push_back({Kind::Punctual, int(i)});
    choiceWeights.push_back(power);
  }
  const Environment& env = scene.environment;
  if (!env.isBlack()) {
    float average;
    if (!env.map.empty()) {
      // Density proportional to luminance x sin(theta) (the pixel's solid angle).
      const Image& map = env.map;
      std::vector<float> pixelWeights(size_t(map.width) * map.height);
      double sum = 0;
      for (int y = 0; y < map.height; ++y) {
        float sinTheta = std::sin(kPi * (y + 0.5f) / map.height);
        for (int x = 0; x < map.width; ++x) {
          float l = std::max(0.0f, luminance(map.rgb(x, y)));
          pixelWeights[size_t(y) * map.width + x] = l * sinTheta + 1e-6f;
          sum += l * sinTheta;
        }
      }
      environmentDistribution_ = Distribution2D(pixelWeights, map.width, map.height);
      average = float(sum / (double(map.width) * map.height) * (kPi / 2));
    } else {
      average = luminance(env.constant);
    }
    choices_.push_back({Kind::Environment, 0});
    // An environment of radiance L illuminates the scene's bounding sphere with power ~ pi L x 4 pi r^2.
    choiceWeights.push_back(average * env.intensity * 4 * kPi * kPi * sceneRadius_ * sceneRadius_);
  }
  if (!choiceWeights.empty()) {
    choice_ = Distribution1D(choiceWeights);
    for (size_t c = 0; c < choices_.size(); ++c) {
      if (choices_[c].kind == Kind::Emitters) emitterChoiceProbability_ = choice_.probability(c);
      if (choices_[c].kind == Kind::Environment) environmentChoiceProbability_ = choice_.probability(c);
    }
  }
}

Rgb LightSampler::environmentRadiance(const Vec3f& dir) const {
  const Environment& env = scene_.environment;
  if (env.map.empty()) return env.constant * env.intensity;
  Vec2f uv = directionToEquirect(dir, env.rotationY);
  int x = std::min(int(uv.x * env.map.width), env.map.width - 1);
  int y = std::min(int(uv.y * env.map.height), env.map.height - 1);
  return env.map.rgb(x, y) * env.intensity;
}

float LightSampler::environmentPdf(const Vec3f& dir) const {
  if (environmentChoiceProbability_ <= 0) return 0;
  const Environment& env = scene_.environment;
  if (env.map.empty()) return environmentChoiceProbability_ * uniformSpherePdf();
  Vec2f uv = directionToEquirect(dir, env.rotationY);
  float sinTheta = std::sin(uv.y * kPi);
  if (sinTheta <= 0) return 0;
  // Map density on the unit square to solid angle: dw = 2 pi^2 sin(theta) du dv.
  return environmentChoiceProbability_ * environmentDistribution_.pdf(uv) / (2 * kPi * kPi * sinTheta);
}

float LightSampler::emitterPdf(const Vec3f& p, const Vec3f& hitPoint, const Vec3f& hitNormal, int mesh,
                               int triangle) const {
  if (mesh < 0 || emitterLookup_[mesh] < 0) return 0;
  const Emitter& e = emitters_[emitterLookup_[mesh] + triangle];
  Vec3f d = hitPoint - p;
  float dist2 = dot(d, d);
  float cosLight = std::abs(dot(hitNormal, normalize(d)));
  if (cosLight <= 0 || e.area <= 0) return 0;
  float areaPdf = emitterChoiceProbability_ * emitterDistribution_.probability(emitterLookup_[mesh] + triangle) / e.area;
  return areaPdf * dist2 / cosLight;
}

LightSample LightSampler::sample(const Vec3f& p, float u1, Vec2f u2) const {
  LightSample s;
  if (choices_.empty()) return s;
  float choiceProbability;
  size_t c = choice_.sample(u1, &choiceProbability, &u1);
  const Choice& choice = choices_[c];
  switch (choice.kind) {
    case Kind::Emitters: {
      float triangleProbability;
      size_t index = emitterDistribution_.sample(u1, &triangleProbability);
      const Emitter& e = emitters_[index];
      const TriangleMesh& mesh = scene_.meshes[e.mesh];
      uint32_t i0 = mesh.indices[3 * e.triangle], i1 = mesh.indices[3 * e.triangle + 1],
               i2 = mesh.indices[3 * e.triangle + 2];
      Vec2f b = sampleUniformTriangle(u2);
      Vec3f q = mesh.positions[i0] * b.x + mesh.positions[i1] * b.y + mesh.positions[i2] * (1 - b.x - b.y);
      Vec3f n = normalize(cross(mesh.positions[i1] - mesh.positions[i0], mesh.positions[i2] - mesh.positions[i0]));
      Vec3f d = q - p;
      float dist2 = dot(d, d);
      if (dist2 <= 0 || e.area <= 0) return s;
      s.distance = std::sqrt(dist2);
      s.wi = d / s.distance;
      float cosLight = std::abs(dot(n, s.wi));
      if (cosLight <= 1e-6f) return s;
      Vec2f uv = mesh.uvs.empty() ? Vec2f(b.y, 1 - b.x - b.y)
                                  : mesh.uvs[i0] * b.x + mesh.uvs[i1] * b.y + mesh.uvs[i2] * (1 - b.x - b.y);
      s.radiance = scene_.emission(mesh.material, uv);
      s.pdf = choiceProbability * triangleProbability / e.area * dist2 / cosLight;
      return s;
    }
    case Kind::Punctual: {
      const PunctualLight& light = scene_.lights[choice.index];
      s.isDelta = true;
      s.pdf = choiceProbability;
      if (light.type == PunctualLight::Type::Directional) {
        s.wi = -normalize(light.direction);
        s.distance = kInfinity;
        s.radiance = light.intensity;  // irradiance at normal incidence
        return s;
      }
      Vec3f d = light.position - p;
      float dist2 = dot(d, d);
      if (dist2 <= 0) return LightSample{};
      s.distance = std::sqrt(dist2);
      s.wi = d / s.distance;
      Rgb intensity = light.intensity;
      if (light.type == PunctualLight::Type::Spot) {
        float cosAngle = dot(-s.wi, normalize(light.direction));
        intensity *= spotAttenuation(cosAngle, std::cos(light.outerConeAngle), std::cos(light.innerConeAngle));
      }
      s.radiance = intensity / dist2;  // irradiance at normal incidence
      return s;
    }
    case Kind::Environment: {
      const Environment& env = scene_.environment;
      s.distance = kInfinity;
      if (env.map.empty()) {
        s.wi = sampleUniformSphere(u2);
        s.pdf = choiceProbability * uniformSpherePdf();
      } else {
        float mapPdf;
        Vec2f uv = environmentDistribution_.sample(u2, &mapPdf);
        s.wi = equirectToDirection(uv, env.rotationY);
        float sinTheta = std::sin(uv.y * kPi);
        if (sinTheta <= 0) return LightSample{};
        s.pdf = choiceProbability * mapPdf / (2 * kPi * kPi * sinTheta);
      }
      s.radiance = environmentRadiance(s.wi);
      return s;
    }
  }
  return s;
}

}  // namespace glint
