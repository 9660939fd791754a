// The C++ half of the splat-transform round trip (run_roundtrip.sh): makes a small seeded
// scene, and compares a PLY that splat-transform decoded from Glint's .spz or
// .compressed.ply with what Glint exported, within the formats' quantisation tolerances
// (tests/common/splat_check.h).
//   splat_roundtrip_check make SCENE.ply
//   splat_roundtrip_check compare REFERENCE.ply DECODED.ply spz|compressed-ply
//   splat_roundtrip_check import DECODED.ply
// REFERENCE is the scene in Glint's layout (compared with its tonemapped diffuse colour),
// or Glint's 3dgs export of it (compared with its SH colours); exit status 1 on a mismatch.
// `import` reads splat-transform's PLY as a user's file is read (layout detection first)
// and checks that Glint shows the colour a 3DGS viewer shows.
#include <algorithm>
#include <cstdio>
#include <string>

#include "common/random_gaussians.h"
#include "common/splat_check.h"
#include "core/error.h"
#include "io/ply.h"
#include "io/tonemap.h"
#include "scene/compressed_ply_writer.h"
#include "scene/gaussian_ply.h"

namespace glint {
namespace {

// The splats a PLY holds: Glint's layout (display colour = tonemapped diffuse) or 3DGS's
// (display colour from f_dc, SH from f_rest_*, channel-major).
test::DecodedSplats splatsOf(const std::string& path, GaussianScene* sceneOut) {
  PlyTable table = readPly(path);
  const bool glintLayout = table.has("normal_0");
  GaussianScene scene = gaussianSceneFromPly(table, glintLayout ? PlyLayout::Glint : PlyLayout::ThreeDgs);
  SplatColour colour = displayColour(scene);
  if (!glintLayout) {
    // The colour as a viewer shows it, 0.5 + kShC0 f_dc (Glint's reader would turn it
    // back into linear diffuse).
    for (int k = 0; k < 3; ++k) {
      const std::vector<float>& fdc = table.column("f_dc_" + std::to_string(k));
      for (size_t i = 0; i < scene.size(); ++i) colour.base[i][k] = float(0.5 + kShC0 * double(fdc[i]));
    }
    size_t columns = 0;
    while (table.has("f_rest_" + std::to_string(columns))) ++columns;
    const size_t rest = columns / 3;
    colour.shDegree = rest >= 15 ? 3 : rest >= 8 ? 2 : rest >= 3 ? 1 : 0;
    colour.sh.assign(scene.size() * rest, Rgb(0.0f));
    for (size_t j = 0; j < columns; ++j) {
      const std::vector<float>& column = table.column("f_rest_" + std::to_string(j));
      for (size_t i = 0; i < scene.size(); ++i) colour.sh[i * rest + j % rest][int(j / rest)] = column[i];
    }
  }
  if (sceneOut) *sceneOut = scene;
  return test::expectedSplats(scene, colour);
}

// The widest chunk's ranges, as the compressed PLY writer forms its chunks.
test::SplatTolerance compressedTolerance(const test::DecodedSplats& s) {
  float position = 0, logScale = 0, colour = 0;
  for (size_t first = 0; first < s.size(); first += kCompressedPlyChunkSize) {
    const size_t last = std::min(s.size(), first + kCompressedPlyChunkSize);
    for (int a = 0; a < 3; ++a) {
      float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
      for (size_t i = first; i < last; ++i) {
        const float v[3] = {s.position[i][a], std::clamp(s.logScale[i][a], -20.0f, 20.0f), s.colour[i][a]};
        for (int q = 0; q < 3; ++q) lo[q] = std::min(lo[q], v[q]), hi[q] = std::max(hi[q], v[q]);
      }
      position = std::max(position, hi[0] - lo[0]);
      logScale = std::max(logScale, hi[1] - lo[1]);
      colour = std::max(colour, hi[2] - lo[2]);
    }
  }
  return test::compressedPlyTolerance(position, logScale, colour);
}

int compare(const std::string& referencePath, const std::string& decodedPath, const std::string& format) {
  GaussianScene reference;
  test::DecodedSplats expected = splatsOf(referencePath, &reference);
  const test::DecodedSplats decoded = splatsOf(decodedPath, nullptr);
  test::SplatTolerance tolerance = test::spzTolerance();
  if (format == "compressed-ply") {
    // Written in Morton order; the decoded file keeps that order.
    SplatColour colour;
    colour.base = expected.colour;
    colour.shDegree = expected.shDegree;
    colour.sh = expected.sh;
    expected = test::expectedSplats(reference, colour, compressedPlyOrder(reference));
    tolerance = compressedTolerance(expected);
  }
  const std::string failures = test::compareSplats(expected, decoded, tolerance);
  std::printf("%s: %zu Gaussians, SH degree %d, %s\n", decodedPath.c_str(), decoded.size(), decoded.shDegree,
              failures.empty() ? "all within the tolerances" : "MISMATCH");
  if (!failures.empty()) std::printf("%s", failures.c_str());
  return failures.empty() ? 0 : 1;
}

// splat-transform's PLY read by Glint's loader as `glint render FILE` reads it: a file with
// f_rest_* is 3DGS by its properties, one without (degree 0) for want of Glint's header,
// which the import must say. Either way, Glint's 8-bit filmic display of the imported
// diffuse must be the viewer's 0.5 + C0 f_dc within half a level (1 level where the
// viewer's colour lies above what the tonemap reaches).
int importCheck(const std::string& decodedPath) {
  const test::DecodedSplats viewer = splatsOf(decodedPath, nullptr);
  GaussianPlyImport import;
  GaussianScene scene;
  try {
    scene = readGaussianPly(decodedPath, PlyLayout::Auto, &import);
  } catch (const Error& e) {
    std::printf("%s: MISMATCH: refused: %s\n", decodedPath.c_str(), e.what());
    return 1;
  }
  if (import.layoutAssumed != (viewer.shDegree == 0)) {
    std::printf("%s: MISMATCH: the import %s that the missing header decided\n", decodedPath.c_str(),
                import.layoutAssumed ? "says" : "does not say");
    return 1;
  }
  const std::string how = import.layoutAssumed ? "read as 3DGS for want of Glint's header" : "detected as 3DGS";
  if (import.layout != PlyLayout::ThreeDgs || scene.size() != viewer.size()) {
    std::printf("%s: MISMATCH: read as Glint's layout or with a different count\n", decodedPath.c_str());
    return 1;
  }
  // Above 254.5 / 255 the tonemap saturates (tonemapFilmic(128) is that value), so a brighter
  // viewer colour can only be approached: those samples get a whole level.
  double worst = 0, worstSaturated = 0;
  size_t saturated = 0;
  for (size_t i = 0; i < scene.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      const double shown = 255.0 * tonemapFilmic(scene.diffuse[i][k]);
      const double wanted = 255.0 * std::clamp(double(viewer.colour[i][k]), 0.0, 1.0);
      if (wanted > 254.5) {
        ++saturated;
        worstSaturated = std::max(worstSaturated, std::abs(shown - wanted));
      } else {
        worst = std::max(worst, std::abs(shown - wanted));
      }
    }
  }
  const bool ok = worst <= 0.5 && worstSaturated <= 1.0;
  std::printf("%s: SH degree %d, %s; display colour off by at most %.4f of an 8-bit level (%zu saturated "
              "samples: %.3f), %s\n",
              decodedPath.c_str(), viewer.shDegree, how.c_str(), worst, saturated, worstSaturated,
              ok ? "as a 3DGS viewer shows it" : "MISMATCH");
  return ok ? 0 : 1;
}

int run(int argc, char** argv) {
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "make" && argc == 3) {
    GaussianScene scene = randomScene(700, 23);  // three chunks of the compressed PLY, the last partial
    for (size_t i = 0; i < scene.size(); ++i) scene.diffuse[i] *= 3.0f;  // HDR, so the tonemap matters
    writeGaussianPly(argv[2], scene);
    return 0;
  }
  if (command == "compare" && argc == 5) return compare(argv[2], argv[3], argv[4]);
  if (command == "import" && argc == 3) return importCheck(argv[2]);
  std::fprintf(stderr,
               "usage: %s make SCENE.ply | compare REFERENCE.ply DECODED.ply spz|compressed-ply | import DECODED.ply\n",
               argv[0]);
  return 2;
}

}  // namespace
}  // namespace glint

int main(int argc, char** argv) {
  try {
    return glint::run(argc, argv);
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "splat_roundtrip_check: %s\n", e.what());
    return 2;
  }
}
