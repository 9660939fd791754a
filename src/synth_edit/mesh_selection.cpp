// Selections over mesh-scene nodes: a handful of nodes, so plain loops suffice.
#include "synth_edit/mesh_selection.h"

#include <limits>

#include "core/error.h"
#include "edit/selection_plan.h"
#include "edit/shape.h"

namespace glint {

namespace {

// One selection's mask from its operands' masks, then its filters.
NodeMask evaluateNodes(const Selection& selection, const std::vector<const NodeMask*>& operands,
                       const MeshScene& scene) {
  size_t n = nodeCount(scene);
  NodeMask mask(n, 0);
  for (size_t i = 0; i < n; ++i) {
    switch (selection.kind) {
      case Selection::Kind::Everything: mask[i] = 1; break;
      case Selection::Kind::Shape: mask[i] = shapeContains(selection.shape, nodeCenter(scene, i)); break;
      case Selection::Kind::Union:
      case Selection::Kind::Intersection:
      case Selection::Kind::Difference: {
        bool inFirst = (*operands.at(0))[i], inAny = false, inAll = true;
        for (size_t k = 1; k < operands.size(); ++k) inAny |= bool((*operands[k])[i]), inAll &= bool((*operands[k])[i]);
        if (selection.kind == Selection::Kind::Union) mask[i] = inFirst || inAny;
        else if (selection.kind == Selection::Kind::Intersection) mask[i] = inFirst && inAll;
        else mask[i] = inFirst && !inAny;  // Difference: the first minus all the others
        break;
      }
    }
    for (const AttributeFilter& filter : selection.filters)
      if (mask[i] && !materialPassesFilter(filter, scene.materials[nodeMaterial(scene, i)])) mask[i] = 0;
  }
  return mask;
}

}  // namespace

size_t nodeCount(const MeshScene& scene) { return scene.meshes.size() + scene.spheres.size(); }

bool isSphereNode(const MeshScene& scene, size_t node) { return node >= scene.meshes.size(); }

Vec3f nodeCenter(const MeshScene& scene, size_t node) {
  if (isSphereNode(scene, node)) return scene.spheres[node - scene.meshes.size()].center;
  const TriangleMesh& mesh = scene.meshes[node];
  // A mesh without vertices lies nowhere: no shape holds an infinite point.
  if (mesh.positions.empty()) return Vec3f(std::numeric_limits<float>::infinity());
  Vec3f lower = mesh.positions[0], upper = mesh.positions[0];
  for (const Vec3f& p : mesh.positions) lower = min(lower, p), upper = max(upper, p);
  return (lower + upper) * 0.5f;
}

int nodeMaterial(const MeshScene& scene, size_t node) {
  return isSphereNode(scene, node) ? scene.spheres[node - scene.meshes.size()].material : scene.meshes[node].material;
}

void setNodeMaterial(MeshScene& scene, size_t node, int material) {
  if (isSphereNode(scene, node)) scene.spheres[node - scene.meshes.size()].material = material;
  else scene.meshes[node].material = material;
}

bool materialPassesFilter(const AttributeFilter& filter, const Material& material) {
  SurfaceMaterial factors = materialFactors(material);
  return filterAccepts(filter, factors.F0, factors.roughness, factors.diffuse);
}

NodeMask selectNodes(const EditDocument& document, const std::string& name, const MeshScene& scene) {
  return evaluatePlan<NodeMask>(planSelection(document, name),
                                [&](const Selection& selection, const std::vector<const NodeMask*>& operands) {
                                  return evaluateNodes(selection, operands, scene);
                                });
}

}  // namespace glint
