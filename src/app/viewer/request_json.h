// Strict reading of the viewer's JSON request bodies: every field is checked for type,
// finiteness and range, and unknown fields are refused, so a malformed request becomes
// one 400 answer naming the field instead of undefined behaviour in the renderer.
#pragma once

#include <initializer_list>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "math/vec.h"

namespace glint {

// A request the server refuses: the HTTP status (4xx) and a message for the page.
class RequestError : public std::runtime_error {
 public:
  RequestError(int status, const std::string& message) : std::runtime_error(message), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

// Parses a body as a JSON object no larger than maxBytes; throws RequestError 413 or 400.
nlohmann::json parseRequestObject(const std::string& body, size_t maxBytes);

// Throws RequestError 400 naming the first field of object not in allowed.
void requireOnlyFields(const nlohmann::json& object, std::initializer_list<const char*> allowed);

// The named field as a finite number in [lo, hi]; throws RequestError 400 otherwise.
double readNumber(const nlohmann::json& object, const char* field, double lo, double hi);
int readInteger(const nlohmann::json& object, const char* field, int lo, int hi);
bool readBool(const nlohmann::json& object, const char* field);
std::string readString(const nlohmann::json& object, const char* field, size_t maxLength);
// A 3-element array of finite numbers, each within [-limit, limit].
Vec3d readVec3(const nlohmann::json& object, const char* field, double limit);

}  // namespace glint
