// Applies an edit document to a ground-truth mesh scene (`glint synth --edits`), so the
// true edited scene can be rendered and compared with the edited Gaussian scene.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "edit/edit_document.h"
#include "synth/mesh_scene.h"
#include "synth_edit/mesh_selection.h"

namespace glint {

struct MeshOperationReport {
  std::string description;  // e.g. `operations[1] rotate "chrome"`
  size_t selected = 0;      // nodes the selection held when the operation ran
};

struct MeshEditReport {
  std::vector<MeshOperationReport> operations;
  std::vector<std::string> warnings;  // selections that held no node
  size_t nodesBefore = 0, nodesAfter = 0;
  size_t materialsBefore = 0, materialsAfter = 0;  // grows when shared materials are split
};

// Applies the operations in order; each selection is evaluated on the scene as the
// operations before it left it. The document must be valid (parseEditDocument).
// Geometry: vertices and shading normals of meshes, centres and radii of spheres.
// Materials: a material the selection shares with unselected nodes is first copied for
// the selected ones (once per operation), so an edit never leaks to other nodes.
MeshEditReport applyMeshEdits(const EditDocument& document, MeshScene& scene);

// Applies one operation to the nodes whose mask entry is set.
void applyMeshOperation(const EditDocument& document, const Operation& op, const NodeMask& mask, MeshScene& scene);

// The report as lines for the terminal: one per operation, then the warnings.
std::string formatMeshEditReport(const MeshEditReport& report);

}  // namespace glint
