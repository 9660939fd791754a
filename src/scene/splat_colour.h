// The colour a plain 3D Gaussian Splatting viewer shows for each Gaussian: display-referred
// (after the filmic tonemap, as 3DGS treats f_dc), a constant term and optional
// spherical-harmonics coefficients. What every splat exporter writes besides the geometry.
#pragma once

#include <cstddef>
#include <filesystem>
#include <vector>

#include "math/spherical_harmonics.h"
#include "math/vec.h"
#include "scene/gaussians.h"

namespace glint {

struct SplatColour {
  // colour(d) = base + sum_{k >= 1} sh_k B_k(d) (math/spherical_harmonics.h), so base is
  // 0.5 + kShC0 f_dc in 3DGS's terms and the sh_k are its f_rest coefficients.
  std::vector<Rgb> base;
  int shDegree = 0;  // 0..3
  // Gaussian i's coefficient k >= 1 at i * restCount() + (k - 1); empty for degree 0.
  std::vector<Rgb> sh;

  size_t size() const { return base.size(); }
  size_t restCount() const { return size_t(shCoefficientCount(shDegree) - 1); }
  const Rgb* rest(size_t i) const { return sh.data() + i * restCount(); }
  // True when base has n entries and sh n * restCount().
  bool consistent(size_t n) const;
  // The same colours at SH degree `degree`: coefficients the colours lack are zero, those
  // beyond the degree are dropped.
  SplatColour withDegree(int degree) const;
  // Keeps the colours of the Gaussians whose keep[i] is true, in order (as
  // GaussianScene::filter keeps the Gaussians).
  void filter(const std::vector<bool>& keep);
};

// The view-independent display colour of every Gaussian: tonemapFilmic(exposure x diffuse)
// (io/tonemap.h), the picture Glint's own 8-bit images show for the diffuse pass. Degree 0.
SplatColour displayColour(const GaussianScene& scene, float exposure = 1.0f);

// Throws Error naming `path` (the file about to be written) when a position, scale,
// rotation, opacity or colour value is NaN or infinite, which no compressed format can hold.
void requireFiniteSplats(const std::filesystem::path& path, const GaussianScene& scene, const SplatColour& colour);

}  // namespace glint
