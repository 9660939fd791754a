// Small pieces shared by the viewer's route handlers: JSON answers, the error handlers
// that turn every failure into a JSON 4xx/5xx, query parsing and static file reading.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace httplib {
class Server;
struct Response;
}  // namespace httplib

namespace glint {

void sendJson(httplib::Response& res, const nlohmann::json& body, int status = 200);
// Exception and error handlers: RequestError -> its status, Error -> 400, anything else
// -> 500; bare httplib errors (404 of unknown POST routes, 413, ...) get a JSON body too.
void installErrorHandlers(httplib::Server& http);
// A non-negative decimal integer of at most 18 digits; throws RequestError 400 otherwise.
uint64_t parseQueryCount(const std::string& text, const char* name);
// Reads a file of the page (at most a few megabytes); throws RequestError 404/413.
std::string readSmallFile(const std::filesystem::path& file);

}  // namespace glint
