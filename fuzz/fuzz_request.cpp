// Fuzz harness for the viewer's JSON request bodies: camera, display settings, and the
// edit session's preview and apply (app/viewer/). Every body is offered to every route.
#include <cstddef>
#include <cstdint>
#include <string>

#include "app/viewer/display_settings.h"
#include "app/viewer/edit_session.h"
#include "app/viewer/request_json.h"
#include "app/viewer/viewer_camera.h"
#include "core/error.h"
#include "edit/gaussian_edits.h"
#include "fuzz/fuzz_support.h"

namespace {

// viewer_server.h's kMaxRequestBytes; restated so that the harness needs no HTTP server.
constexpr size_t kMaxBodyBytes = 64 * 1024;

// A route's clean rejections: a 4xx answer or a user error.
template <typename Route>
void offer(Route route) {
  try {
    route();
  } catch (const glint::RequestError&) {
  } catch (const glint::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  nlohmann::json request;
  try {
    request = glint::parseRequestObject(std::string(reinterpret_cast<const char*>(data), size), kMaxBodyBytes);
  } catch (const glint::RequestError&) {
    return 0;
  }
  offer([&] { glint::parseCameraRequest(request); });
  offer([&] {
    glint::DisplaySettings settings;
    glint::applySettingsRequest(request, &settings);
  });
  // A fresh session per input keeps every run independent of the ones before it.
  glint::EditSession session(glint::fuzz::smallScene(), glint::TraceSettings{}, glint::kDefaultMaxGaussians);
  offer([&] { session.preview(request); });
  offer([&] {
    glint::TracerUpdateContext context;
    context.probeCamera = glint::ViewerCamera{}.camera(16, 16);
    context.workRays = 16.0 * 16.0;
    session.apply(request, context);
  });
  return 0;
}
