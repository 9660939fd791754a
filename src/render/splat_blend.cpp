// Front-to-back blending of per-Gaussian SH colours along a traced ray's hit list.
#include "render/splat_blend.h"

#include <algorithm>

namespace glint {

Rgb splatColourAt(const SplatColour& colour, size_t i, const Vec3f& d) {
  Rgb c = colour.base[i];
  if (colour.shDegree == 0) return c;
  float basis[kMaxShCoefficients];
  shBasis(d, colour.shDegree, basis);
  const Rgb* rest = colour.rest(i);
  for (size_t k = 0; k < colour.restCount(); ++k) c += rest[k] * basis[k + 1];
  return c;
}

Rgb blendSplatColour(const GaussianScene& scene, const SplatColour& colour, const Vec3f& eye, const HitList& hits) {
  Rgb sum(0.0f);
  float T = 1.0f;
  for (const HitRecord& hit : hits.hits) {
    const Vec3f d = normalize(scene.position[hit.id] - eye);
    const Rgb c = splatColourAt(colour, hit.id, d);
    // 3DGS clamps the SH colour at 0 (its rasteriser's clamp before blending).
    sum += Rgb(std::max(c.x, 0.0f), std::max(c.y, 0.0f), std::max(c.z, 0.0f)) * (T * hit.alpha);
    T *= 1.0f - hit.alpha;
  }
  return sum;
}

}  // namespace glint
