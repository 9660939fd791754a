// Each operation changes the selected Gaussians' parameters in place (in parallel), or their
// number (duplicate, delete). Geometry edits move the whole Gaussian: its mean, its
// orientation and its attached normal, so the shading of a moved object moves with it.
#include "edit/gaussian_edits.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/parallel.h"
#include "edit/edit_file.h"
#include "edit/gaussian_selection.h"
#include "edit/value_changes.h"

namespace glint {

namespace {

constexpr int64_t kGrain = 4096;

// Calls change(i) for every selected Gaussian.
template <typename Change>
void forSelected(const GaussianMask& mask, Change&& change) {
  parallelFor(int64_t(mask.size()), kGrain, [&](int64_t i) {
    if (mask[i]) change(size_t(i));
  });
}

// A translation by zero, a rotation by no angle or a scaling by one leaves every Gaussian
// where it was: it is not applied (so they stay bit for bit as they were, not an ulp off
// after a turn about the pivot and back) and moves nothing in the provenance, so relighting
// traces no ray for it.
bool movesNothing(const Operation& op) {
  switch (op.kind) {
    case Operation::Kind::Translate: return op.offset == Vec3f(0.0f);
    case Operation::Kind::Rotate: return op.angleDegrees == 0.0f;
    case Operation::Kind::Scale: return op.factor == 1.0f;
    default: return false;
  }
}

}  // namespace

void applyOperation(const EditDocument& document, const Operation& op, const GaussianMask& mask,
                    GaussianScene& scene) {
  if (movesNothing(op)) return;
  switch (op.kind) {
    case Operation::Kind::Translate:
      forSelected(mask, [&](size_t i) { scene.position[i] += op.offset; });
      break;
    case Operation::Kind::Rotate: {
      // The rotation r turns means about the pivot, and composes with each orientation
      // (q' = r q: first the Gaussian's own rotation, then the edit's).
      Quatf r = quatFromAxisAngle(op.axis, op.angleDegrees * std::numbers::pi_v<float> / 180.0f);
      Mat3f rotation = quatToRotation(r);
      Vec3f pivot = operationPivot(document, op);
      forSelected(mask, [&](size_t i) {
        scene.position[i] = pivot + rotation * (scene.position[i] - pivot);
        scene.rotation[i] = r * scene.rotation[i];
        scene.normal[i] = rotation * scene.normal[i];
      });
      break;
    }
    case Operation::Kind::Scale: {
      Vec3f pivot = operationPivot(document, op);
      float logFactor = std::log(op.factor);
      forSelected(mask, [&](size_t i) {
        scene.position[i] = pivot + (scene.position[i] - pivot) * op.factor;
        scene.logScale[i] += Vec3f(logFactor);
      });
      break;
    }
    case Operation::Kind::Duplicate: {
      size_t n = scene.size();
      for (size_t i = 0; i < n; ++i) {
        if (!mask[i]) continue;
        scene.append(scene, i);
        scene.position.back() += op.offset;
      }
      break;
    }
    case Operation::Kind::Delete: {
      std::vector<bool> keep(mask.size());
      for (size_t i = 0; i < mask.size(); ++i) keep[i] = !mask[i];
      scene.filter(keep);
      break;
    }
    case Operation::Kind::Roughness:
      forSelected(mask, [&](size_t i) { scene.roughness[i] = changeRoughness(scene.roughness[i], op); });
      break;
    case Operation::Kind::F0:
      forSelected(mask, [&](size_t i) {
        scene.f0[i] = clampF0(changeColor(scene.f0[i], op.color));
      });
      break;
    case Operation::Kind::Diffuse:
      forSelected(mask, [&](size_t i) { scene.diffuse[i] = clampDiffuse(changeColor(scene.diffuse[i], op.color)); });
      break;
  }
}

EditProvenance EditProvenance::identity(size_t n) {
  EditProvenance p;
  p.countBefore = n;
  p.source.resize(n);
  for (size_t i = 0; i < n; ++i) p.source[i] = uint32_t(i);
  p.moved.assign(n, 0);
  return p;
}

std::vector<uint32_t> EditProvenance::unmoved() const {
  std::vector<uint32_t> indices;
  for (size_t i = 0; i < moved.size(); ++i)
    if (!moved[i]) indices.push_back(uint32_t(i));
  return indices;
}

std::vector<uint32_t> EditProvenance::movedOrAdded() const {
  std::vector<uint32_t> indices;
  for (size_t i = 0; i < moved.size(); ++i)
    if (moved[i]) indices.push_back(uint32_t(i));
  return indices;
}

std::vector<uint32_t> EditProvenance::movedOrRemoved() const {
  // A Gaussian before stays in place when some Gaussian after is it, unmoved (a copy is
  // always marked moved, so copies never count).
  std::vector<uint8_t> inPlace(countBefore, 0);
  for (size_t i = 0; i < source.size(); ++i)
    if (!moved[i]) inPlace[source[i]] = 1;
  std::vector<uint32_t> indices;
  for (size_t i = 0; i < countBefore; ++i)
    if (!inPlace[i]) indices.push_back(uint32_t(i));
  return indices;
}

namespace {

// What one operation does to the provenance record (run after the operation itself).
void recordOperation(const Operation& op, const GaussianMask& mask, EditProvenance& p) {
  switch (op.kind) {
    case Operation::Kind::Translate:
    case Operation::Kind::Rotate:
    case Operation::Kind::Scale:
      if (movesNothing(op)) break;
      for (size_t i = 0; i < mask.size(); ++i) p.moved[i] = p.moved[i] || mask[i];
      break;
    case Operation::Kind::Duplicate:
      for (size_t i = 0; i < mask.size(); ++i)
        if (mask[i]) p.source.push_back(p.source[i]), p.moved.push_back(1);
      break;
    case Operation::Kind::Delete: {
      size_t kept = 0;
      for (size_t i = 0; i < mask.size(); ++i)
        if (!mask[i]) p.source[kept] = p.source[i], p.moved[kept] = p.moved[i], ++kept;
      p.source.resize(kept);
      p.moved.resize(kept);
      break;
    }
    case Operation::Kind::Roughness:
    case Operation::Kind::F0:
    case Operation::Kind::Diffuse:
      break;  // materials: the geometry that shadows stays
  }
}

}  // namespace

EditReport applyEdits(const EditDocument& document, GaussianScene& scene, size_t maxGaussians,
                      EditProvenance* provenance) {
  GLINT_CHECK(!provenance || provenance->source.size() == scene.size(), "applyEdits: provenance of another scene");
  EditReport report;
  report.countBefore = scene.size();
  for (size_t k = 0; k < document.operations.size(); ++k) {
    const Operation& op = document.operations[k];
    GaussianMask mask = selectGaussians(document, op.selection, scene);
    OperationReport entry;
    entry.description =
        "operations[" + std::to_string(k) + "] " + operationName(op.kind) + " \"" + op.selection + "\"";
    entry.selected = countSelected(mask);
    if (entry.selected == 0) report.warnings.push_back(entry.description + ": the selection holds no Gaussians");
    // Duplication doubles a selection that holds its own copies: 40 of them in a 3 kB file
    // would ask for 2^40 Gaussians. The count is known before anything is allocated.
    size_t added = op.kind == Operation::Kind::Duplicate ? entry.selected : 0;
    if (added > 0 && scene.size() + added > maxGaussians)
      throw GaussianLimitError(document.source.empty() ? "edits" : document.source,
                               entry.description + " would make " + std::to_string(scene.size() + added) +
                                   " Gaussians, more than the limit of " + std::to_string(maxGaussians) +
                                   " (--max-gaussians)");
    applyOperation(document, op, mask, scene);
    if (provenance) recordOperation(op, mask, *provenance);
    report.operations.push_back(entry);
  }
  report.countAfter = scene.size();
  return report;
}

std::string formatEditReport(const EditReport& report) {
  std::string text;
  for (const OperationReport& op : report.operations)
    text += op.description + ": " + std::to_string(op.selected) + " Gaussians\n";
  for (const std::string& warning : report.warnings) text += "warning: " + warning + "\n";
  text += "Gaussians: " + std::to_string(report.countBefore) + " -> " + std::to_string(report.countAfter) +
          (report.countChanged() ? "" : " (unchanged)") + "\n";
  return text;
}

}  // namespace glint
