// Conversions that bring buffers from a network predictor (real captures, issue 21) to the
// definitions of docs/data-format.md: depth kinds, camera-space normals, F0 and roughness.
#pragma once

#include "io/image.h"
#include "math/mat3.h"
#include "math/vec.h"

namespace glint {

// The four numbers that turn a pixel position into a camera-space ray, in pixels. Pixel
// (i, j) has its centre at (i + 0.5, j + 0.5), counted from the top-left corner.
struct RayIntrinsics {
  double fx = 1, fy = 1;  // focal lengths
  double cx = 0, cy = 0;  // principal point
};

// The camera-space ray through the continuous pixel position (px, py) in OpenGL camera
// axes, ((px - cx)/fx, -(py - cy)/fy, -1). Not normalised: its z is -1, so a point at
// z-depth z along it is z times this vector.
Vec3d cameraRay(const RayIntrinsics& k, double px, double py);
// Length of cameraRay at the centre of pixel (i, j): distance = z-depth x this.
double rayLengthPerZ(const RayIntrinsics& k, int i, int j);

// Depth kinds. Glint's depth buffer holds the distance from the camera centre along the
// pixel's ray; predictors and COLMAP give z-depth, the distance along the camera axis.
// Both keep "no surface" values (0, or kNoSurfaceDepth and above) as they are.
Image zDepthToDistance(const Image& zDepth, const RayIntrinsics& k);
Image distanceToZDepth(const Image& distance, const RayIntrinsics& k);

// Axes of a camera-space normal map.
enum class CameraAxes {
  OpenGl,      // x right, y up, z toward the viewer (Glint's and Blender's camera axes)
  OpenCv,      // x right, y down, z forward (COLMAP's)
  PaperPrior,  // x left, y up, z toward the viewer: OpenCV negated, what the paper's prior
               // loaders expect in their normal PNGs (docs/paper-prior-layout.md)
};
constexpr int kCameraAxesCount = 3;
const char* cameraAxesName(CameraAxes axes);  // "OpenGL", "OpenCV", "paper prior"

// A camera-space vector in the given axes, expressed in OpenGL camera axes, and back.
Vec3d toOpenGlAxes(const Vec3d& v, CameraAxes axes);
Vec3d fromOpenGlAxes(const Vec3d& v, CameraAxes axes);

// A unit normal decodes to length 1 (up to quantisation); a decoded vector outside these
// bounds is "no surface", not a direction: background stored as mid-grey decodes to about
// 0, stored as black or white to length sqrt(3).
constexpr double kMinEncodedNormalLength = 0.5;
constexpr double kMaxEncodedNormalLength = 1.5;

// A normal map read by readImage (values in [0, 1], from 8- or 16-bit PNG) decoded with
// n = 2v - 1 and renormalised; vectors outside the bounds above become 0.
Image decodeNormalMap(const Image& encoded);
// Unit normals (or 0 for "no surface") rescaled to unit length, 0 kept as 0.
Image renormalizeNormals(const Image& normals);

// Camera-space normals in the given axes -> world-space normals, given the camera-to-world
// rotation in OpenGL camera axes (the rotation part of a transforms.json matrix). Zero
// normals stay zero. For a COLMAP view with world-to-camera rotation Rcw (OpenCV axes),
// the OpenGL camera-to-world rotation is Rcw^T diag(1, -1, -1).
Image cameraNormalsToWorld(const Image& normals, CameraAxes axes, const Mat3d& cameraToWorld);
Image worldNormalsToCamera(const Image& normals, CameraAxes axes, const Mat3d& cameraToWorld);

// Glint's F0 (docs/data-format.md): (1 - metallic) 0.08 specularLevel + metallic baseColour,
// with the Principled specular level 0.5 giving the dielectric 0.04 of glTF's
// metallic-roughness model, F0 = mix(0.04, baseColour, metallic).
Rgb f0FromMetalness(const Rgb& baseColour, float metalness, float specularLevel = 0.5f);
// Per pixel; an empty baseColour means white, the paper's rule for captures with only a
// metalness prediction (F0 = 0.04 (1 - m) + m, grey). Metalness is clamped to [0, 1].
Image f0FromMetalness(const Image& baseColour, const Image& metalness, float specularLevel = 0.5f);
// The metalness a predictor without F0 would give: the inverse of the grey rule above on F0's
// brightest channel, m = (max(F0) - 0.04) / 0.96 clamped to [0, 1], so a tinted metal
// (gold's F0 of about (1, 0.78, 0.34)) reads fully metallic and loses its tint.
Image metalnessFromF0(const Image& f0);
// Whether a grey F0 made from a metalness by the white-base rule stands for a metal
// (metalness >= 0.5, so F0 >= 0.52). Only a metal's F0 can be tinted: a dielectric's is the
// Fresnel reflectance of a real refractive index at normal incidence, achromatic (0.02-0.08).
bool greyF0IsMetal(const Rgb& f0);
// glTF's diffuse albedo baseColour (1 - metallic). Glint's diffuse buffer is radiance, not
// albedo: this serves predictors that give albedo, e.g. to initialise Gaussian colours.
Rgb diffuseAlbedoFromMetalness(const Rgb& baseColour, float metalness);

// Roughness conventions. Glint's roughness buffer holds perceptual roughness r; the GGX
// width is alpha = r^2. A predictor may give either.
enum class RoughnessKind { Perceptual, Alpha };
inline float alphaFromPerceptual(float r) { return r * r; }
float perceptualFromAlpha(float alpha);  // sqrt, alpha clamped to [0, 1]
// A roughness image of the given kind as perceptual roughness in [0, 1].
Image toPerceptualRoughness(const Image& roughness, RoughnessKind kind);

}  // namespace glint
