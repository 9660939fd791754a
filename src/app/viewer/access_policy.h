// Who may talk to the viewer: a request must name the server by an address that cannot be
// a rebinding DNS name (Host), come from the viewer's own page when a browser says where
// it comes from (Origin), and, to change anything, carry the per-launch token printed in
// the page's URL and a JSON body. See README "Viewer" for the reasons.
#pragma once

#include <optional>
#include <string>

namespace glint {

// The header through which the page sends the token it read from its URL (?token=...).
constexpr const char* kTokenHeader = "X-Glint-Token";

struct AccessPolicy {
  std::string boundHost;  // the address the server listens on, as given to --host
  std::string token;  // required on every POST
};

// What the policy needs of a request (header values; empty when absent).
struct RequestFacts {
  std::string method;
  std::string host;
  std::optional<std::string> origin;
  std::string contentType;
  std::string token;
};

struct AccessRefusal {
  int status;  // 403 or 415
  std::string message;
};

// Nothing when the request may proceed; otherwise the answer to give instead.
std::optional<AccessRefusal> checkAccess(const AccessPolicy& policy, const RequestFacts& request);

// 128 random bits from the operating system, as 32 hexadecimal digits.
std::string makeAccessToken();

}  // namespace glint
