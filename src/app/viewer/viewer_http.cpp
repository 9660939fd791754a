// JSON answers and error handling of the viewer's HTTP routes.
#include "app/viewer/viewer_http.h"

#include <exception>
#include <fstream>
#include <sstream>

#include <httplib.h>

#include "app/viewer/request_json.h"
#include "core/error.h"

namespace glint {

namespace {

constexpr uintmax_t kMaxStaticFileBytes = 8u << 20;

const char* statusText(int status) {
  switch (status) {
    case 400: return "bad request";
    case 403: return "forbidden";
    case 404: return "not found";
    case 405: return "method not allowed";
    case 409: return "conflict";
    case 413: return "request too large";
    case 414: return "URI too long";
    default: return status >= 500 ? "internal error" : "request refused";
  }
}

}  // namespace

void sendJson(httplib::Response& res, const nlohmann::json& body, int status) {
  res.status = status;
  res.set_header("Cache-Control", "no-store");
  res.set_content(body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), "application/json");
}

void installErrorHandlers(httplib::Server& http) {
  http.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
    try {
      std::rethrow_exception(error);
    } catch (const RequestError& e) {
      sendJson(res, {{"error", e.what()}}, e.status());
    } catch (const Error& e) {
      sendJson(res, {{"error", e.what()}}, 400);
    } catch (const std::exception& e) {
      sendJson(res, {{"error", std::string("internal error: ") + e.what()}}, 500);
    } catch (...) {
      sendJson(res, {{"error", "internal error"}}, 500);
    }
  });
  // Errors httplib produces itself (unknown routes, oversized bodies) arrive without a body.
  http.set_error_handler([](const httplib::Request&, httplib::Response& res) {
    if (res.body.empty()) sendJson(res, {{"error", statusText(res.status)}}, res.status);
  });
}

uint64_t parseQueryCount(const std::string& text, const char* name) {
  if (text.empty() || text.size() > 18 || text.find_first_not_of("0123456789") != std::string::npos)
    throw RequestError(400, std::string("\"") + name + "\" must be a non-negative integer");
  return std::stoull(text);
}

std::string readSmallFile(const std::filesystem::path& file) {
  std::error_code error;
  uintmax_t size = std::filesystem::file_size(file, error);
  if (error) throw RequestError(404, "not found");
  if (size > kMaxStaticFileBytes) throw RequestError(413, "file too large to serve");
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

}  // namespace glint
