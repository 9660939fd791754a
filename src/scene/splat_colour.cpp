// Display-referred colour of Gaussians for splat exporters.
#include "scene/splat_colour.h"

#include <cmath>
#include <string>

#include "core/error.h"
#include "io/tonemap.h"

namespace glint {

bool SplatColour::consistent(size_t n) const {
  return shDegree >= 0 && shDegree <= kMaxShDegree && base.size() == n && sh.size() == n * restCount();
}

SplatColour displayColour(const GaussianScene& scene, float exposure) {
  SplatColour colour;
  colour.base.resize(scene.size());
  for (size_t i = 0; i < scene.size(); ++i) colour.base[i] = tonemapFilmic(scene.diffuse[i] * exposure);
  return colour;
}

void requireFiniteSplats(const std::filesystem::path& path, const GaussianScene& scene, const SplatColour& colour) {
  auto finite = [](const Vec3f& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  for (size_t i = 0; i < scene.size(); ++i) {
    const Quatf& q = scene.rotation[i];
    bool ok = finite(scene.position[i]) && finite(scene.logScale[i]) && std::isfinite(scene.opacityLogit[i]) &&
              finite({q.x, q.y, q.z}) && std::isfinite(q.w) && finite(colour.base[i]);
    for (size_t k = 0; k < colour.restCount(); ++k) ok = ok && finite(colour.rest(i)[k]);
    if (!ok) throw Error(path.string(), "Gaussian " + std::to_string(i) + " has a NaN or infinite value; not written");
  }
}

}  // namespace glint
