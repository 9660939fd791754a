// Each operation moves whole nodes (every vertex and normal of a mesh, a sphere's centre and
// radius), copies or removes them, or changes the factors of their materials.
#include "synth_edit/mesh_edits.h"

#include <numbers>

#include "edit/edit_file.h"
#include "edit/value_changes.h"
#include "synth_edit/material_colors.h"

namespace glint {

namespace {

// Calls move(point) for every position of the selected nodes (vertices, sphere centres).
template <typename Move>
void moveSelectedPoints(const NodeMask& mask, MeshScene& scene, Move&& move) {
  for (size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    if (isSphereNode(scene, i)) {
      Sphere& sphere = scene.spheres[i - scene.meshes.size()];
      sphere.center = move(sphere.center);
    } else {
      for (Vec3f& p : scene.meshes[i].positions) p = move(p);
    }
  }
}

void rotateNodes(const EditDocument& document, const Operation& op, const NodeMask& mask, MeshScene& scene) {
  Mat3f rotation = quatToRotation(quatFromAxisAngle(op.axis, op.angleDegrees * std::numbers::pi_v<float> / 180.0f));
  Vec3f pivot = operationPivot(document, op);
  moveSelectedPoints(mask, scene, [&](const Vec3f& p) { return pivot + rotation * (p - pivot); });
  for (size_t i = 0; i < scene.meshes.size(); ++i)
    if (mask[i])
      for (Vec3f& n : scene.meshes[i].normals) n = rotation * n;
}

// Uniform scaling keeps normals; spheres grow with their centres' distances.
void scaleNodes(const EditDocument& document, const Operation& op, const NodeMask& mask, MeshScene& scene) {
  Vec3f pivot = operationPivot(document, op);
  moveSelectedPoints(mask, scene, [&](const Vec3f& p) { return pivot + (p - pivot) * op.factor; });
  for (size_t i = scene.meshes.size(); i < mask.size(); ++i)
    if (mask[i]) scene.spheres[i - scene.meshes.size()].radius *= op.factor;
}

// Copies are appended after every existing node of their kind, sharing the material.
void duplicateNodes(const Operation& op, const NodeMask& mask, MeshScene& scene) {
  std::vector<TriangleMesh> meshCopies;
  std::vector<Sphere> sphereCopies;
  for (size_t i = 0; i < mask.size(); ++i) {
    if (!mask[i]) continue;
    if (isSphereNode(scene, i)) {
      Sphere copy = scene.spheres[i - scene.meshes.size()];
      copy.center += op.offset;
      sphereCopies.push_back(copy);
    } else {
      TriangleMesh copy = scene.meshes[i];
      for (Vec3f& p : copy.positions) p += op.offset;
      meshCopies.push_back(std::move(copy));
    }
  }
  scene.meshes.insert(scene.meshes.end(), meshCopies.begin(), meshCopies.end());
  scene.spheres.insert(scene.spheres.end(), sphereCopies.begin(), sphereCopies.end());
}

void deleteNodes(const NodeMask& mask, MeshScene& scene) {
  std::vector<TriangleMesh> meshes;
  std::vector<Sphere> spheres;
  for (size_t i = 0; i < mask.size(); ++i) {
    if (mask[i]) continue;
    if (isSphereNode(scene, i)) spheres.push_back(scene.spheres[i - scene.meshes.size()]);
    else meshes.push_back(std::move(scene.meshes[i]));
  }
  scene.meshes = std::move(meshes);
  scene.spheres = std::move(spheres);
}

// The materials the selected nodes use, each once, after giving the selected nodes their own
// copy of every material they share with unselected nodes.
std::vector<int> ownMaterials(const NodeMask& mask, MeshScene& scene) {
  size_t materialCount = scene.materials.size();
  std::vector<uint8_t> usedBySelected(materialCount, 0), usedByOthers(materialCount, 0);
  for (size_t i = 0; i < mask.size(); ++i) (mask[i] ? usedBySelected : usedByOthers)[nodeMaterial(scene, i)] = 1;
  std::vector<int> owned;
  std::vector<int> copyOf(materialCount, -1);
  for (size_t m = 0; m < materialCount; ++m) {
    if (!usedBySelected[m]) continue;
    if (usedByOthers[m]) {
      Material copy = scene.materials[m];
      copy.name += " (edited)";
      scene.materials.push_back(copy);
      copyOf[m] = int(scene.materials.size()) - 1;
      owned.push_back(copyOf[m]);
    } else {
      owned.push_back(int(m));
    }
  }
  for (size_t i = 0; i < mask.size(); ++i)
    if (mask[i] && copyOf[nodeMaterial(scene, i)] >= 0) setNodeMaterial(scene, i, copyOf[nodeMaterial(scene, i)]);
  return owned;
}

// Changes a material's factors: roughness directly; F0 or diffuse through the
// metallic-roughness mapping, keeping the other colour (synth_edit/material_colors.h).
void changeMaterial(const Operation& op, Material& material) {
  SurfaceMaterial factors = materialFactors(material);
  switch (op.kind) {
    case Operation::Kind::Roughness: material.roughness = changeRoughness(factors.roughness, op); break;
    case Operation::Kind::F0:
      setDiffuseAndF0(material, factors.diffuse, clampF0(changeColor(factors.F0, op.color)));
      break;
    case Operation::Kind::Diffuse:
      setDiffuseAndF0(material, clampDiffuse(changeColor(factors.diffuse, op.color)), factors.F0);
      break;
    default: break;
  }
}

}  // namespace

void applyMeshOperation(const EditDocument& document, const Operation& op, const NodeMask& mask, MeshScene& scene) {
  switch (op.kind) {
    case Operation::Kind::Translate:
      moveSelectedPoints(mask, scene, [&](const Vec3f& p) { return p + op.offset; });
      break;
    case Operation::Kind::Rotate: rotateNodes(document, op, mask, scene); break;
    case Operation::Kind::Scale: scaleNodes(document, op, mask, scene); break;
    case Operation::Kind::Duplicate: duplicateNodes(op, mask, scene); break;
    case Operation::Kind::Delete: deleteNodes(mask, scene); break;
    case Operation::Kind::Roughness:
    case Operation::Kind::F0:
    case Operation::Kind::Diffuse:
      for (int m : ownMaterials(mask, scene)) changeMaterial(op, scene.materials[m]);
      break;
  }
}

MeshEditReport applyMeshEdits(const EditDocument& document, MeshScene& scene) {
  MeshEditReport report;
  report.nodesBefore = nodeCount(scene);
  report.materialsBefore = scene.materials.size();
  for (size_t k = 0; k < document.operations.size(); ++k) {
    const Operation& op = document.operations[k];
    NodeMask mask = selectNodes(document, op.selection, scene);
    MeshOperationReport entry;
    entry.description = "operations[" + std::to_string(k) + "] " + operationName(op.kind) + " \"" + op.selection + "\"";
    for (uint8_t m : mask) entry.selected += m;
    if (entry.selected == 0) report.warnings.push_back(entry.description + ": the selection holds no mesh or sphere");
    applyMeshOperation(document, op, mask, scene);
    report.operations.push_back(entry);
  }
  report.nodesAfter = nodeCount(scene);
  report.materialsAfter = scene.materials.size();
  return report;
}

std::string formatMeshEditReport(const MeshEditReport& report) {
  std::string text;
  for (const MeshOperationReport& op : report.operations)
    text += op.description + ": " + std::to_string(op.selected) + (op.selected == 1 ? " node\n" : " nodes\n");
  for (const std::string& warning : report.warnings) text += "warning: " + warning + "\n";
  text += "nodes (meshes and spheres): " + std::to_string(report.nodesBefore) + " -> " +
          std::to_string(report.nodesAfter) + "; materials: " + std::to_string(report.materialsBefore) + " -> " +
          std::to_string(report.materialsAfter) + "\n";
  return text;
}

}  // namespace glint
