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

}  // namespace

HealReport healUncovered(const GaussianScene& before, GaussianScene& after, EditProvenance& provenance,
                         const HealSettings& settings) {
  HealReport report;
  GLINT_CHECK(settings.fitSpacings > 0 && settings.minSupport >= 1 && settings.continueFrom >= 1,
              "healUncovered: bad settings");
  GLINT_CHECK(provenance.source.size() == after.size() && provenance.countBefore == before.size(),
              "healUncovered: provenance does not match the scenes");

  // Vacated: moved or removed, and not kept where it was by any Gaussian after the edit.
  std::vector<uint8_t> keptInPlace(before.size(), 0);
  for (size_t j = 0; j < after.size(); ++j) {
    const uint32_t i = provenance.source[j];
    if (provenance.moved[j] && after.position[j] == before.position[i] && after.logScale[j] == before.logScale[i])
      keptInPlace[i] = 1;
  }
  std::vector<uint32_t> vacated;
  for (uint32_t i : provenance.movedOrRemoved())
    if (!keptInPlace[i]) vacated.push_back(i);
  report.vacated = vacated.size();
  if (vacated.empty()) return report;

  // A sphere around the vacated means.
  Vec3d sum(0.0);
  for (uint32_t i : vacated) sum += Vec3d(before.position[i]);
  const Vec3f centre(sum * (1.0 / double(vacated.size())));
  float radius = 0;
  for (uint32_t i : vacated) radius = std::max(radius, length(before.position[i] - centre));

  // Support candidates: unmoved, opaque enough, with a normal, near the sphere. Their spacing
  // sets every length below; the ring around the sphere is as wide as a plane fit reaches.
  std::vector<uint32_t> nearby;
  for (size_t j = 0; j < after.size(); ++j)
    if (!provenance.moved[j] && after.opacity(j) >= settings.minSupportOpacity &&
        length(after.normal[j]) >= settings.minNormalLength)
      nearby.push_back(uint32_t(j));
  std::vector<float> spreads;
  for (uint32_t j : nearby)
    if (length(after.position[j] - centre) <= 1.5f * radius) spreads.push_back(inPlaneSpread(after, j));
  const float spacing = percentileOf(spreads, 0.5);
  if (!(spacing > 0)) return report;
  report.spacing = spacing;
  const float reach = settings.fitSpacings * spacing;
  std::vector<uint32_t> support;
  for (uint32_t j : nearby)
    if (length(after.position[j] - centre) <= radius + 2.0f * reach) support.push_back(j);
  report.support = support.size();
  if (support.size() < size_t(settings.minSupport)) return report;
  const CellGrid supportGrid(after, support, reach);

  // The ring: support no vacated Gaussian came within reach of (what the training views saw).
  std::vector<uint8_t> touched(support.size(), 0);
  {
    std::unordered_map<uint32_t, size_t> slot;
    for (size_t k = 0; k < support.size(); ++k) slot[support[k]] = k;
    std::vector<std::vector<uint32_t>> touchedBy(vacated.size());
    parallelFor(int64_t(vacated.size()), 64, [&](int64_t v) {
      supportGrid.near(before.position[vacated[size_t(v)]], reach,
                       [&](uint32_t j) { touchedBy[size_t(v)].push_back(j); });
    });
    for (const auto& list : touchedBy)
      for (uint32_t j : list) touched[slot[j]] = 1;
  }
  std::vector<uint32_t> ring;
  for (size_t k = 0; k < support.size(); ++k)
    if (!touched[k]) ring.push_back(support[k]);
  if (ring.empty()) return report;

  // Coverage of a surface point: the opacity collected along its normal from the Gaussians
  // (every one after the edit, moved ones included) near the surface there.
  std::vector<uint32_t> all;
  for (size_t j = 0; j < after.size(); ++j)
    if (length(after.position[j] - centre) <= radius + 3.0f * reach) all.push_back(uint32_t(j));
  const CellGrid allGrid(after, all, reach);
  const float slab = settings.coverageSlabSpacings * spacing;
  auto coverage = [&](const Vec3f& p, const Vec3f& n) {
    float transmittance = 1;
    allGrid.near(p, reach, [&](uint32_t j) {
      float t = 0;
      float alpha = rayAlpha(after, j, p, n, &t);
      if (std::abs(t) <= slab) transmittance *= 1.0f - std::min(alpha, 0.999f);
    });
    return 1.0f - transmittance;
  };
  std::vector<float> ringCoverages(ring.size());
  parallelFor(int64_t(ring.size()), 64, [&](int64_t k) {
    const uint32_t j = ring[size_t(k)];
    ringCoverages[size_t(k)] = coverage(after.position[j], normalize(after.normal[j]));
  });
  report.ringCoverage = percentileOf(ringCoverages, 0.5);

  // Surface points under the vacated Gaussians: each projected onto the plane fitted to the
  // support within reach (weights: opacity times a smooth fall-off with distance).
  // A vacated Gaussian amid a wide hole (a disc of floor that the selection took along with
  // the object) has no support within reach: its fit widens, doubling up to widestFitSpacings.
  const float widestFit = std::max(settings.widestFitSpacings, settings.fitSpacings) * spacing;
  const CellGrid wideGrid(after, support, widestFit);  // wide queries visit 27 cells, not thousands
  // The plane fitted to the support around c; invalid where too little support lies within
  // the widest fit, or it strays from a plane.
  auto fitAt = [&](const Vec3f& c) {
    double weightSum = 0;
    Vec3d pointSum(0.0), normalSum(0.0);
    int count = 0;
    float fit = reach;
    auto grid = [&]() -> const CellGrid& { return fit > reach ? wideGrid : supportGrid; };
    for (;; fit *= 2) {
      weightSum = 0, pointSum = normalSum = Vec3d(0.0), count = 0;
      grid().near(c, fit, [&](uint32_t j) {
        const float q = 1.0f - dot(after.position[j] - c, after.position[j] - c) / (fit * fit);
        const double w = double(after.opacity(j)) * double(q * q);
        weightSum += w;
        pointSum += Vec3d(after.position[j]) * w;
        normalSum += Vec3d(normalize(after.normal[j])) * w;
        ++count;
      });
      if (count >= settings.minSupport || fit * 2 > widestFit) break;
    }
    if (count < settings.minSupport || !(weightSum > 0) || !(length(normalSum) > 0.5 * weightSum)) return SurfacePoint{};
    SurfacePoint plane{Vec3f(pointSum * (1.0 / weightSum)), Vec3f(normalize(normalSum)), true};
    double residual = 0;
    grid().near(c, fit, [&](uint32_t j) {
      const float q = 1.0f - dot(after.position[j] - c, after.position[j] - c) / (fit * fit);
      const double h = dot(after.position[j] - plane.point, plane.normal);
      residual += double(after.opacity(j)) * double(q * q) * h * h;
    });
    if (std::sqrt(residual / weightSum) > settings.maxResidualSpacings * spacing) return SurfacePoint{};
    return plane;
  };
  std::vector<SurfacePoint> projected(vacated.size());
  parallelFor(int64_t(vacated.size()), 64, [&](int64_t v) {
    const Vec3f c = before.position[vacated[size_t(v)]];
    const SurfacePoint plane = fitAt(c);
    if (!plane.valid) return;
    // The vacated Gaussian must have stood on the surface's front side, within reach of it,
    // and the surface must face the vacated Gaussians' centre: what an object hid faces it
    // (a fit to the underside of a cap the selection left behind faces away).
    const float height = dot(c - plane.point, plane.normal);
    if (height < -slab || height > reach || dot(centre - plane.point, plane.normal) <= 0) return;
    projected[size_t(v)] = {c - plane.normal * height, plane.normal, true};
  });

  // The uncovered surface reaches past the projections: a sphere's lowest Gaussians are
  // sparse, and the floor between them, which no training view saw, may hold no Gaussian at
  // all (on builtin:spheres none within 10 cm of a sphere's contact). So every point of the
  // fitted plane within `reach` of a projection, on a lattice of the spacing, one per cell
  // (the first in vacated order: deterministic), is projected onto the plane fitted around
  // it in turn; it is a candidate where it lay within a spacing of that plane and the plane
  // faces the same way (a plane tilted by what the object left behind strays from the floor
  // within its reach), one per cell again. The coverage test below keeps the uncovered ones.
  const int steps = int(std::ceil(settings.fitSpacings));
  auto cellOf = [&](const Vec3f& p) {
    auto axis = [&](float x) { return int64_t(std::floor(x / spacing)); };
    return std::make_tuple(axis(p.x), axis(p.y), axis(p.z));
  };
  std::map<std::tuple<int64_t, int64_t, int64_t>, SurfacePoint> lattice;  // the projection's normal
  for (const SurfacePoint& c : projected) {
    if (!c.valid) continue;
    const Framef frame = Framef::fromNormal(c.normal);
    for (int a = -steps; a <= steps; ++a)
      for (int b = -steps; b <= steps; ++b) {
        if (a * a + b * b > steps * steps) continue;
        const Vec3f p = c.point + (frame.s * float(a) + frame.t * float(b)) * spacing;
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
    if (std::abs(height) > settings.maxResidualSpacings * spacing) return;
    c = {c.point - plane.normal * height, plane.normal, true};
  });
  std::map<std::tuple<int64_t, int64_t, int64_t>, SurfacePoint> firstInCell;
  for (const SurfacePoint& c : onSurface)
    if (c.valid) firstInCell.emplace(cellOf(c.point), c);
  std::vector<SurfacePoint> candidates;
  for (const auto& [cell, c] : firstInCell) candidates.push_back(c);
  report.candidates = candidates.size();

  // The nearest ring Gaussians to p within eight reaches (by distance, then index), weighted
  // by inverse distance; false when there are none.
  const CellGrid ringGrid(after, ring, 8.0f * reach);
  auto continueRing = [&](const Vec3f& p, HealedGaussian& h) {
    return nearestWeighted(after, ringGrid, p, 8.0f * reach, settings.continueFrom, spacing, h);
  };

  // The hole: support the vacated Gaussians hid (its trained colour is the object's shadow at
  // best) and the candidates of low coverage.
  std::vector<uint8_t> hidden(support.size(), 0);
  if (settings.recolourSpacings > 0) {
    const float hiddenReach = settings.recolourSpacings * spacing;
    const CellGrid vacatedGrid(before, vacated, reach);
    parallelFor(int64_t(support.size()), 64, [&](int64_t k) {
      if (!touched[size_t(k)]) return;
      vacatedGrid.near(after.position[support[size_t(k)]], hiddenReach, [&](uint32_t) { hidden[size_t(k)] = 1; });
    });
  }
  std::vector<uint8_t> fill(candidates.size(), 0);
  parallelFor(int64_t(candidates.size()), 16, [&](int64_t k) {
    const SurfacePoint& candidate = candidates[size_t(k)];
    fill[size_t(k)] = coverage(candidate.point, candidate.normal) < settings.fillBelow * report.ringCoverage;
  });

  // Where the surface's texture repeats (a checker, tiles), the hole continues it from the one
  // offset at which the seen texture around the hole repeats (edit/texture_offset.h): each
  // point copies the seen Gaussians at the point shifted by it. Elsewhere, and where that
  // finds no source, the hole takes the ring's mean. Either way relighting lights the copy
  // where it stands (edit_effects/healed_lighting.h), not where its source stands.
  HoleTexture texture;
  if (settings.continueTexture) {
    std::vector<SurfacePoint> hole;
    for (size_t k = 0; k < support.size(); ++k)
      if (hidden[k]) hole.push_back({after.position[support[k]], normalize(after.normal[support[k]]), true});
    for (size_t k = 0; k < candidates.size(); ++k)
      if (fill[k]) hole.push_back(candidates[k]);
    // Seen: the surface left in place, less what the vacated Gaussians hid.
    std::vector<uint8_t> isHidden(after.size(), 0);
    for (size_t k = 0; k < support.size(); ++k)
      if (hidden[k]) isHidden[support[k]] = 1;
    std::vector<uint32_t> seen;
    for (uint32_t j : nearby)
      if (!isHidden[j]) seen.push_back(j);
    texture = holeTexture(after, hole, seen, spacing, slab, reach, settings.texture);
    if (texture.offset) {
      report.textureOffset = texture.offset->offset;
      report.textureCorrelation = texture.offset->correlation;
    }
  }
  const float copyReach = 2.0f * spacing;
  const CellGrid sourceGrid(after, texture.sources, copyReach);
  // The copyFrom nearest sources to p shifted by the texture's offset (within copyReach),
  // weighted by inverse distance; false without an offset or a source there.
  auto copyTexture = [&](const Vec3f& p, const Vec3f& n, HealedGaussian& h) {
    if (!texture.offset || dot(n, texture.normal) < kSameSurfaceCosine) return false;
    return nearestWeighted(after, sourceGrid, p + texture.offset->offset, copyReach, settings.copyFrom, spacing, h);
  };
  std::atomic<size_t> copied = 0;
  auto continueHole = [&](const Vec3f& p, const Vec3f& n, HealedGaussian& h) {
    if (copyTexture(p, n, h)) {
      copied.fetch_add(1, std::memory_order_relaxed);
      return true;
    }
    return continueRing(p, h);
  };

  // The hidden support takes the continued colour (from the ring or the texture's source,
  // never from another recoloured Gaussian: order-independent).
  {
    std::vector<HealedGaussian> recoloured(support.size());
    std::vector<uint8_t> found(support.size(), 0);
    parallelFor(int64_t(support.size()), 64, [&](int64_t k) {
      const uint32_t j = support[size_t(k)];
      if (hidden[size_t(k)] && continueHole(after.position[j], normalize(after.normal[j]), recoloured[size_t(k)]))
        found[size_t(k)] = 1;
    });
    for (size_t k = 0; k < support.size(); ++k) {
      if (!found[k]) continue;
      recoloured[k].index = support[k];
      report.healed.push_back(std::move(recoloured[k]));
      ++report.recoloured;
    }
    continueHealedColours(report, after);
  }

  // Fill the candidates of low coverage.
  std::vector<HealedGaussian> made(candidates.size());
  parallelFor(int64_t(candidates.size()), 16, [&](int64_t k) {
    if (fill[size_t(k)] && !continueHole(candidates[size_t(k)].point, candidates[size_t(k)].normal, made[size_t(k)]))
      fill[size_t(k)] = 0;
  });
  report.copied = copied;

  for (size_t k = 0; k < candidates.size() && report.added < settings.maxAdded; ++k) {
    if (!fill[k]) continue;
    const SurfacePoint& candidate = candidates[k];
    HealedGaussian h = std::move(made[k]);
    const uint32_t shape = h.neighbours.front();  // the nearest
    const size_t index = after.size();
    GaussianScene copy;  // shape, orientation and opacity of the nearest ring Gaussian
    copy.append(after, shape);
    after.append(copy, 0);
    after.position[index] = candidate.point;
    after.normal[index] = candidate.normal;
    Rgb diffuse(0.0f), f0(0.0f);
    float roughness = 0;
    for (size_t n = 0; n < h.neighbours.size(); ++n) {
      diffuse += after.diffuse[h.neighbours[n]] * h.weights[n];
      f0 += after.f0[h.neighbours[n]] * h.weights[n];
      roughness += after.roughness[h.neighbours[n]] * h.weights[n];
    }
    after.diffuse[index] = diffuse;
    after.f0[index] = f0;
    after.roughness[index] = roughness;
    provenance.source.push_back(provenance.source[shape]);
    provenance.moved.push_back(1);
    h.index = uint32_t(index);
    report.healed.push_back(std::move(h));
    ++report.added;
  }
  return report;
}

void continueHealedColours(const HealReport& report, GaussianScene& scene) {
  for (const HealedGaussian& h : report.healed) {
    Rgb diffuse(0.0f);
    for (size_t n = 0; n < h.neighbours.size(); ++n) diffuse += scene.diffuse[h.neighbours[n]] * h.weights[n];
    scene.diffuse[h.index] = diffuse;
  }
}

}  // namespace glint
