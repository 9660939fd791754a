// Display-referred colour of Gaussians for splat exporters.
#include "scene/splat_colour.h"

#include <algorithm>

#include <cmath>
#include <string>

#include "core/error.h"
#include "io/tonemap.h"

namespace glint {

bool SplatColour::consistent(size_t n) const {
  return shDegree >= 0 && shDegree <= kMaxShDegree && base.size() == n && sh.size() == n * restCount();
}

SplatColour SplatColour::withDegree(int degree) const {
  SplatColour out;
  out.base = base;
  out.shDegree = degree;
  const size_t from = restCount(), to = out.restCount(), common = std::min(from, to);
  out.sh.assign(size() * to, Rgb(0.0f));
  for (size_t i = 0; i < size(); ++i)
    for (size_t k = 0; k < common; ++k) out.sh[i * to + k] = sh[i * from + k];
  return out;
}

void SplatColour::filter(const std::vector<bool>& keep) {
  const size_t rest = restCount();
  size_t kept = 0;
  for (size_t i = 0; i < keep.size(); ++i) {
    if (!keep[i]) continue;
    base[kept] = base[i];
    for (size_t k = 0; k < rest; ++k) sh[kept * rest + k] = sh[i * rest + k];
    ++kept;
  }
  base.resize(kept);
  sh.resize(kept * rest);
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
