// Applies an edit document to a Gaussian scene, operation by operation (docs/edit-files.md).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/error.h"
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

// The Gaussians an edit may leave in a scene unless told otherwise (--max-gaussians). The
// viewer holds about 230 bytes a Gaussian shown (scene copies and the tracer), 390 at the
// peak of a rebuild (measured, README "Viewer"): 10 million stay near 4 GB, and trained
// scenes hold a few million at most.
constexpr size_t kDefaultMaxGaussians = 10'000'000;

// An operation that would leave more Gaussians than allowed. Thrown before the operation
// allocates anything; the scene then holds what the operations before it made.
class GaussianLimitError : public Error {
 public:
  using Error::Error;
};

// Applies the operations in order; each selection is evaluated on the scene as the
// operations before it left it. The document must be valid (parseEditDocument). Throws
// GaussianLimitError (naming document.source) before an operation would make the scene
// hold more than maxGaussians; operations that do not add Gaussians always apply.
EditReport applyEdits(const EditDocument& document, GaussianScene& scene,
                      size_t maxGaussians = kDefaultMaxGaussians);

// Applies one operation to the Gaussians whose mask entry is set.
void applyOperation(const EditDocument& document, const Operation& op, const std::vector<uint8_t>& mask,
                    GaussianScene& scene);

// The report as lines for the terminal: one per operation, then the warnings.
std::string formatEditReport(const EditReport& report);

}  // namespace glint
