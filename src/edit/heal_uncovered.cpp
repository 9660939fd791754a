// Healing the uncovered surface: vacated Gaussians projected onto planes fitted to the
// support around them, points of low coverage filled with Gaussians continued from the ring.
#include "edit/heal_uncovered.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>

#include "core/error.h"
#include "core/parallel.h"
#include "edit/texture_offset.h"
#include "math/frame.h"
#include "math/percentile.h"
#include "math/quat.h"
#include "scene/gaussian_cell_grid.h"

namespace glint {

namespace {

// The standard deviations across a Gaussian's two widest axes, as one (geometric mean).
float inPlaneSpread(const GaussianScene& scene, size_t i) {
  Vec3f s = scene.scale(i);
  float a[3] = {s.x, s.y, s.z};
  std::sort(a, a + 3);
  return std::sqrt(a[1] * a[2]);
}

// The largest opacity a ray through p along the unit direction w collects from Gaussian i
// (its response at the ray's closest approach in the Gaussian's own metric), and where along
// the ray that is.
float rayAlpha(const GaussianScene& scene, size_t i, const Vec3f& p, const Vec3f& w, float* t) {
  const Mat3f r = quatToRotation(scene.rotation[i]);
  const Vec3f s = scene.scale(i);
  const Vec3f offset = p - scene.position[i];
  // Local, whitened coordinates: the columns of r are the Gaussian's axes.
  Vec3f o, d;
  for (int k = 0; k < 3; ++k) {
    Vec3f axis(r.m[0][k], r.m[1][k], r.m[2][k]);
    o[k] = dot(offset, axis) / s[k];
    d[k] = dot(w, axis) / s[k];
  }
  const float dd = std::max(dot(d, d), 1e-20f);
  *t = -dot(o, d) / dd;
  const float distanceSquared = std::max(0.0f, dot(o, o) - dot(o, d) * dot(o, d) / dd);
  return scene.opacity(i) * std::exp(-0.5f * distanceSquared);
}

// Sets h's neighbours to the `count` Gaussians of `grid` nearest p within `radius` (by
// distance, then index), weighted by inverse distance (at most 10 / spacing) and normalised;
// false when there are none.
bool nearestWeighted(const GaussianScene& scene, const CellGrid& grid, const Vec3f& p, float radius, int count,
                     float spacing, HealedGaussian& h) {
  std::vector<std::pair<float, uint32_t>> found;
  grid.near(p, radius, [&](uint32_t j) { found.push_back({length(scene.position[j] - p), j}); });
  if (found.empty()) return false;
  std::sort(found.begin(), found.end());
  found.resize(std::min(found.size(), size_t(std::max(1, count))));
  float total = 0;
  for (const auto& [distance, j] : found) {
    h.neighbours.push_back(j);
    h.weights.push_back(1.0f / std::max(distance, 0.1f * spacing));
    total += h.weights.back();
  }
  for (float& w : h.weights) w /= total;
  return true;
}

// A point of a surface and its unit normal: a plane fitted to support Gaussians (their
// weighted centroid and mean normal) or a point of the uncovered surface; invalid where none
// was found.
struct SurfacePoint {
  Vec3f point, normal;
  bool valid = false;
};

// The texture a hole continues: the offset found (edit/texture_offset.h) on the plane of the
// hole's points that face their mean normal, and the sources, the seen Gaussians of that
// plane around the hole shifted by the offset. No offset where none repeats the texture.
struct HoleTexture {
  std::optional<TextureOffset> offset;
  Vec3f normal{0.0f};
  std::vector<uint32_t> sources;
};

HoleTexture holeTexture(const GaussianScene& scene, std::span<const SurfacePoint> hole, std::span<const uint32_t> seen,
                        float spacing, float slab, float reach, const TextureOffsetSettings& settings) {
  HoleTexture texture;
  Vec3f normalSum(0.0f);
  for (const SurfacePoint& h : hole) normalSum += h.normal;
  if (!(length(normalSum) > 0)) return texture;
  texture.normal = normalize(normalSum);
  std::vector<Vec3f> points;
  for (const SurfacePoint& h : hole)
    if (dot(h.normal, texture.normal) >= kSameSurfaceCosine) points.push_back(h.point);
  if (points.empty()) return texture;
  texture.offset = findTextureOffset(scene, seen, points, texture.normal, spacing, slab, settings);
  if (!texture.offset) return texture;
  Vec3d sum(0.0);
  for (const Vec3f& p : points) sum += Vec3d(p);
  const Vec3f centre(sum * (1.0 / double(points.size())));
  float radius = 0;
  for (const Vec3f& p : points) radius = std::max(radius, length(p - centre));
  const Vec3f shifted = centre + texture.offset->offset;
  for (uint32_t j : seen)
    if (length(scene.position[j] - shifted) <= radius + 4.0f * reach &&
        std::abs(dot(scene.position[j] - centre, texture.normal)) <= slab &&
        dot(normalize(scene.normal[j]), texture.normal) >= kSameSurfaceCosine)
      texture.sources.push_back(j);
  return texture;
}

// Healing's steps over shared state, in the order healUncovered takes them. Each step that
// can find nothing to do returns false, and healing ends there with what it reported.
class Healing {
 public:
  Healing(const GaussianScene& before, GaussianScene& after, EditProvenance& provenance, const HealSettings& settings)
      : before_(before), after_(after), provenance_(provenance), settings_(settings) {}

  HealReport run() {
    if (!findVacated() || !findSupport() || !findRing()) return report_;
    measureRingCoverage();
    candidates_ = candidatesAround(projectVacated());
    report_.candidates = candidates_.size();
    ringGrid_.emplace(after_, ring_, 8.0f * reach_);
    findHole();
    if (settings_.continueTexture) findTexture();
    sourceGrid_.emplace(after_, texture_.sources, 2.0f * spacing_);
    recolourHidden();
    fillHole();
    return report_;
  }

 private:
  // Vacated: moved or removed, and not kept where it was by any Gaussian after the edit;
  // and a sphere around their means.
  bool findVacated() {
    std::vector<uint8_t> keptInPlace(before_.size(), 0);
    for (size_t j = 0; j < after_.size(); ++j) {
      const uint32_t i = provenance_.source[j];
      if (provenance_.moved[j] && after_.position[j] == before_.position[i] &&
          after_.logScale[j] == before_.logScale[i])
        keptInPlace[i] = 1;
    }
    for (uint32_t i : provenance_.movedOrRemoved())
      if (!keptInPlace[i]) vacated_.push_back(i);
    report_.vacated = vacated_.size();
    if (vacated_.empty()) return false;
    Vec3d sum(0.0);
    for (uint32_t i : vacated_) sum += Vec3d(before_.position[i]);
    centre_ = Vec3f(sum * (1.0 / double(vacated_.size())));
    for (uint32_t i : vacated_) radius_ = std::max(radius_, length(before_.position[i] - centre_));
    return true;
  }

  // Support candidates: unmoved, opaque enough, with a normal, near the sphere. Their spacing
  // sets every length below; the ring around the sphere is as wide as a plane fit reaches.
  bool findSupport() {
    for (size_t j = 0; j < after_.size(); ++j)
      if (!provenance_.moved[j] && after_.opacity(j) >= settings_.minSupportOpacity &&
          length(after_.normal[j]) >= settings_.minNormalLength)
        nearby_.push_back(uint32_t(j));
    std::vector<float> spreads;
    for (uint32_t j : nearby_)
      if (length(after_.position[j] - centre_) <= 1.5f * radius_) spreads.push_back(inPlaneSpread(after_, j));
    spacing_ = percentileOf(spreads, 0.5);
    if (!(spacing_ > 0)) return false;
    report_.spacing = spacing_;
    reach_ = settings_.fitSpacings * spacing_;
    slab_ = settings_.coverageSlabSpacings * spacing_;
    for (uint32_t j : nearby_)
      if (length(after_.position[j] - centre_) <= radius_ + 2.0f * reach_) support_.push_back(j);
    report_.support = support_.size();
    if (support_.size() < size_t(settings_.minSupport)) return false;
    supportGrid_.emplace(after_, support_, reach_);
    return true;
  }

  // The ring: support no vacated Gaussian came within reach of (what the training views saw).
  bool findRing() {
    touched_.assign(support_.size(), 0);
    std::unordered_map<uint32_t, size_t> slot;
    for (size_t k = 0; k < support_.size(); ++k) slot[support_[k]] = k;
    std::vector<std::vector<uint32_t>> touchedBy(vacated_.size());
    parallelFor(int64_t(vacated_.size()), 64, [&](int64_t v) {
      supportGrid_->near(before_.position[vacated_[size_t(v)]], reach_,
                         [&](uint32_t j) { touchedBy[size_t(v)].push_back(j); });
    });
    for (const auto& list : touchedBy)
      for (uint32_t j : list) touched_[slot[j]] = 1;
    for (size_t k = 0; k < support_.size(); ++k)
      if (!touched_[k]) ring_.push_back(support_[k]);
    return !ring_.empty();
  }

  // Coverage of a surface point: the opacity collected along its normal from the Gaussians
  // (every one after the edit, moved ones included) near the surface there.
  float coverage(const Vec3f& p, const Vec3f& n) const {
    float transmittance = 1;
    allGrid_->near(p, reach_, [&](uint32_t j) {
      float t = 0;
      float alpha = rayAlpha(after_, j, p, n, &t);
      if (std::abs(t) <= slab_) transmittance *= 1.0f - std::min(alpha, 0.999f);
    });
    return 1.0f - transmittance;
  }

  void measureRingCoverage() {
    std::vector<uint32_t> all;
    for (size_t j = 0; j < after_.size(); ++j)
      if (length(after_.position[j] - centre_) <= radius_ + 3.0f * reach_) all.push_back(uint32_t(j));
    allGrid_.emplace(after_, all, reach_);
    std::vector<float> ringCoverages(ring_.size());
    parallelFor(int64_t(ring_.size()), 64, [&](int64_t k) {
      const uint32_t j = ring_[size_t(k)];
      ringCoverages[size_t(k)] = coverage(after_.position[j], normalize(after_.normal[j]));
    });
    report_.ringCoverage = percentileOf(ringCoverages, 0.5);
  }

  // The plane fitted to the support around c (weights: opacity times a smooth fall-off with
  // distance); invalid where too little support lies within the widest fit, or it strays
  // from a plane. A point amid a wide hole (a disc of floor that the selection took along
  // with the object) has no support within reach: its fit widens, doubling up to
  // widestFitSpacings.
  SurfacePoint fitAt(const Vec3f& c) const {
    const float widestFit = std::max(settings_.widestFitSpacings, settings_.fitSpacings) * spacing_;
    double weightSum = 0;
    Vec3d pointSum(0.0), normalSum(0.0);
    int count = 0;
    float fit = reach_;
    auto grid = [&]() -> const CellGrid& { return fit > reach_ ? *wideGrid_ : *supportGrid_; };
    for (;; fit *= 2) {
      weightSum = 0, pointSum = normalSum = Vec3d(0.0), count = 0;
      grid().near(c, fit, [&](uint32_t j) {
        const float q = 1.0f - dot(after_.position[j] - c, after_.position[j] - c) / (fit * fit);
        const double w = double(after_.opacity(j)) * double(q * q);
        weightSum += w;
        pointSum += Vec3d(after_.position[j]) * w;
        normalSum += Vec3d(normalize(after_.normal[j])) * w;
        ++count;
      });
      if (count >= settings_.minSupport || fit * 2 > widestFit) break;
    }
    if (count < settings_.minSupport || !(weightSum > 0) || !(length(normalSum) > 0.5 * weightSum)) return SurfacePoint{};
    SurfacePoint plane{Vec3f(pointSum * (1.0 / weightSum)), Vec3f(normalize(normalSum)), true};
    double residual = 0;
    grid().near(c, fit, [&](uint32_t j) {
      const float q = 1.0f - dot(after_.position[j] - c, after_.position[j] - c) / (fit * fit);
      const double h = dot(after_.position[j] - plane.point, plane.normal);
      residual += double(after_.opacity(j)) * double(q * q) * h * h;
    });
    if (std::sqrt(residual / weightSum) > settings_.maxResidualSpacings * spacing_) return SurfacePoint{};
    return plane;
  }

  // Surface points under the vacated Gaussians: each projected onto the plane fitted around it.
  std::vector<SurfacePoint> projectVacated() {
    const float widestFit = std::max(settings_.widestFitSpacings, settings_.fitSpacings) * spacing_;
    wideGrid_.emplace(after_, support_, widestFit);  // wide queries visit 27 cells, not thousands
    std::vector<SurfacePoint> projected(vacated_.size());
    parallelFor(int64_t(vacated_.size()), 64, [&](int64_t v) {
      const Vec3f c = before_.position[vacated_[size_t(v)]];
      const SurfacePoint plane = fitAt(c);
      if (!plane.valid) return;
      // The vacated Gaussian must have stood on the surface's front side, within reach of it,
      // and the surface must face the vacated Gaussians' centre: what an object hid faces it
      // (a fit to the underside of a cap the selection left behind faces away).
      const float height = dot(c - plane.point, plane.normal);
      if (height < -slab_ || height > reach_ || dot(centre_ - plane.point, plane.normal) <= 0) return;
      projected[size_t(v)] = {c - plane.normal * height, plane.normal, true};
    });
    return projected;
  }

  std::tuple<int64_t, int64_t, int64_t> cellOf(const Vec3f& p) const {
    auto axis = [&](float x) { return int64_t(std::floor(x / spacing_)); };
    return std::make_tuple(axis(p.x), axis(p.y), axis(p.z));
  }

  // The uncovered surface reaches past the projections: a sphere's lowest Gaussians are
  // sparse, and the floor between them, which no training view saw, may hold no Gaussian at
  // all (on builtin:spheres none within 10 cm of a sphere's contact). So every point of the
  // fitted plane within `reach` of a projection, on a lattice of the spacing, one per cell
  // (the first in vacated order: deterministic), is projected onto the plane fitted around
  // it in turn; it is a candidate where it lay within a spacing of that plane and the plane
  // faces the same way (a plane tilted by what the object left behind strays from the floor
  // within its reach), one per cell again. The coverage test keeps the uncovered ones.
  std::vector<SurfacePoint> candidatesAround(const std::vector<SurfacePoint>& projected) const {
    const int steps = int(std::ceil(settings_.fitSpacings));
    std::map<std::tuple<int64_t, int64_t, int64_t>, SurfacePoint> lattice;  // the projection's normal
    for (const SurfacePoint& c : projected) {
      if (!c.valid) continue;
      const Framef frame = Framef::fromNormal(c.normal);
      for (int a = -steps; a <= steps; ++a)
        for (int b = -steps; b <= steps; ++b) {
          if (a * a + b * b > steps * steps) continue;
          const Vec3f p = c.point + (frame.s * float(a) + frame.t * float(b)) * spacing_;
          lattice.emplace(cellOf(p), SurfacePoint{p, c.normal, false});
        }
    }
    std::vector<SurfacePoint> onSurface;
    for (const auto& [cell, c] : lattice) onSurface.push_back(c);
    parallelFor(int64_t(onSurface.size()), 16, [&](int64_t k) {
      SurfacePoint& c = onSurface[size_t(k)];
      const SurfacePoint plane = fitAt(c.point);
      // The same surface, facing the same way (an object's leftover underside faces down).
      if (!plane.valid || dot(plane.normal, c.normal) < 0.9f) return;
      const float height = dot(c.point - plane.point, plane.normal);
      if (std::abs(height) > settings_.maxResidualSpacings * spacing_) return;
      c = {c.point - plane.normal * height, plane.normal, true};
    });
    std::map<std::tuple<int64_t, int64_t, int64_t>, SurfacePoint> firstInCell;
    for (const SurfacePoint& c : onSurface)
      if (c.valid) firstInCell.emplace(cellOf(c.point), c);
    std::vector<SurfacePoint> candidates;
    for (const auto& [cell, c] : firstInCell) candidates.push_back(c);
    return candidates;
  }

  // The hole: support the vacated Gaussians hid (its trained colour is the object's shadow at
  // best) and the candidates of low coverage.
  void findHole() {
    hidden_.assign(support_.size(), 0);
    if (settings_.recolourSpacings > 0) {
      const float hiddenReach = settings_.recolourSpacings * spacing_;
      const CellGrid vacatedGrid(before_, vacated_, reach_);
      parallelFor(int64_t(support_.size()), 64, [&](int64_t k) {
        if (!touched_[size_t(k)]) return;
        vacatedGrid.near(after_.position[support_[size_t(k)]], hiddenReach, [&](uint32_t) { hidden_[size_t(k)] = 1; });
      });
    }
    fill_.assign(candidates_.size(), 0);
    parallelFor(int64_t(candidates_.size()), 16, [&](int64_t k) {
      const SurfacePoint& candidate = candidates_[size_t(k)];
      fill_[size_t(k)] = coverage(candidate.point, candidate.normal) < settings_.fillBelow * report_.ringCoverage;
    });
  }

  // Where the surface's texture repeats (a checker, tiles), the hole continues it from the one
  // offset at which the seen texture around the hole repeats (edit/texture_offset.h): each
  // point copies the seen Gaussians at the point shifted by it. Elsewhere, and where that
  // finds no source, the hole takes the ring's mean. Either way relighting lights the copy
  // where it stands (edit_effects/healed_lighting.h), not where its source stands.
  void findTexture() {
    std::vector<SurfacePoint> hole;
    for (size_t k = 0; k < support_.size(); ++k)
      if (hidden_[k]) hole.push_back({after_.position[support_[k]], normalize(after_.normal[support_[k]]), true});
    for (size_t k = 0; k < candidates_.size(); ++k)
      if (fill_[k]) hole.push_back(candidates_[k]);
    // Seen: the surface left in place, less what the vacated Gaussians hid.
    std::vector<uint8_t> isHidden(after_.size(), 0);
    for (size_t k = 0; k < support_.size(); ++k)
      if (hidden_[k]) isHidden[support_[k]] = 1;
    std::vector<uint32_t> seen;
    for (uint32_t j : nearby_)
      if (!isHidden[j]) seen.push_back(j);
    texture_ = holeTexture(after_, hole, seen, spacing_, slab_, reach_, settings_.texture);
    if (texture_.offset) {
      report_.textureOffset = texture_.offset->offset;
      report_.textureCorrelation = texture_.offset->correlation;
    }
  }

  // h's sources for a point p (normal n) of the hole: the copyFrom nearest sources to p
  // shifted by the texture's offset (within two spacings), else the continueFrom nearest
  // ring Gaussians (within eight reaches), weighted by inverse distance; false when neither
  // has one.
  bool continueHole(const Vec3f& p, const Vec3f& n, HealedGaussian& h) {
    if (texture_.offset && dot(n, texture_.normal) >= kSameSurfaceCosine &&
        nearestWeighted(after_, *sourceGrid_, p + texture_.offset->offset, 2.0f * spacing_, settings_.copyFrom,
                        spacing_, h)) {
      copied_.fetch_add(1, std::memory_order_relaxed);
      return true;
    }
    return nearestWeighted(after_, *ringGrid_, p, 8.0f * reach_, settings_.continueFrom, spacing_, h);
  }

  // The hidden support takes the continued colour (from the ring or the texture's source,
  // never from another recoloured Gaussian: order-independent).
  void recolourHidden() {
    std::vector<HealedGaussian> recoloured(support_.size());
    std::vector<uint8_t> found(support_.size(), 0);
    parallelFor(int64_t(support_.size()), 64, [&](int64_t k) {
      const uint32_t j = support_[size_t(k)];
      if (hidden_[size_t(k)] && continueHole(after_.position[j], normalize(after_.normal[j]), recoloured[size_t(k)]))
        found[size_t(k)] = 1;
    });
    for (size_t k = 0; k < support_.size(); ++k) {
      if (!found[k]) continue;
      recoloured[k].index = support_[k];
      report_.healed.push_back(std::move(recoloured[k]));
      ++report_.recoloured;
    }
    continueHealedColours(report_, after_);
  }

  // Fills the candidates of low coverage: each a copy of its nearest source's shape,
  // orientation and opacity at the candidate, with its sources' weighted colour and material.
  void fillHole() {
    std::vector<HealedGaussian> made(candidates_.size());
    parallelFor(int64_t(candidates_.size()), 16, [&](int64_t k) {
      if (fill_[size_t(k)] && !continueHole(candidates_[size_t(k)].point, candidates_[size_t(k)].normal, made[size_t(k)]))
        fill_[size_t(k)] = 0;
    });
    report_.copied = copied_;
    for (size_t k = 0; k < candidates_.size() && report_.added < settings_.maxAdded; ++k) {
      if (!fill_[k]) continue;
      HealedGaussian h = std::move(made[k]);
      const uint32_t shape = h.neighbours.front();  // the nearest
      const size_t index = after_.size();
      GaussianScene copy;
      copy.append(after_, shape);
      after_.append(copy, 0);
      after_.position[index] = candidates_[k].point;
      after_.normal[index] = candidates_[k].normal;
      Rgb diffuse(0.0f), f0(0.0f);
      float roughness = 0;
      for (size_t n = 0; n < h.neighbours.size(); ++n) {
        diffuse += after_.diffuse[h.neighbours[n]] * h.weights[n];
        f0 += after_.f0[h.neighbours[n]] * h.weights[n];
        roughness += after_.roughness[h.neighbours[n]] * h.weights[n];
      }
      after_.diffuse[index] = diffuse;
      after_.f0[index] = f0;
      after_.roughness[index] = roughness;
      provenance_.source.push_back(provenance_.source[shape]);
      provenance_.moved.push_back(1);
      h.index = uint32_t(index);
      report_.healed.push_back(std::move(h));
      ++report_.added;
    }
  }

  const GaussianScene& before_;
  GaussianScene& after_;
  EditProvenance& provenance_;
  const HealSettings& settings_;
  HealReport report_;
  std::vector<uint32_t> vacated_, nearby_, support_, ring_;
  Vec3f centre_{0.0f};
  float radius_ = 0, spacing_ = 0, reach_ = 0, slab_ = 0;
  std::vector<uint8_t> touched_, hidden_, fill_;  // per support Gaussian, per candidate
  std::vector<SurfacePoint> candidates_;
  HoleTexture texture_;
  std::atomic<size_t> copied_ = 0;
  // Built as the steps need them: over the support (a fit's reach and the widest fit), every
  // Gaussian near the hole, the ring, and the texture's sources.
  std::optional<CellGrid> supportGrid_, wideGrid_, allGrid_, ringGrid_, sourceGrid_;
};

}  // namespace

HealReport healUncovered(const GaussianScene& before, GaussianScene& after, EditProvenance& provenance,
                         const HealSettings& settings) {
  GLINT_CHECK(settings.fitSpacings > 0 && settings.minSupport >= 1 && settings.continueFrom >= 1,
              "healUncovered: bad settings");
  GLINT_CHECK(provenance.source.size() == after.size() && provenance.countBefore == before.size(),
              "healUncovered: provenance does not match the scenes");
  return Healing(before, after, provenance, settings).run();
}

void continueHealedColours(const HealReport& report, GaussianScene& scene) {
  for (const HealedGaussian& h : report.healed) {
    Rgb diffuse(0.0f);
    for (size_t n = 0; n < h.neighbours.size(); ++n) diffuse += scene.diffuse[h.neighbours[n]] * h.weights[n];
    scene.diffuse[h.index] = diffuse;
  }
}

}  // namespace glint
