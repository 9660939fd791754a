// The viewer's undoable edit stack over an edit document.
#include "app/viewer/edit_session.h"

#include <chrono>

#include <algorithm>
#include <atomic>
#include <optional>

#include "app/viewer/request_json.h"
#include "core/error.h"
#include "edit/edit_file.h"
#include "edit/gaussian_edits.h"
#include "edit/gaussian_selection.h"
#include "edit/shape.h"
#include "edit_effects/edit_consequences.h"
#include "scene/gaussian_ply.h"

namespace glint {

namespace {

// The request's selection and operation as a one-operation edit document, parsed by the
// edit file reader so the page speaks exactly the edit file format.
EditDocument parseSingleOperation(const nlohmann::json& request, bool needsOperation) {
  if (needsOperation)
    requireOnlyFields(request, {"selection", "operation"});
  if (!request.contains("selection")) throw RequestError(400, "missing field \"selection\"");
  nlohmann::json document = {{"glint_edits", EditDocument::kVersion},
                             {"selections", {{"s", request["selection"]}}},
                             {"operations", nlohmann::json::array()}};
  if (needsOperation) {
    if (!request.contains("operation") || !request["operation"].is_object())
      throw RequestError(400, "\"operation\" must be an object");
    nlohmann::json op = request["operation"];
    if (op.contains("selection")) throw RequestError(400, "\"operation\" must not name a selection");
    op["selection"] = "s";
    document["operations"].push_back(op);
  }
  try {
    return parseEditDocument(document, "request");
  } catch (const Error& e) {
    throw RequestError(400, e.what());
  }
}

std::optional<Attribute> attributeFromName(const std::string& name) {
  if (name == "roughness") return Attribute::Roughness;
  if (name == "f0") return Attribute::F0;
  if (name == "diffuse") return Attribute::Diffuse;
  if (name == "metalness") return Attribute::Metalness;
  return std::nullopt;
}

float attributeValue(const GaussianScene& scene, size_t i, Attribute attribute) {
  auto mean = [](const Rgb& c) { return (c.x + c.y + c.z) / 3.0f; };
  switch (attribute) {
    case Attribute::Roughness: return scene.roughness[i];
    case Attribute::F0: return mean(scene.f0[i]);
    case Attribute::Diffuse: return mean(scene.diffuse[i]);
    case Attribute::Metalness: return derivedMetalness(mean(scene.diffuse[i]), mean(scene.f0[i]));
  }
  return 0;
}

}  // namespace

EditSession::EditSession(GaussianScene pristine, const TraceSettings& trace, size_t maxGaussians,
                         std::optional<RelightSettings> relight, std::optional<HealSettings> heal,
                         bool deferRelighting)
    : pristine_(std::make_shared<const GaussianScene>(std::move(pristine))),
      trace_(trace),
      maxGaussians_(maxGaussians),
      shownScene_(std::make_shared<GaussianScene>(*pristine_)),
      current_(traceScene(shownScene_, trace_)),
      relight_(relight),
      heal_(heal),
      deferRelighting_(deferRelighting) {}

std::shared_ptr<const TracedScene> EditSession::current() const {
  std::lock_guard lock(mutex_);
  return current_;
}

size_t EditSession::exportPly(const std::filesystem::path& file) const {
  std::lock_guard lock(mutex_);
  writeGaussianPly(file, *shownScene_);
  return shownScene_->size();
}

EditDocument EditSession::documentOfSteps() const {
  EditDocument document;
  document.source = "the viewer's edits";
  for (const Step& step : steps_) {
    document.selections[step.selectionName] = step.selection;
    document.operations.push_back(step.operation);
  }
  return document;
}

void EditSession::update(const TracerUpdateContext& context) {
  relightCancel_ = std::make_shared<std::atomic<bool>>(false);  // the previous edit's is set
  // Applied to a copy first: an operation that cannot apply throws before anything shown changes.
  GaussianScene edited = *pristine_;
  UpdatedTracer updated;
  EditCallbacks callbacks;
  callbacks.uneditedTracer = [this](const GaussianScene&) -> const GaussianTracer& { return pristineTracer(); };
  callbacks.editedTracer = [&](GaussianScene& scene) -> TracedScenePointers {
    // A refit needs the shown tracer and its scene object to ourselves: the render thread
    // lets go of them; a request that took them through current() just before still holds them.
    std::unique_ptr<GaussianTracer> previous;
    noRefitReason_ = "the Gaussian count changed";
    if (scene.size() == shownScene_->size()) {
      noRefitReason_ = "the shown scene was in use";
      previous = takeShownTracer(context);
    }
    if (previous)
      *shownScene_ = std::move(scene);  // the same object, which the previous tracer references
    else
      shownScene_ = std::make_shared<GaussianScene>(std::move(scene));
    bool refitPossible = previous != nullptr;
    updated = updateTracerAfterEdit(std::move(previous), *shownScene_, trace_, viewerTracer(), refitPossible,
                                    context.probeCamera, context.workRays);
    return {updated.tracer.get(), shownScene_.get()};
  };
  EditConsequenceSettings settings{maxGaussians_, heal_, relight_, deferRelighting_};
  EditOutcome outcome = applyEditDocument(documentOfSteps(), edited, pristine_.get(), settings, callbacks);
  lastHealed_ = outcome.healedCount;
  pending_.reset();
  if (outcome.pending) {
    pending_ = PendingRelight{std::move(*outcome.pending), nullptr};
    lastRelight_ = "waiting";
    lastRelightSeconds_ = 0;
  } else if (relight_) {
    lastRelight_ = outcome.relightLine;
    lastRelightSeconds_ = outcome.relightSeconds;
  }
  show(std::move(updated.tracer));
  lastUpdate_ = updated.times;
}

std::unique_ptr<GaussianTracer> EditSession::takeShownTracer(const TracerUpdateContext& context) {
  if (context.releaseShown) context.releaseShown();
  if (current_.use_count() != 1 || shownScene_.use_count() != 2) return nullptr;
  // Pairs with the release of the other holders' reference counts: their reads of the scene
  // happen before the caller overwrites it.
  std::atomic_thread_fence(std::memory_order_acquire);
  return std::move(current_->tracer);
}

void EditSession::show(std::unique_ptr<GaussianTracer> tracer) {
  auto next = std::make_shared<TracedScene>();
  next->scene = shownScene_;
  next->tracer = std::move(tracer);
  current_ = std::move(next);
}

const GaussianTracer& EditSession::pristineTracer() {
  if (!pristineTracer_) {
    pristineTracer_ = makeGaussianTracer(viewerTracer());
    pristineTracer_->build(*pristine_, trace_);
  }
  return *pristineTracer_;
}

std::unique_lock<std::mutex> EditSession::lockForEdit() {
  std::unique_lock lock(mutex_);
  relightCancel_->store(true);  // a deferred relighting still running is stale from now on
  return lock;
}

std::optional<EditSession::DeferredRelight> EditSession::startDeferred(std::unique_lock<std::mutex>& lock,
                                                                        const RelightSettings& settings,
                                                                        bool preview) {
  if (!pending_ || (preview && pending_->unrelit)) return std::nullopt;
  DeferredRelight job;
  job.stale = relightCancel_;  // this edit's flag: set by the next edit request
  job.unrelit = pending_->unrelit ? pending_->unrelit : current_;
  job.inputs = pending_->inputs;
  job.started = std::chrono::steady_clock::now();
  const GaussianTracer& pristine = pristineTracer();  // built under the lock, read-only after
  RelightSettings cancellable = settings;
  cancellable.cancel = job.stale.get();
  // Traced without the lock: status, selection previews, saves and edits go on meanwhile (an
  // edit cancels it and makes it stale); the unrelit scene it reads is held by job.unrelit,
  // so no edit overwrites it in place (takeShownTracer).
  lock.unlock();
  GaussianScene relit = *job.unrelit->scene;
  try {
    job.line = relightEdit(pristine, *pristine_, *job.unrelit->tracer, relit, job.inputs, cancellable);
  } catch (const RelightCancelled&) {
    lock.lock();
    return std::nullopt;  // a newer edit's status stands
  }
  job.relit = std::move(relit);
  lock.lock();
  if (*job.stale || !pending_) return std::nullopt;  // an edit, or the full relighting, came first
  return job;
}

std::shared_ptr<const TracedScene> EditSession::relightPreview() {
  std::unique_lock lock(mutex_);
  RelightSettings preview = *relight_;
  preview.tracedBudget = kPreviewTraced;
  preview.setRays(std::min(kPreviewRays, relight_->rays));
  preview.path.bounces = kPreviewBounces;
  std::optional<DeferredRelight> job = startDeferred(lock, preview, true);
  if (!job || pending_->unrelit) return current_;
  // Shown over a tracer of its own, built without the lock: the unrelit scene and its tracer
  // are kept for the full relighting, which must trace the colours as the edit left them.
  auto relit = std::make_shared<GaussianScene>(std::move(job->relit));
  lock.unlock();
  std::unique_ptr<GaussianTracer> tracer = makeGaussianTracer(viewerTracer());
  tracer->build(*relit, trace_);
  lock.lock();
  if (*job->stale || !pending_ || pending_->unrelit) return current_;
  pending_->unrelit = current_;  // job->unrelit: nothing else changes what is shown meanwhile
  shownScene_ = std::move(relit);
  show(std::move(tracer));
  lastRelight_ = "preview: " + job->line;
  lastRelightSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - job->started).count();
  return current_;
}

std::shared_ptr<const TracedScene> EditSession::relight(const TracerUpdateContext& context) {
  std::unique_lock lock(mutex_);
  // On a copy of the unrelit scene (the shown one unless a preview is shown): the renderer
  // traces the shown scene meanwhile. Only the colours differ.
  std::optional<DeferredRelight> job = startDeferred(lock, *relight_, false);
  if (!job) return current_;
  pending_.reset();  // and with it the unrelit scene a preview kept
  job->unrelit.reset();

  // As in update: the shown scene is overwritten in place and its tracer refitted only when
  // nobody else holds them once the renderer has let go.
  std::unique_ptr<GaussianTracer> tracer = takeShownTracer(context);
  if (tracer) {
    shownScene_->diffuse = std::move(job->relit.diffuse);
    tracer->refit();  // tracers may keep copies of the colours
  } else {
    shownScene_ = std::make_shared<GaussianScene>(std::move(job->relit));
    tracer = makeGaussianTracer(viewerTracer());
    tracer->build(*shownScene_, trace_);
  }
  show(std::move(tracer));
  lastRelight_ = job->line;
  lastRelightSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - job->started).count();
  return current_;
}

std::shared_ptr<const TracedScene> EditSession::apply(const nlohmann::json& request,
                                                      const TracerUpdateContext& context) {
  EditDocument single = parseSingleOperation(request, true);
  std::unique_lock lock = lockForEdit();
  if (steps_.size() >= kMaxOperations)
    throw RequestError(409, "the edit stack holds " + std::to_string(kMaxOperations) + " operations; save and restart");
  Step step{"selection_" + std::to_string(nextSelectionId_++), single.selections.at("s"), single.operations[0]};
  step.operation.selection = step.selectionName;
  steps_.push_back(std::move(step));
  try {
    update(context);
  } catch (const GaussianLimitError& e) {
    steps_.pop_back();
    throw RequestError(413, e.what());
  } catch (const Error& e) {  // the operation cannot apply (e.g. a rotation without pivot)
    steps_.pop_back();
    throw RequestError(400, e.what());
  }
  redo_.clear();
  return current_;
}

std::shared_ptr<const TracedScene> EditSession::undo(const TracerUpdateContext& context) {
  std::unique_lock lock = lockForEdit();
  if (steps_.empty()) throw RequestError(409, "nothing to undo");
  redo_.push_back(std::move(steps_.back()));
  steps_.pop_back();
  update(context);
  return current_;
}

std::shared_ptr<const TracedScene> EditSession::redo(const TracerUpdateContext& context) {
  std::unique_lock lock = lockForEdit();
  if (redo_.empty()) throw RequestError(409, "nothing to redo");
  steps_.push_back(std::move(redo_.back()));
  redo_.pop_back();
  update(context);
  return current_;
}

nlohmann::json EditSession::status() const {
  std::lock_guard lock(mutex_);
  nlohmann::json status = {
      {"operations", steps_.size()}, {"redoable", redo_.size()}, {"gaussians", current_->scene->size()}};
  if (lastUpdate_) {
    const TracerUpdateTimes& t = *lastUpdate_;
    status["tracer_update"] = {{"action", t.refitChosen ? "refit" : "rebuild"},
                               {"refit_possible", t.refitPossible},
                               {"refit_ms", 1e3 * t.refitSeconds},
                               {"rebuild_ms", 1e3 * t.rebuildSeconds},
                               {"refit_probe_ms", 1e3 * t.refitProbeSeconds},
                               {"rebuild_probe_ms", 1e3 * t.rebuildProbeSeconds},
                               {"probe_rays", t.probeRays},
                               {"work_rays", t.workRays}};
    if (!t.refitPossible) status["tracer_update"]["no_refit"] = noRefitReason_;
  }
  if (heal_) status["healed"] = lastHealed_;
  if (!lastRelight_.empty()) {
    status["relight"] = lastRelight_;
    status["relight_ms"] = 1e3 * lastRelightSeconds_;
    status["relight_pending"] = pending_.has_value();
    status["relight_preview"] = pending_ && pending_->unrelit;
  }
  return status;
}

EditDocument EditSession::document() const {
  std::lock_guard lock(mutex_);
  return documentOfSteps();
}

nlohmann::json EditSession::preview(const nlohmann::json& request) const {
  requireOnlyFields(request, {"selection", "attribute", "bins"});
  EditDocument single = parseSingleOperation(request, false);
  std::string name = request.contains("attribute") ? readString(request, "attribute", 16) : "roughness";
  std::optional<Attribute> attribute = attributeFromName(name);
  if (!attribute) throw RequestError(400, "\"attribute\" must be one of f0, roughness, diffuse, metalness");
  int bins = request.contains("bins") ? readInteger(request, "bins", 1, 256) : 32;

  // Under the lock, so an edit never overwrites the scene read here (and can refit it).
  std::lock_guard lock(mutex_);
  const GaussianScene& scene = *shownScene_;
  GaussianMask selected;
  try {
    selected = selectGaussians(single, "s", scene);
  } catch (const Error& e) {
    throw RequestError(400, e.what());
  }
  // Attributes lie in [0, 1] except diffuse, whose histogram spans the selection's range.
  float lo = 0, hi = 1;
  if (*attribute == Attribute::Diffuse) {
    hi = 0;
    for (size_t i = 0; i < selected.size(); ++i)
      if (selected[i]) hi = std::max(hi, attributeValue(scene, i, *attribute));
    hi = std::max(hi, 1e-6f);
  }
  std::vector<int64_t> histogram(size_t(bins), 0);
  int64_t count = 0;
  for (size_t i = 0; i < selected.size(); ++i) {
    if (!selected[i]) continue;
    ++count;
    float t = (attributeValue(scene, i, *attribute) - lo) / (hi - lo);
    histogram[size_t(std::clamp(int(t * float(bins)), 0, bins - 1))]++;
  }
  return {{"count", count}, {"total", selected.size()}, {"attribute", name}, {"histogram", histogram},
          {"range", {lo, hi}}};
}

}  // namespace glint
