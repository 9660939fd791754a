// Physics tests of the reference path tracer: furnaces, analytic direct lighting, the
// diffuse/specular split, and exact G-buffers of a sphere.
#include "synth/path_tracer.h"

#include <gtest/gtest.h>

#include <cmath>

#include "math/sampling.h"
#include "synth/dataset_generator.h"
#include "synth/light_sampler.h"
#include "synth/mesh_builder.h"
#include "synth/ray_caster.h"

namespace glint {
namespace {

// A single sphere of radius 1 at the origin under a uniform white environment of radiance 1.
MeshScene furnaceScene(const Material& material) {
  MeshScene scene;
  scene.materials.push_back(material);
  scene.spheres.push_back({{0, 0, 0}, 1.0f, 0});
  scene.environment.constant = Rgb(1.0f);
  return scene;
}

Camera lookingAtOrigin(int width, int height, double distance = 4.0) {
  Camera camera;
  camera.cameraToWorld = Mat4::lookAt({0.3, 0.2, distance}, {0, 0, 0}, {0, 1, 0});
  camera.width = width;
  camera.height = height;
  camera = Camera::fromFieldOfView(camera.cameraToWorld, 0.6, camera.width, camera.height);
  return camera;
}

struct RenderResult {
  ViewBuffers buffers;
  double meanOnSphere = 0;
  double maxDeviation = 0;
  int sphereCount = 0;
};

RenderResult renderFurnace(const Material& material, int spp) {
  MeshScene scene = furnaceScene(material);
  RayCaster caster(scene);
  LightSampler lights(scene);
  PathTracer tracer(scene, caster, lights, PathTracerSettings{8, 3});
  SynthSettings settings;
  settings.spp = spp;
  settings.seed = 7;
  RenderResult r;
  r.buffers = renderView(tracer, lookingAtOrigin(24, 18), settings, 1);
  const Image& render = r.buffers[Buffer::Render];
  double sum = 0;
  for (int y = 0; y < render.height; ++y)
    for (int x = 0; x < render.width; ++x) {
      if (!hasSurface(r.buffers[Buffer::Depth].at(x, y))) continue;
      for (int c = 0; c < 3; ++c) {
        sum += render.at(x, y, c);
        r.maxDeviation = std::max(r.maxDeviation, std::abs(double(render.at(x, y, c)) - 1.0));
      }
      ++r.sphereCount;
    }
  r.meanOnSphere = sum / (3.0 * r.sphereCount);
  return r;
}

TEST(PathTracerFurnace, WhiteDiffuseSphereReflectsExactlyTheEnvironment) {
  Material white;
  white.baseColor = Rgb(1.0f);
  white.metallic = 0.0f;
  white.specularLevel = 0.0f;  // no specular lobe: albedo exactly 1
  RenderResult r = renderFurnace(white, 64);
  ASSERT_GT(r.sphereCount, 50);
  EXPECT_NEAR(r.meanOnSphere, 1.0, 0.01);
  EXPECT_LT(r.maxDeviation, 0.25);  // per pixel, 64 samples
  // Without a specular lobe the specular buffer is exactly zero.
  for (float v : r.buffers[Buffer::Specular].pixels) ASSERT_EQ(v, 0.0f);
}

TEST(PathTracerFurnace, AnEnvironmentMapOfOnesIsAFurnaceToo) {
  // The same furnace through the importance-sampled equirectangular path: a map whose
  // every texel is 1 must light a white diffuse sphere to exactly 1.
  Material white;
  white.baseColor = Rgb(1.0f);
  white.specularLevel = 0.0f;
  MeshScene scene = furnaceScene(white);
  scene.environment.map = Image(16, 8, 3, 1.0f);
  scene.environment.rotationY = 0.7f;
  RayCaster caster(scene);
  LightSampler lights(scene);
  PathTracer tracer(scene, caster, lights, PathTracerSettings{8, 3});
  Rng rng(3);
  double sum = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    Vec3f target = sampleUniformSphere(rng.uniform2()) * 0.9f;
    Vec3f origin(0, 0, 4);
    sum += tracer.trace(origin, normalize(target - origin), rng).render().y;
  }
  EXPECT_NEAR(sum / n, 1.0, 0.01);
}

TEST(PathTracerFurnace, SmoothMetalSphereWithUnitF0ReflectsTheEnvironment) {
  Material chrome;
  chrome.baseColor = Rgb(1.0f);
  chrome.metallic = 1.0f;
  chrome.roughness = 0.05f;
  RenderResult r = renderFurnace(chrome, 16);
  ASSERT_GT(r.sphereCount, 50);
  // Single-scattering GGX loses < 0.5% at this roughness.
  EXPECT_NEAR(r.meanOnSphere, 1.0, 0.01);
  // Per pixel, grazing views at the silhouette lose a few percent to single scattering
  // (G2 / G1 < 1 there), which is the model, not noise.
  EXPECT_LT(r.maxDeviation, 0.1);
  // A metal has no diffuse lobe: all its light is specular, except where the environment is seen.
  // (Pixels on the silhouette mix in jittered samples that miss the sphere: skip them.)
  const Image& diffuse = r.buffers[Buffer::Diffuse];
  const Image& depth = r.buffers[Buffer::Depth];
  for (int y = 1; y + 1 < diffuse.height; ++y)
    for (int x = 1; x + 1 < diffuse.width; ++x) {
      bool interior = true;
      for (int d = -1; d <= 1; ++d) interior = interior && hasSurface(depth.at(x + d, y)) && hasSurface(depth.at(x, y + d));
      if (interior) {
        ASSERT_EQ(diffuse.at(x, y, 0), 0.0f) << x << "," << y;
      }
    }
}

TEST(PathTracerSplit, RenderIsDiffusePlusSpecularPerPixel) {
  MeshScene scene;
  Material plastic;
  plastic.baseColor = Rgb(0.6f, 0.3f, 0.2f);
  plastic.roughness = 0.3f;
  scene.materials.push_back(plastic);
  Material emitter;
  emitter.baseColor = Rgb(0.0f);
  emitter.emission = Rgb(4.0f);
  scene.materials.push_back(emitter);
  scene.spheres.push_back({{0, 0, 0}, 1.0f, 0});
  scene.meshes.push_back(makeQuad("light", {-1, 2.5f, -1}, {2, 0, 0}, {0, 0, 2}, 1));
  scene.environment.constant = Rgb(0.2f, 0.3f, 0.4f);
  RayCaster caster(scene);
  LightSampler lights(scene);
  PathTracer tracer(scene, caster, lights, PathTracerSettings{4, 3});
  SynthSettings settings;
  settings.spp = 8;
  settings.exposure = 3.5f;
  ViewBuffers b = renderView(tracer, lookingAtOrigin(20, 16, 6.0), settings, 3);
  for (size_t i = 0; i < b[Buffer::Render].pixels.size(); ++i) {
    float sum = b[Buffer::Diffuse].pixels[i] + b[Buffer::Specular].pixels[i];
    ASSERT_NEAR(b[Buffer::Render].pixels[i], sum, 1e-5f * std::max(1.0f, std::abs(sum)));
  }
}

TEST(PathTracerGBuffer, DepthAndNormalsMatchTheAnalyticSphere) {
  Material grey;
  MeshScene scene = furnaceScene(grey);
  scene.spheres[0].center = {0.2f, -0.1f, 0.3f};
  scene.spheres[0].radius = 0.8f;
  RayCaster caster(scene);
  LightSampler lights(scene);
  PathTracer tracer(scene, caster, lights, PathTracerSettings{1, 3});
  SynthSettings settings;
  settings.spp = 1;
  Camera camera = lookingAtOrigin(32, 24);
  ViewBuffers b = renderView(tracer, camera, settings, 1);
  const Vec3d c(0.2, -0.1, 0.3);
  const double r = 0.8;
  int hits = 0;
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      Ray ray = camera.generateRay(x + 0.5, y + 0.5);
      // |o + t d - c|^2 = r^2 with |d| = 1.
      Vec3d oc = ray.origin - c;
      double bHalf = dot(oc, ray.direction);
      double disc = bHalf * bHalf - (dot(oc, oc) - r * r);
      float depth = b[Buffer::Depth].at(x, y);
      if (disc <= 1e-9) {
        if (disc < -1e-6) {
          EXPECT_EQ(depth, 0.0f) << x << "," << y;
        }
        continue;
      }
      double t = -bHalf - std::sqrt(disc);
      Vec3d n = normalize(ray.origin + ray.direction * t - c);
      EXPECT_NEAR(depth, t, 1e-4 * t) << x << "," << y;
      Rgb normal = b[Buffer::Normal].rgb(x, y);
      EXPECT_NEAR(normal.x, n.x, 1e-4);
      EXPECT_NEAR(normal.y, n.y, 1e-4);
      EXPECT_NEAR(normal.z, n.z, 1e-4);
      EXPECT_NEAR(b[Buffer::Roughness].at(x, y), grey.roughness, 1e-6);
      ++hits;
    }
  EXPECT_GT(hits, 100);
}

TEST(PathTracerDirect, DiffusePlaneUnderPointLightMatchesTheAnalyticRadiance) {
  // Lambert plane y = 0 of albedo a, point light of intensity I at height h:
  // L = a / pi * I cos(theta) / d^2 at every point.
  MeshScene scene;
  Material matte;
  matte.baseColor = Rgb(0.5f);
  matte.specularLevel = 0.0f;
  scene.materials.push_back(matte);
  scene.meshes.push_back(makeQuad("plane", {-50, 0, 50}, {100, 0, 0}, {0, 0, -100}, 0));
  PunctualLight light;
  light.position = {0.4f, 2.0f, -0.3f};
  light.intensity = Rgb(10.0f);
  scene.lights.push_back(light);
  RayCaster caster(scene);
  LightSampler lights(scene);
  PathTracer tracer(scene, caster, lights, PathTracerSettings{1, 3});
  Rng rng(5);
  for (int i = 0; i < 50; ++i) {
    Vec3f target(rng.uniform() * 4 - 2, 0, rng.uniform() * 4 - 2);
    Vec3f origin(0.1f, 3.0f, 3.0f);
    Vec3f dir = normalize(target - origin);
    RadianceSample s = tracer.trace(origin, dir, rng);
    Vec3f toLight = light.position - target;
    float d2 = dot(toLight, toLight);
    float expected = 0.5f * kInvPi * 10.0f * (toLight.y / std::sqrt(d2)) / d2;
    EXPECT_NEAR(s.diffuse.x, expected, 1e-3f * expected);
    EXPECT_EQ(s.specular.x, 0.0f);
  }
}

TEST(PathTracerDirect, AreaLightMatchesTheAnalyticFormFactor) {
  // A small Lambert receiver of albedo 1 at the origin facing +y, under an emissive square.
  // The square has side 1 and hangs at height 1; Lambert's polygon formula gives its
  // irradiance E = L/2 sum_i angle_i (n . unit(v_i x v_{i+1})).
  MeshScene scene;
  Material matte;
  matte.baseColor = Rgb(1.0f);
  matte.specularLevel = 0.0f;
  scene.materials.push_back(matte);
  Material emitter;
  emitter.baseColor = Rgb(0.0f);
  emitter.specularLevel = 0.0f;
  emitter.emission = Rgb(3.0f);
  scene.materials.push_back(emitter);
  scene.meshes.push_back(makeQuad("floor", {-0.01f, 0, 0.01f}, {0.02f, 0, 0}, {0, 0, -0.02f}, 0));
  const float h = 1.0f, half = 0.5f;
  scene.meshes.push_back(makeQuad("light", {-half, h, -half}, {2 * half, 0, 0}, {0, 0, 2 * half}, 1));
  RayCaster caster(scene);
  LightSampler lights(scene);
  PathTracer tracer(scene, caster, lights, PathTracerSettings{1, 3});
  // Lambert's polygon formula: E / L = 1/2 sum_i angle_i (n . (v_i x v_{i+1}) / |v_i x v_{i+1}|).
  Vec3d corners[4] = {{-half, h, -half}, {half, h, -half}, {half, h, half}, {-half, h, half}};
  double sum = 0;
  for (int i = 0; i < 4; ++i) {
    Vec3d a = normalize(corners[i]), b = normalize(corners[(i + 1) % 4]);
    Vec3d c = cross(a, b);
    sum += std::acos(std::clamp(dot(a, b), -1.0, 1.0)) * std::abs(c.y) / length(c);
  }
  double irradiance = 3.0 * 0.5 * sum;
  double expected = irradiance / kPi;  // albedo 1
  Rng rng(11);
  double total = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) total += tracer.trace({0, 0.5f, 0.2f}, normalize(Vec3f(0, -0.5f, -0.2f)), rng).diffuse.x;
  EXPECT_NEAR(total / n, expected, 0.01 * expected);
}

TEST(PathTracerDeterminism, SameSeedSameImageWhateverTheThreads) {
  Material white;
  MeshScene scene = furnaceScene(white);
  RayCaster caster(scene);
  LightSampler lights(scene);
  PathTracer tracer(scene, caster, lights, PathTracerSettings{3, 3});
  SynthSettings settings;
  settings.spp = 4;
  ViewBuffers a = renderView(tracer, lookingAtOrigin(16, 12), settings, 9);
  ViewBuffers b = renderView(tracer, lookingAtOrigin(16, 12), settings, 9);
  EXPECT_EQ(a[Buffer::Render].pixels, b[Buffer::Render].pixels);
  ViewBuffers c = renderView(tracer, lookingAtOrigin(16, 12), settings, 10);
  EXPECT_NE(a[Buffer::Render].pixels, c[Buffer::Render].pixels);
}

}  // namespace
}  // namespace glint
