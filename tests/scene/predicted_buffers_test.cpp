// Depth kinds, normal axes and decoding, F0 from metalness and roughness conventions.
#include "scene/predicted_buffers.h"

#include <gtest/gtest.h>

#include <cmath>

#include "math/quat.h"
#include "scene/buffers.h"

namespace glint {
namespace {

constexpr double kPiDouble = 3.14159265358979323846;

Mat3d someRotation() { return quatToRotation(quatFromAxisAngle(normalize(Vec3d(0.3, -1.0, 0.5)), 0.8)); }

TEST(DepthKinds, DistanceIsZDepthTimesTheRayLengthAtPixelCentres) {
  // cx, cy fall on the centre of pixel (2, 1), whose ray is the optical axis.
  RayIntrinsics k{100, 80, 2.5, 1.5};
  Image z(5, 3, 1, 4.0f);
  z.at(4, 2) = 0.0f;  // no surface
  z.at(0, 0) = kNoSurfaceDepth;
  Image distance = zDepthToDistance(z, k);
  EXPECT_FLOAT_EQ(distance.at(2, 1), 4.0f);
  // Pixel (0, 2): centre (0.5, 2.5), ray (-2/100, -1/80, -1).
  EXPECT_NEAR(distance.at(0, 2), 4.0 * std::sqrt(1.0 + 0.0004 + 1.0 / 6400.0), 1e-6);
  EXPECT_EQ(distance.at(4, 2), 0.0f);
  EXPECT_EQ(distance.at(0, 0), kNoSurfaceDepth);
  Image back = distanceToZDepth(distance, k);
  for (size_t p = 0; p < z.pixels.size(); ++p) EXPECT_NEAR(back.pixels[p], z.pixels[p], 1e-5f * z.pixels[p]);
}

TEST(DepthKinds, AFrontalPlaneHasConstantZDepth) {
  // A plane 3 units in front of a wide camera: distance along each ray is 3 |ray|.
  RayIntrinsics k{20, 20, 16, 12};
  Image distance(32, 24, 1);
  for (int j = 0; j < 24; ++j)
    for (int i = 0; i < 32; ++i) distance.at(i, j) = float(3.0 * length(cameraRay(k, i + 0.5, j + 0.5)));
  Image z = distanceToZDepth(distance, k);
  for (float v : z.pixels) EXPECT_NEAR(v, 3.0f, 1e-5f);
}

TEST(NormalAxes, ConversionsAreInvolutionsAndMatchTheirDefinitions) {
  Vec3d v(0.2, -0.5, 0.7);
  for (CameraAxes axes : {CameraAxes::OpenGl, CameraAxes::OpenCv, CameraAxes::PaperPrior}) {
    Vec3d back = fromOpenGlAxes(toOpenGlAxes(v, axes), axes);
    EXPECT_DOUBLE_EQ(back.x, v.x);
    EXPECT_DOUBLE_EQ(back.y, v.y);
    EXPECT_DOUBLE_EQ(back.z, v.z);
  }
  // A surface facing the camera: OpenGL +z, OpenCV -z, paper +z.
  EXPECT_DOUBLE_EQ(toOpenGlAxes({0, 0, -1}, CameraAxes::OpenCv).z, 1.0);
  EXPECT_DOUBLE_EQ(toOpenGlAxes({0, 0, 1}, CameraAxes::PaperPrior).z, 1.0);
  // Up: OpenCV's y points down; the paper's x points left.
  EXPECT_DOUBLE_EQ(toOpenGlAxes({0, -1, 0}, CameraAxes::OpenCv).y, 1.0);
  EXPECT_DOUBLE_EQ(toOpenGlAxes({-1, 0, 0}, CameraAxes::PaperPrior).x, 1.0);
}

TEST(NormalAxes, PaperPriorReadingMatchesThePaperLoadersRule) {
  // The paper's loaders compute n_world = R_cv (-v), with R_cv the camera-to-world rotation
  // in OpenCV axes, R_gl diag(1, -1, -1).
  Mat3d r = someRotation();
  Vec3d v = normalize(Vec3d(0.3, 0.4, 0.8));
  Vec3d flipped(-v.x, v.y, v.z);  // diag(1, -1, -1) (-v)
  Vec3d expected = r * flipped;
  Image map(1, 1, 3);
  map.setRgb(0, 0, Rgb(v));
  Rgb world = cameraNormalsToWorld(map, CameraAxes::PaperPrior, r).rgb(0, 0);
  EXPECT_NEAR(world.x, expected.x, 1e-6);
  EXPECT_NEAR(world.y, expected.y, 1e-6);
  EXPECT_NEAR(world.z, expected.z, 1e-6);
}

TEST(NormalAxes, CameraToWorldAndBackRoundTrip) {
  Mat3d r = someRotation();
  Image camera(3, 1, 3);
  camera.setRgb(0, 0, Rgb(normalize(Vec3f(0.1f, 0.2f, 0.9f))));
  camera.setRgb(1, 0, Rgb(0, 1, 0));
  // pixel 2 stays 0: no surface
  for (CameraAxes axes : {CameraAxes::OpenGl, CameraAxes::OpenCv, CameraAxes::PaperPrior}) {
    Image world = cameraNormalsToWorld(camera, axes, r);
    EXPECT_NEAR(length(world.rgb(0, 0)), 1.0f, 1e-6f);
    EXPECT_EQ(length(world.rgb(2, 0)), 0.0f);
    Image back = worldNormalsToCamera(world, axes, r);
    for (size_t p = 0; p < camera.pixels.size(); ++p) EXPECT_NEAR(back.pixels[p], camera.pixels[p], 1e-6f);
  }
  // OpenGL axes: the camera's +y is the rotation's second column.
  Rgb up = cameraNormalsToWorld(camera, CameraAxes::OpenGl, r).rgb(1, 0);
  Vec3d column = r.column(1);
  EXPECT_NEAR(up.x, column.x, 1e-6);
  EXPECT_NEAR(up.y, column.y, 1e-6);
  EXPECT_NEAR(up.z, column.z, 1e-6);
}

TEST(NormalDecoding, EightBitMapsDecodeWithinQuantisationAndBackgroundIsZero) {
  Image encoded(4, 1, 3);
  Vec3d n = normalize(Vec3d(0.36, -0.48, 0.8));
  for (int c = 0; c < 3; ++c) encoded.at(0, 0, c) = std::round((float(n[c]) * 0.5f + 0.5f) * 255.0f) / 255.0f;
  encoded.setRgb(1, 0, Rgb(128.0f / 255.0f));  // mid grey, a common background
  // pixel 2: black, the other common background
  encoded.setRgb(3, 0, Rgb(1.0f));  // white
  Image decoded = decodeNormalMap(encoded);
  Vec3d d(decoded.rgb(0, 0));
  EXPECT_NEAR(length(d), 1.0, 1e-6);
  EXPECT_LT(std::acos(std::min(1.0, dot(d, n))), 0.5 * kPiDouble / 180.0);  // 8-bit steps are ~0.2 degrees
  EXPECT_EQ(length(decoded.rgb(1, 0)), 0.0f);
  EXPECT_EQ(length(decoded.rgb(2, 0)), 0.0f);
  EXPECT_EQ(length(decoded.rgb(3, 0)), 0.0f);
}

TEST(NormalDecoding, SixteenBitMapsDecodeFarMorePrecisely) {
  Vec3d n = normalize(Vec3d(-0.7, 0.1, 0.7));
  Image encoded(1, 1, 3);
  for (int c = 0; c < 3; ++c) encoded.at(0, 0, c) = std::round((float(n[c]) * 0.5f + 0.5f) * 65535.0f) / 65535.0f;
  Vec3d d(decodeNormalMap(encoded).rgb(0, 0));
  // 2 asin(|d - n| / 2) measures small angles without the rounding of acos near 1.
  EXPECT_LT(2.0 * std::asin(length(d - n) / 2.0), 0.005 * kPiDouble / 180.0);  // 16-bit steps are ~0.002 degrees
}

TEST(NormalDecoding, RenormalisingKeepsZeroAndFixesLength) {
  Image normals(2, 1, 3);
  normals.setRgb(0, 0, Rgb(0.0f, 0.0f, 0.5f));
  Image unit = renormalizeNormals(normals);
  EXPECT_FLOAT_EQ(unit.at(0, 0, 2), 1.0f);
  EXPECT_EQ(length(unit.rgb(1, 0)), 0.0f);
}

TEST(F0, MetalnessRuleMatchesGlintsDefinitionAndGltf) {
  Rgb base(0.9f, 0.6f, 0.2f);
  Rgb dielectric = f0FromMetalness(base, 0.0f);
  EXPECT_FLOAT_EQ(dielectric.x, 0.04f);
  EXPECT_FLOAT_EQ(dielectric.z, 0.04f);
  Rgb metal = f0FromMetalness(base, 1.0f);
  EXPECT_FLOAT_EQ(metal.y, 0.6f);
  // glTF: mix(0.04, base, m).
  Rgb half = f0FromMetalness(base, 0.5f);
  EXPECT_NEAR(half.x, 0.5f * 0.04f + 0.5f * 0.9f, 1e-6f);
  // Glint's Principled specular level: 0.08 x level for dielectrics.
  EXPECT_NEAR(f0FromMetalness(base, 0.0f, 1.0f).x, 0.08f, 1e-7f);
  Rgb albedo = diffuseAlbedoFromMetalness(base, 0.25f);
  EXPECT_NEAR(albedo.x, 0.675f, 1e-6f);
}

TEST(F0, WithoutBaseColourFollowsThePapersGreyRule) {
  Image metalness(3, 1, 1);
  metalness.at(0, 0) = 0.0f;
  metalness.at(1, 0) = 0.3f;
  metalness.at(2, 0) = 1.2f;  // a predictor overshooting: clamped
  Image f0 = f0FromMetalness(Image(), metalness);
  ASSERT_EQ(f0.channels, 3);
  EXPECT_FLOAT_EQ(f0.at(0, 0, 1), 0.04f);
  EXPECT_NEAR(f0.at(1, 0, 0), 0.04f * 0.7f + 0.3f, 1e-6f);  // 0.04 (1 - m) + m
  EXPECT_FLOAT_EQ(f0.at(2, 0, 2), 1.0f);
  Image base(3, 1, 3, 0.5f);
  EXPECT_NEAR(f0FromMetalness(base, metalness).at(1, 0, 0), 0.04f * 0.7f + 0.3f * 0.5f, 1e-6f);
}

TEST(Roughness, AlphaAndPerceptualConvert) {
  EXPECT_FLOAT_EQ(alphaFromPerceptual(0.5f), 0.25f);
  EXPECT_FLOAT_EQ(perceptualFromAlpha(0.25f), 0.5f);
  EXPECT_FLOAT_EQ(perceptualFromAlpha(-0.1f), 0.0f);
  Image alpha(2, 1, 1);
  alpha.at(0, 0) = 0.09f;
  alpha.at(1, 0) = 1.5f;
  Image r = toPerceptualRoughness(alpha, RoughnessKind::Alpha);
  EXPECT_NEAR(r.at(0, 0), 0.3f, 1e-6f);
  EXPECT_FLOAT_EQ(r.at(1, 0), 1.0f);
  EXPECT_FLOAT_EQ(toPerceptualRoughness(alpha, RoughnessKind::Perceptual).at(0, 0), 0.09f);
}

TEST(MetalnessFromF0, InvertsTheGreyRuleAndCallsTintedMetalsMetallic) {
  Image f0(3, 1, 3);
  f0.setRgb(0, 0, Rgb(0.04f));                // a dielectric
  f0.setRgb(1, 0, Rgb(1.0f, 0.78f, 0.34f));   // gold
  f0.setRgb(2, 0, Rgb(0.52f));                // a half-metallic grey
  const Image m = metalnessFromF0(f0);
  ASSERT_EQ(m.channels, 1);
  EXPECT_NEAR(m.at(0, 0), 0.0f, 1e-6f);
  EXPECT_NEAR(m.at(1, 0), 1.0f, 1e-6f);
  EXPECT_NEAR(m.at(2, 0), 0.5f, 1e-6f);
  const Image back = f0FromMetalness(Image(), m);
  EXPECT_NEAR(back.at(2, 0, 1), 0.52f, 1e-6f);
}

// Metals are where the grey rule's metalness reaches one half; tinted metals count by their
// brightest channel, as metalnessFromF0 reads them.
TEST(MetalnessFromF0, GreyF0IsAMetalFromHalfMetalness) {
  EXPECT_FALSE(greyF0IsMetal(Rgb(0.04f)));
  EXPECT_FALSE(greyF0IsMetal(Rgb(0.51f)));
  EXPECT_TRUE(greyF0IsMetal(Rgb(0.52f)));
  EXPECT_TRUE(greyF0IsMetal(Rgb(1.0f)));
  EXPECT_TRUE(greyF0IsMetal(Rgb(0.2f, 0.3f, 0.9f)));
}

}  // namespace
}  // namespace glint
