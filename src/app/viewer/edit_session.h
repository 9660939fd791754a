// The viewer's edit stack: an EditDocument whose operations the page appends one at a
// time. Undo pops the last operation onto a redo list and redo pushes it back; either way
// the document is re-applied to a pristine copy of the scene and the tracer rebuilt, so
// what is shown is always exactly what `glint edit` would bake from the saved file.
#pragma once

#include <memory>
#include <mutex>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/viewer/progressive_renderer.h"
#include "edit/edit_document.h"
#include "raytrace/trace_settings.h"

namespace glint {

class EditSession {
 public:
  EditSession(GaussianScene pristine, const TraceSettings& trace);

  std::shared_ptr<const TracedScene> current() const;

  // {"selection": S, "operation": O}: S a selection as in an edit file, O an operation as in
  // an edit file without its "selection" field. Returns the edited scene; throws
  // RequestError 400 for a malformed request (nothing changes).
  std::shared_ptr<const TracedScene> apply(const nlohmann::json& request);
  // Throw RequestError 409 when there is nothing to undo or redo.
  std::shared_ptr<const TracedScene> undo();
  std::shared_ptr<const TracedScene> redo();

  // {"operations", "redoable", "gaussians"}
  nlohmann::json status() const;
  // {"selection": S, "attribute": "roughness"|"f0"|"diffuse"|"metalness", "bins": 1..256}
  // -> {"count", "total", "attribute", "histogram": [...], "range": [lo, hi]}: how many
  // Gaussians of the current scene S holds and the histogram of the attribute over them.
  nlohmann::json preview(const nlohmann::json& request) const;
  EditDocument document() const;

  static constexpr size_t kMaxOperations = 1000;

 private:
  struct Step {
    std::string selectionName;
    Selection selection;
    Operation operation;
  };
  // Applies steps_ to the pristine scene and builds its tracer (mutex_ held).
  void rebuild();

  mutable std::mutex mutex_;
  std::shared_ptr<const GaussianScene> pristine_;
  TraceSettings trace_;
  std::vector<Step> steps_;
  std::vector<Step> redo_;
  std::shared_ptr<const TracedScene> current_;
  int nextSelectionId_ = 0;
};

}  // namespace glint
