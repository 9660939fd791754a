// `glint synth`: renders every camera of a scene's two paths with the reference path tracer
// and writes a complete dataset (docs/data-format.md), then a point cloud from the depth buffers.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "io/image.h"
#include "synth/depth_point_cloud.h"
#include "scene/buffers.h"
#include "scene/camera.h"
#include "synth/mesh_scene.h"
#include "synth/path_tracer.h"

namespace glint {

struct SynthSettings {
  int trainViews = 100;
  int testViews = 20;
  int width = 256;
  int height = 192;
  int spp = 256;
  // Samples per pixel of the test split; 0 means spp. Test views are the ground truth of
  // evaluation: their own Monte Carlo noise is scored as reconstruction error (at 256 spp
  // it caps builtin:spheres' final PSNR near 33.6 dB), so they may be rendered closer to
  // convergence than the training views, whose noise averages out over many views.
  int testSpp = 0;
  int bounces = 6;
  uint64_t seed = 0;
  ImageFormat format = ImageFormat::Exr;
  float exposure = 1.0f;  // multiplies render, diffuse and specular
  int pointCloudMaxPoints = 300000;

  // The test split's samples per pixel, with 0 resolved to spp.
  int testSamplesPerPixel() const { return testSpp > 0 ? testSpp : spp; }
};

// Renders one view: radiance buffers average spp jittered samples per pixel (box filter);
// the G-buffers (depth, normal, roughness, F0) come from the ray through the pixel centre,
// so they are exact values of one surface point, never blends across an edge. viewKey
// selects the random streams (one per pixel, derived from seed, viewKey and pixel).
// progress advances by spp units (path samples) per pixel.
ViewBuffers renderView(const PathTracer& tracer, const Camera& camera, const SynthSettings& settings,
                       uint64_t viewKey, class ProgressBar* progress = nullptr);

// Generates the whole dataset into outDir (created if needed). Files are written
// atomically; existing datasets are overwritten only file by file. In an MPI job the views
// (training then test, as one list) go round-robin to the ranks (scene/view_sharing.h),
// each writing its own views' buffers; rank 0 makes the folders first and alone writes
// the transforms files and the point cloud.
void generateDataset(const MeshScene& scene, const SynthSettings& settings, const std::filesystem::path& outDir);

}  // namespace glint
