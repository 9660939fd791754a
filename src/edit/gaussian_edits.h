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

// Where each Gaussian of an edited scene came from, for differential relighting: which
// Gaussians the edit left in place (they receive the changed light) and which it moved,
// added or removed (they change it).
struct EditProvenance {
  size_t countBefore = 0;
  std::vector<uint32_t> source;  // per Gaussian after the edit: its index before (a copy: its original's)
  std::vector<uint8_t> moved;    // per Gaussian after: translated, rotated or scaled, or a copy

  // Starts the record of an unedited scene of n Gaussians.
  static EditProvenance identity(size_t n);
  // Indices after the edit of Gaussians neither moved nor added.
  std::vector<uint32_t> unmoved() const;
  // Indices after the edit of Gaussians moved or added.
  std::vector<uint32_t> movedOrAdded() const;
  // Indices before the edit of Gaussians the edit moved or removed.
  std::vector<uint32_t> movedOrRemoved() const;
};

// Applies the operations in order; each selection is evaluated on the scene as the
// operations before it left it. The document must be valid (parseEditDocument). Throws
// GaussianLimitError (naming document.source) before an operation would make the scene
// hold more than maxGaussians; operations that do not add Gaussians always apply.
// With `provenance` (started with EditProvenance::identity of the scene's size), it records
// what each operation did to each Gaussian.
EditReport applyEdits(const EditDocument& document, GaussianScene& scene,
                      size_t maxGaussians = kDefaultMaxGaussians, EditProvenance* provenance = nullptr);

// Applies one operation to the Gaussians whose mask entry is set.
void applyOperation(const EditDocument& document, const Operation& op, const std::vector<uint8_t>& mask,
                    GaussianScene& scene);

// The report as lines for the terminal: one per operation, then the warnings.
std::string formatEditReport(const EditReport& report);

}  // namespace glint
