// Strict JSON field readers for the viewer's requests.
#include "app/viewer/request_json.h"

#include <cmath>

namespace glint {

namespace {

const nlohmann::json& field(const nlohmann::json& object, const char* name) {
  auto it = object.find(name);
  if (it == object.end()) throw RequestError(400, std::string("missing field \"") + name + "\"");
  return *it;
}

double finiteNumber(const nlohmann::json& value, const std::string& what) {
  if (!value.is_number()) throw RequestError(400, what + " must be a number");
  double x = value.get<double>();
  if (!std::isfinite(x)) throw RequestError(400, what + " must be finite");
  return x;
}

}  // namespace

nlohmann::json parseRequestObject(const std::string& body, size_t maxBytes) {
  if (body.size() > maxBytes)
    throw RequestError(413, "request body of " + std::to_string(body.size()) + " bytes exceeds the limit of " +
                                std::to_string(maxBytes));
  // Depth-limited parse: nlohmann's parser recurses, so a body of nested brackets could
  // exhaust the stack; the callback refuses anything nested deeper than any request needs.
  constexpr int kMaxDepth = 32;
  nlohmann::json::parser_callback_t limitDepth = [](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > kMaxDepth) throw RequestError(400, "JSON nested too deeply");
    return true;
  };
  nlohmann::json j = nlohmann::json::parse(body, limitDepth, /*allow_exceptions=*/false);
  if (j.is_discarded()) throw RequestError(400, "body is not valid JSON");
  if (!j.is_object()) throw RequestError(400, "body must be a JSON object");
  return j;
}

void requireOnlyFields(const nlohmann::json& object, std::initializer_list<const char*> allowed) {
  for (auto it = object.begin(); it != object.end(); ++it) {
    bool known = false;
    for (const char* name : allowed) known = known || it.key() == name;
    if (!known) throw RequestError(400, "unknown field \"" + it.key().substr(0, 64) + "\"");
  }
}

double readNumber(const nlohmann::json& object, const char* name, double lo, double hi) {
  double x = finiteNumber(field(object, name), std::string("\"") + name + "\"");
  if (x < lo || x > hi)
    throw RequestError(400, std::string("\"") + name + "\" must lie in [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]");
  return x;
}

int readInteger(const nlohmann::json& object, const char* name, int lo, int hi) {
  const nlohmann::json& value = field(object, name);
  if (!value.is_number_integer()) throw RequestError(400, std::string("\"") + name + "\" must be an integer");
  return int(readNumber(object, name, lo, hi));
}

bool readBool(const nlohmann::json& object, const char* name) {
  const nlohmann::json& value = field(object, name);
  if (!value.is_boolean()) throw RequestError(400, std::string("\"") + name + "\" must be true or false");
  return value.get<bool>();
}

std::string readString(const nlohmann::json& object, const char* name, size_t maxLength) {
  const nlohmann::json& value = field(object, name);
  if (!value.is_string()) throw RequestError(400, std::string("\"") + name + "\" must be a string");
  std::string s = value.get<std::string>();
  if (s.size() > maxLength) throw RequestError(400, std::string("\"") + name + "\" is too long");
  return s;
}

Vec3d readVec3(const nlohmann::json& object, const char* name, double limit) {
  const nlohmann::json& value = field(object, name);
  std::string what = std::string("\"") + name + "\"";
  if (!value.is_array() || value.size() != 3) throw RequestError(400, what + " must be an array of 3 numbers");
  Vec3d v;
  for (int i = 0; i < 3; ++i) {
    double x = finiteNumber(value[size_t(i)], what + "[" + std::to_string(i) + "]");
    if (std::abs(x) > limit) throw RequestError(400, what + " components must lie within +-" + std::to_string(limit));
    v[i] = x;
  }
  return v;
}

}  // namespace glint
