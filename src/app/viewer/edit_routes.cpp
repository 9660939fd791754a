// The viewer's edit endpoints: apply an operation, undo, redo, preview a selection, save
// the edit file and export the edited scene, all under /api/edits.
#include <httplib.h>

#include "app/viewer/edit_session.h"
#include "app/viewer/progressive_renderer.h"
#include "app/viewer/request_json.h"
#include "app/viewer/viewer_http.h"
#include "app/viewer/viewer_server.h"
#include "edit/edit_file.h"
#include "scene/gaussian_ply.h"

namespace glint {

namespace {

// The file a save or export request names: a plain file name with the given extension,
// inside the output folder (a request never chooses a folder).
std::filesystem::path outputFile(const std::filesystem::path& folder, const nlohmann::json& request,
                                 const char* defaultName, const char* extension) {
  requireOnlyFields(request, {"name"});
  std::string name = request.contains("name") ? readString(request, "name", 100) : defaultName;
  bool plain = !name.empty() && name[0] != '.' && name.find_first_not_of("abcdefghijklmnopqrstuvwxyz"
                                                                          "ABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_.") ==
                                                       std::string::npos;
  std::string ext = extension;
  if (!plain || name.size() <= ext.size() || name.compare(name.size() - ext.size(), ext.size(), ext) != 0)
    throw RequestError(400, "\"name\" must be a plain file name ending in " + ext);
  return folder / name;
}

}  // namespace

void ViewerServer::addEditRoutes() {
  httplib::Server& http = *http_;

  auto answer = [this](httplib::Response& res, std::shared_ptr<const TracedScene> scene) {
    renderer_->setScene(std::move(scene));
    sendJson(res, edits_->status());
  };

  http.Get("/api/edits", [this](const httplib::Request&, httplib::Response& res) {
    sendJson(res, editDocumentToJson(edits_->document()));
  });
  http.Post("/api/edits/apply", [this, answer](const httplib::Request& req, httplib::Response& res) {
    answer(res, edits_->apply(parseRequestObject(req.body, kMaxRequestBytes)));
  });
  http.Post("/api/edits/undo", [this, answer](const httplib::Request&, httplib::Response& res) {
    answer(res, edits_->undo());
  });
  http.Post("/api/edits/redo", [this, answer](const httplib::Request&, httplib::Response& res) {
    answer(res, edits_->redo());
  });
  http.Post("/api/edits/preview", [this](const httplib::Request& req, httplib::Response& res) {
    sendJson(res, edits_->preview(parseRequestObject(req.body, kMaxRequestBytes)));
  });
  http.Post("/api/edits/save", [this](const httplib::Request& req, httplib::Response& res) {
    std::filesystem::path file =
        outputFile(options_.outputFolder, parseRequestObject(req.body, kMaxRequestBytes), "viewer_edits.json", ".json");
    writeEditFile(file, edits_->document());
    sendJson(res, {{"saved", file.string()}});
  });
  http.Post("/api/edits/export", [this](const httplib::Request& req, httplib::Response& res) {
    std::filesystem::path file =
        outputFile(options_.outputFolder, parseRequestObject(req.body, kMaxRequestBytes), "viewer_edited.ply", ".ply");
    writeGaussianPly(file, *edits_->current()->scene);
    sendJson(res, {{"saved", file.string()}, {"gaussians", edits_->current()->scene->size()}});
  });
}

}  // namespace glint
