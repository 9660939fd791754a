// The viewer's edit endpoints: apply an operation, undo, redo, relight the last edit,
// preview a selection, save the edit file and export the edited scene, all under /api/edits.
#include <functional>

#include <httplib.h>

#include "app/viewer/edit_session.h"
#include "app/viewer/progressive_renderer.h"
#include "app/viewer/request_json.h"
#include "app/viewer/viewer_http.h"
#include "app/viewer/viewer_outputs.h"
#include "app/viewer/viewer_server.h"
#include "core/error.h"
#include "core/folder_lock.h"
#include "edit/edit_file.h"

namespace glint {

void ViewerServer::addEditRoutes() {
  httplib::Server& http = *http_;

  // The measurement of refit against rebuild (render/tracer_update.h) probes the camera
  // shown; until the next edit the viewer traces at most its sample budget at full size,
  // 1 + bounces segments a path.
  auto context = [this] {
    TracerUpdateContext c;
    c.probeCamera = renderer_->camera().camera(renderer_->width(), renderer_->height());
    c.workRays = double(renderer_->width()) * renderer_->height() * options_.maxSamples *
                 (1 + renderer_->settings().bounces);
    c.releaseShown = [this] { renderer_->releaseScene(); };
    return c;
  };
  // Runs an edit and shows its scene. The renderer may have let go of the shown scene
  // (releaseShown) before the edit failed: it gets the session's current scene back.
  auto answer = [this](httplib::Response& res, const std::function<std::shared_ptr<const TracedScene>()>& edit) {
    std::shared_ptr<const TracedScene> scene;
    try {
      scene = edit();
    } catch (...) {
      if (!renderer_->scene()) renderer_->setScene(edits_->current());
      throw;
    }
    renderer_->setScene(std::move(scene));
    sendJson(res, edits_->status());
  };
  // A save or export holds the run folder's lock while it writes; 409 names the process that
  // holds it (a `glint train` resumed into the run).
  auto lockForWriting = [this]() -> FolderLock {
    try {
      return FolderLock(options_.lockFolder.empty() ? options_.outputFolder : options_.lockFolder, "glint view");
    } catch (const Error& e) {
      throw RequestError(409, e.what());
    }
  };

  http.Get("/api/edits", [this](const httplib::Request&, httplib::Response& res) {
    sendJson(res, editDocumentToJson(edits_->document()));
  });
  http.Post("/api/edits/apply", [this, answer, context](const httplib::Request& req, httplib::Response& res) {
    nlohmann::json request = parseRequestObject(req.body, kMaxRequestBytes);
    answer(res, [&] { return edits_->apply(request, context()); });
  });
  http.Post("/api/edits/undo", [this, answer, context](const httplib::Request&, httplib::Response& res) {
    answer(res, [&] { return edits_->undo(context()); });
  });
  http.Post("/api/edits/redo", [this, answer, context](const httplib::Request&, httplib::Response& res) {
    answer(res, [&] { return edits_->redo(context()); });
  });
  // The page asks for this after an edit whose status says "relight_pending": the edit is
  // shown first, a preview of its shadows when {"preview": true} answers (in about a second),
  // and the full relighting when {} answers.
  http.Post("/api/edits/relight", [this, answer, context](const httplib::Request& req, httplib::Response& res) {
    nlohmann::json request = parseRequestObject(req.body.empty() ? "{}" : req.body, kMaxRequestBytes);
    requireOnlyFields(request, {"preview"});
    const bool preview = request.contains("preview") && readBool(request, "preview");
    answer(res, [&] { return preview ? edits_->relightPreview() : edits_->relight(context()); });
  });
  http.Post("/api/edits/preview", [this](const httplib::Request& req, httplib::Response& res) {
    sendJson(res, edits_->preview(parseRequestObject(req.body, kMaxRequestBytes)));
  });
  http.Post("/api/edits/save", [this, lockForWriting](const httplib::Request& req, httplib::Response& res) {
    std::filesystem::path file = viewerOutputFile(options_.outputFolder, parseRequestObject(req.body, kMaxRequestBytes),
                                                  "viewer_edits.json", ".json");
    const FolderLock lock = lockForWriting();
    writeEditFile(file, edits_->document());
    sendJson(res, {{"saved", file.string()}});
  });
  http.Post("/api/edits/export", [this, lockForWriting](const httplib::Request& req, httplib::Response& res) {
    std::filesystem::path file = viewerOutputFile(options_.outputFolder, parseRequestObject(req.body, kMaxRequestBytes),
                                                  "viewer_edited.ply", ".ply");
    const FolderLock lock = lockForWriting();
    size_t gaussians = edits_->exportPly(file);
    sendJson(res, {{"saved", file.string()}, {"gaussians", gaussians}});
  });
}

}  // namespace glint
