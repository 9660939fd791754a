// Applies an edit document to a Gaussian scene, operation by operation (docs/edit-files.md).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "edit/edit_document.h"
#include "scene/gaussians.h"

namespace glint {

struct OperationReport {
  std::string description;  // e.g. `operations[1] rotate "chrome"`
  size_t selected = 0;      // Gaussians the selection held when the operation ran
};

struct EditReport {
  std::vector<OperationReport> operations;
  std::vector<std::string> warnings;  // e.g. selections that held nothing
  size_t countBefore = 0, countAfter = 0;
  bool countChanged() const { return countBefore != countAfter; }
};

// Applies the operations in order; each selection is evaluated on the scene as the
// operations before it left it. The document must be valid (parseEditDocument).
EditReport applyEdits(const EditDocument& document, GaussianScene& scene);

// Applies one operation to the Gaussians whose mask entry is set.
void applyOperation(const EditDocument& document, const Operation& op, const std::vector<uint8_t>& mask,
                    GaussianScene& scene);

// The report as lines for the terminal: one per operation, then the warnings.
std::string formatEditReport(const EditReport& report);

}  // namespace glint
