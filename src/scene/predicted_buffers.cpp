// Depth kinds, normal axes and decoding, and F0 and roughness rules for predicted buffers.
#include "scene/predicted_buffers.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "scene/buffers.h"

namespace glint {

Vec3d cameraRay(const RayIntrinsics& k, double px, double py) {
  return {(px - k.cx) / k.fx, -(py - k.cy) / k.fy, -1.0};
}

double rayLengthPerZ(const RayIntrinsics& k, int i, int j) { return length(cameraRay(k, i + 0.5, j + 0.5)); }

namespace {

// Multiplies (z -> distance) or divides (distance -> z) every surface depth by the pixel's
// rayLengthPerZ; "no surface" values are kept.
Image scaleDepthByRayLength(const Image& depth, const RayIntrinsics& k, bool toDistance) {
  GLINT_CHECK(depth.channels == 1, "depth must have one channel");
  Image out = depth;
  for (int j = 0; j < depth.height; ++j)
    for (int i = 0; i < depth.width; ++i) {
      float& d = out.at(i, j);
      double s = rayLengthPerZ(k, i, j);
      if (hasSurface(d)) d = static_cast<float>(toDistance ? d * s : d / s);
    }
  return out;
}

}  // namespace

Image zDepthToDistance(const Image& zDepth, const RayIntrinsics& k) { return scaleDepthByRayLength(zDepth, k, true); }

Image distanceToZDepth(const Image& distance, const RayIntrinsics& k) {
  return scaleDepthByRayLength(distance, k, false);
}

const char* cameraAxesName(CameraAxes axes) {
  switch (axes) {
    case CameraAxes::OpenGl: return "OpenGL";
    case CameraAxes::OpenCv: return "OpenCV";
    case CameraAxes::PaperPrior: return "paper prior";
  }
  return "?";
}

// Each change of axes flips signs of components, so it is its own inverse.
Vec3d toOpenGlAxes(const Vec3d& v, CameraAxes axes) {
  switch (axes) {
    case CameraAxes::OpenGl: return v;
    case CameraAxes::OpenCv: return {v.x, -v.y, -v.z};
    case CameraAxes::PaperPrior: return {-v.x, v.y, v.z};
  }
  return v;
}

Vec3d fromOpenGlAxes(const Vec3d& v, CameraAxes axes) { return toOpenGlAxes(v, axes); }

namespace {

Vec3d normalAt(const Image& image, int i, int j) { return Vec3d(image.rgb(i, j)); }
void setNormal(Image& image, int i, int j, const Vec3d& n) { image.setRgb(i, j, Rgb(n)); }

// Applies f to every normal of a 3-channel image.
template <typename F>
Image mapNormals(const Image& normals, F f) {
  GLINT_CHECK(normals.channels == 3, "normal maps have three channels");
  Image out = normals;
  for (int j = 0; j < normals.height; ++j)
    for (int i = 0; i < normals.width; ++i) setNormal(out, i, j, f(normalAt(normals, i, j)));
  return out;
}

}  // namespace

Image decodeNormalMap(const Image& encoded) {
  return mapNormals(encoded, [](const Vec3d& v) {
    Vec3d n = v * 2.0 - Vec3d(1.0);
    double l = length(n);
    return l < kMinEncodedNormalLength || l > kMaxEncodedNormalLength ? Vec3d() : n / l;
  });
}

Image renormalizeNormals(const Image& normals) {
  return mapNormals(normals, [](const Vec3d& n) { return normalize(n); });
}

Image cameraNormalsToWorld(const Image& normals, CameraAxes axes, const Mat3d& cameraToWorld) {
  return mapNormals(normals, [&](const Vec3d& n) { return cameraToWorld * toOpenGlAxes(n, axes); });
}

Image worldNormalsToCamera(const Image& normals, CameraAxes axes, const Mat3d& cameraToWorld) {
  return mapNormals(normals, [&](const Vec3d& n) { return fromOpenGlAxes(cameraToWorld.transposeTimes(n), axes); });
}

Rgb f0FromMetalness(const Rgb& baseColour, float metalness, float specularLevel) {
  float dielectric = 0.08f * specularLevel;  // 0.04 at the default level 0.5
  return Rgb(dielectric * (1.0f - metalness)) + baseColour * metalness;
}

Image f0FromMetalness(const Image& baseColour, const Image& metalness, float specularLevel) {
  GLINT_CHECK(metalness.channels == 1, "metalness has one channel");
  GLINT_CHECK(baseColour.empty() || (baseColour.width == metalness.width && baseColour.height == metalness.height),
              "base colour and metalness differ in size");
  Image f0(metalness.width, metalness.height, 3);
  for (int j = 0; j < f0.height; ++j)
    for (int i = 0; i < f0.width; ++i) {
      Rgb base = baseColour.empty() ? Rgb(1.0f) : baseColour.rgb(i, j);
      f0.setRgb(i, j, f0FromMetalness(base, std::clamp(metalness.at(i, j), 0.0f, 1.0f), specularLevel));
    }
  return f0;
}

// f0FromMetalness's dielectric at specular level 0.5, the grey rule's F0 at metalness 0.
constexpr float kDielectricF0 = 0.04f;

bool greyF0IsMetal(const Rgb& f0) {
  constexpr float kHalfMetal = kDielectricF0 + (1.0f - kDielectricF0) * 0.5f;  // metalness 0.5: 0.52
  return std::max({f0.x, f0.y, f0.z}) >= kHalfMetal;
}

Image metalnessFromF0(const Image& f0) {
  GLINT_CHECK(f0.channels == 3, "F0 has three channels");
  Image metalness(f0.width, f0.height, 1);
  for (int j = 0; j < f0.height; ++j)
    for (int i = 0; i < f0.width; ++i) {
      const Rgb c = f0.rgb(i, j);
      const float brightest = std::max({c.x, c.y, c.z});
      metalness.at(i, j) = std::clamp((brightest - kDielectricF0) / (1.0f - kDielectricF0), 0.0f, 1.0f);
    }
  return metalness;
}

Rgb diffuseAlbedoFromMetalness(const Rgb& baseColour, float metalness) { return baseColour * (1.0f - metalness); }

float perceptualFromAlpha(float alpha) { return std::sqrt(std::clamp(alpha, 0.0f, 1.0f)); }

Image toPerceptualRoughness(const Image& roughness, RoughnessKind kind) {
  GLINT_CHECK(roughness.channels == 1, "roughness has one channel");
  Image out = roughness;
  for (float& r : out.pixels) r = kind == RoughnessKind::Alpha ? perceptualFromAlpha(r) : std::clamp(r, 0.0f, 1.0f);
  return out;
}

}  // namespace glint
