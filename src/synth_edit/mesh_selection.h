// Evaluates the named selections of an edit document on a ground-truth mesh scene: edits
// select whole nodes (each triangle mesh and each sphere), by the centre of the node's
// world bounds, and filter them by their material's factors (textures ignored).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "edit/edit_document.h"
#include "synth/mesh_scene.h"

namespace glint {

// Nodes are numbered meshes first, then spheres: node i < meshes.size() is mesh i, the
// others are sphere i - meshes.size().
size_t nodeCount(const MeshScene& scene);
bool isSphereNode(const MeshScene& scene, size_t node);
// The centre of the node's world bounds (a sphere's centre; a mesh's vertex-bounds centre).
Vec3f nodeCenter(const MeshScene& scene, size_t node);
int nodeMaterial(const MeshScene& scene, size_t node);
void setNodeMaterial(MeshScene& scene, size_t node, int material);

// One byte per node (1 = selected).
using NodeMask = std::vector<uint8_t>;

// The nodes of `scene` that selection `name` of `document` holds. The document must be
// valid (parseEditDocument): names resolve and combinations have no cycles.
NodeMask selectNodes(const EditDocument& document, const std::string& name, const MeshScene& scene);

// True when the material's factors pass the filter (mean F0, roughness, mean diffuse or the
// derived metalness within [lo, hi]), from the same mapping as MeshScene::surfaceMaterial.
bool materialPassesFilter(const AttributeFilter& filter, const Material& material);

}  // namespace glint
