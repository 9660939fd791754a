// Routes of the viewer's HTTP server: static files, frames, camera, settings, training cameras.
#include "app/viewer/viewer_server.h"

#include <cstdio>

#include <httplib.h>

#include "app/viewer/connection_limits.h"
#include "app/viewer/edit_session.h"
#include "app/viewer/frame_encoding.h"
#include "app/viewer/progressive_renderer.h"
#include "app/viewer/request_json.h"
#include "app/viewer/static_files.h"
#include "app/viewer/viewer_http.h"
#include "core/error.h"
#include "io/image.h"

namespace glint {

namespace {

// A frame request waits at most this long for a newer frame than the page has.
constexpr std::chrono::milliseconds kFrameWait{1000};

}  // namespace

ViewerServer::ViewerServer(ViewerOptions options, GaussianScene scene, const TraceSettings& trace)
    : options_(std::move(options)), trace_(trace), http_(std::make_unique<httplib::Server>()) {
  access_.boundHost = options_.host;
  access_.token = options_.token.empty() ? makeAccessToken() : options_.token;
  if (options_.width < 8 || options_.height < 8 || options_.width > 8192 || options_.height > 8192)
    throw Error("glint view", "the viewer's resolution must lie between 8x8 and 8192x8192");
  renderer_ = std::make_unique<ProgressiveRenderer>(options_.width, options_.height, options_.maxSamples, options_.path);
  if (options_.editable) {
    // Relighting deferred: the page shows the edit at once and asks for it (/api/edits/relight).
    edits_ = std::make_unique<EditSession>(std::move(scene), trace_, options_.maxGaussians, options_.relight,
                                           options_.heal, /*deferRelighting=*/true);
    renderer_->setScene(edits_->current());
  } else {
    renderer_->setScene(traceScene(std::make_shared<const GaussianScene>(std::move(scene)), trace_));
  }
  renderer_->setCamera(options_.initialCamera);
  addRoutes();
  if (options_.editable) addEditRoutes();
  addStaticRoute();  // last: its pattern matches every GET
}

ViewerServer::~ViewerServer() {
  stop();
  renderer_.reset();  // joins the render thread before the scenes go
}

int ViewerServer::bind() {
  http_->set_payload_max_length(kMaxRequestBytes);
  http_->set_tcp_nodelay(true);  // headers and body go out in separate writes: no Nagle delay between them
  ConnectionLimits limits;
  applyConnectionLimits(*http_, limits);
  port_ = bindWithBacklog(*http_, options_.host, options_.port, limits.backlog);
  if (port_ <= 0)
    throw Error("glint view", "cannot listen on " + options_.host + ":" + std::to_string(options_.port) +
                                  " (in use, or not an address of this machine)");
  return port_;
}

void ViewerServer::start() {
  listener_ = std::thread([this] { http_->listen_after_bind(); });
  // The socket already listens (bind), so clients queue; wait only so stop() cannot race listen().
  while (!http_->is_running()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

void ViewerServer::stop() {
  if (http_) http_->stop();
  if (listener_.joinable()) listener_.join();
}

std::string ViewerServer::url() const {
  std::string host = options_.host.find(':') != std::string::npos ? "[" + options_.host + "]" : options_.host;
  return "http://" + host + ":" + std::to_string(port_) + "/?token=" + access_.token;
}

void ViewerServer::showScene(GaussianScene scene) {
  GLINT_CHECK(!options_.editable, "an editable viewer's scene comes from its edits");
  renderer_->setUntracedScene(std::make_shared<const GaussianScene>(std::move(scene)), trace_);
}

void ViewerServer::addRoutes() {
  httplib::Server& http = *http_;
  installErrorHandlers(http);

  // Before routing, and before the body is read: refused requests cost nothing.
  http.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    RequestFacts facts{req.method, req.get_header_value("Host"), std::nullopt, req.get_header_value("Content-Type"),
                       req.get_header_value(kTokenHeader)};
    if (req.has_header("Origin")) facts.origin = req.get_header_value("Origin");
    std::optional<AccessRefusal> refusal = checkAccess(access_, facts);
    if (!refusal) return httplib::Server::HandlerResponse::Unhandled;
    res.set_header("Connection", "close");  // its body, if any, stays unread
    sendJson(res, {{"error", refusal->message}}, refusal->status);
    return httplib::Server::HandlerResponse::Handled;
  });

  http.Get("/api/state", [this](const httplib::Request&, httplib::Response& res) {
    std::shared_ptr<const TracedScene> scene = renderer_->scene();
    nlohmann::json state = {{"camera", toJson(renderer_->camera())},
                            {"settings", toJson(renderer_->settings())},
                            {"width", renderer_->width()},
                            {"height", renderer_->height()},
                            {"gaussians", scene ? scene->scene->size() : 0},
                            {"editable", options_.editable}};
    if (edits_) state["edits"] = edits_->status();
    if (scene && !scene->scene->empty()) {
      Vec3f lo = scene->scene->position[0], hi = lo;
      for (const Vec3f& p : scene->scene->position) lo = min(lo, p), hi = max(hi, p);
      state["bounds"] = {{"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}};
    }
    sendJson(res, state);
  });

  http.Post("/api/camera", [this](const httplib::Request& req, httplib::Response& res) {
    renderer_->setCamera(parseCameraRequest(parseRequestObject(req.body, kMaxRequestBytes)));
    sendJson(res, toJson(renderer_->camera()));
  });

  http.Post("/api/settings", [this](const httplib::Request& req, httplib::Response& res) {
    DisplaySettings settings = renderer_->settings();
    applySettingsRequest(parseRequestObject(req.body, kMaxRequestBytes), &settings);
    renderer_->setSettings(settings);
    sendJson(res, toJson(settings));
  });

  http.Get("/api/training_cameras", [this](const httplib::Request&, httplib::Response& res) {
    nlohmann::json list = nlohmann::json::array();
    for (const TrainingCameraEntry& entry : options_.trainingCameras)
      list.push_back({{"name", entry.name}, {"camera", toJson(entry.camera)}});
    sendJson(res, list);
  });

  // GET /api/frame?after=ID&format=png|jpeg: the newest frame once newer than ID (waiting
  // up to a second), with X-Glint-Frame (its id) and X-Glint-Samples.
  http.Get("/api/frame", [this](const httplib::Request& req, httplib::Response& res) {
    uint64_t after = 0;
    if (req.has_param("after")) after = parseQueryCount(req.get_param_value("after"), "after");
    std::string format = req.has_param("format") ? req.get_param_value("format") : "jpeg";
    if (format != "png" && format != "jpeg") throw RequestError(400, "\"format\" must be png or jpeg");
    std::shared_ptr<const ViewerFrame> frame = renderer_->waitForFrame(after, kFrameWait);
    if (!frame) throw RequestError(503, "no frame rendered yet");
    res.set_header("X-Glint-Frame", std::to_string(frame->id));
    res.set_header("X-Glint-Samples", std::to_string(frame->samples));
    res.set_header("X-Glint-Render-Ms", std::to_string(int(frame->renderSeconds * 1000)));
    res.set_header("Cache-Control", "no-store");
    if (format == "png")
      res.set_content(encodePng(frame->image), "image/png");
    else
      res.set_content(encodeJpeg(frame->image), "image/jpeg");
  });

}

void ViewerServer::addStaticRoute() {
  // Everything else that is a GET is a file of the page, or 404.
  http_->Get(R"(/.*)", [this](const httplib::Request& req, httplib::Response& res) {
    if (req.path.rfind("/api/", 0) == 0) throw RequestError(404, "no such endpoint");
    std::optional<std::filesystem::path> file =
        options_.webRoot.empty() ? std::nullopt : resolveStaticFile(options_.webRoot, req.path);
    if (!file) throw RequestError(404, "not found");
    res.set_content(readSmallFile(*file), contentTypeFor(*file));
  });
}

}  // namespace glint
