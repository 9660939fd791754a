// The viewer's Host, Origin, content type and token checks.
#include "app/viewer/access_policy.h"

#include <arpa/inet.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <random>

namespace glint {

namespace {

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

std::string withoutBrackets(const std::string& name) {
  return name.size() >= 2 && name.front() == '[' && name.back() == ']' ? name.substr(1, name.size() - 2) : name;
}

bool isIpv4(const std::string& name) {
  in_addr address;
  return inet_pton(AF_INET, name.c_str(), &address) == 1;
}

bool isIpv6(const std::string& name) {
  in6_addr address;
  return inet_pton(AF_INET6, name.c_str(), &address) == 1;
}

// A Host header split into its name (IPv6 without brackets) and port ("" when absent).
struct HostName {
  std::string name, port;
};

std::optional<HostName> splitHost(const std::string& header) {
  std::string host = lowercase(header);
  if (!host.empty() && host.front() == '[') {
    size_t close = host.find(']');
    if (close == std::string::npos) return std::nullopt;
    std::string rest = host.substr(close + 1);
    if (!rest.empty() && rest.front() != ':') return std::nullopt;
    return HostName{host.substr(1, close - 1), rest.empty() ? "" : rest.substr(1)};
  }
  size_t colon = host.find(':');
  if (colon == std::string::npos) return HostName{host, ""};
  return HostName{host.substr(0, colon), host.substr(colon + 1)};
}

// Names that a rebinding DNS name can never be: localhost, the bound address, loopback
// addresses and, when the server listens on every address, any address literal (a page
// whose origin is an address literal is that address's own page).
bool isAllowedHostName(const AccessPolicy& policy, const std::string& name) {
  std::string bound = lowercase(withoutBrackets(policy.boundHost));
  if (name == "localhost" || name == bound) return true;
  bool literal = isIpv4(name) || isIpv6(name);
  bool loopback = (isIpv4(name) && name.rfind("127.", 0) == 0) || name == "::1";
  bool wildcard = bound == "0.0.0.0" || bound == "::" || bound.empty();
  return literal && (loopback || wildcard);
}

bool isJsonMediaType(const std::string& contentType) {
  std::string type = lowercase(contentType.substr(0, contentType.find(';')));
  type.erase(std::remove_if(type.begin(), type.end(), [](unsigned char c) { return std::isspace(c); }), type.end());
  return type == "application/json";
}

// Compares in time independent of where the strings first differ.
bool sameToken(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char difference = 0;
  for (size_t i = 0; i < a.size(); ++i) difference |= (unsigned char)(a[i] ^ b[i]);
  return difference == 0;
}

}  // namespace

std::optional<AccessRefusal> checkAccess(const AccessPolicy& policy, const RequestFacts& request) {
  std::optional<HostName> host = splitHost(request.host);
  if (!host || !isAllowedHostName(policy, host->name))
    return AccessRefusal{403, "refused: the Host header \"" + request.host.substr(0, 100) +
                                  "\" is not this viewer's address (open the URL that glint printed)"};
  // Any port: rebinding needs a DNS name, whatever the port, and a forwarded port (ssh -L
  // 9000:127.0.0.1:PORT) names its own.
  if (host->port.find_first_not_of("0123456789") != std::string::npos)
    return AccessRefusal{403, "refused: the Host header \"" + request.host.substr(0, 100) + "\" is malformed"};
  if (request.origin && lowercase(*request.origin) != "http://" + lowercase(request.host))
    return AccessRefusal{403, "refused: a page of another origin (" + request.origin->substr(0, 100) +
                                  ") may not use this viewer"};
  if (request.method == "GET" || request.method == "HEAD") return std::nullopt;
  // Everything else changes state: a JSON body (which a cross-site form cannot send) and
  // the token of this launch.
  if (!isJsonMediaType(request.contentType))
    return AccessRefusal{415, "refused: requests that change the viewer must send Content-Type: application/json"};
  if (request.token.empty())
    return AccessRefusal{403, std::string("refused: missing ") + kTokenHeader +
                                  " header (open the URL that glint printed: it carries ?token=...)"};
  if (!sameToken(request.token, policy.token))
    return AccessRefusal{403, std::string("refused: wrong ") + kTokenHeader +
                                  " (the viewer was restarted? open the URL it printed last)"};
  return std::nullopt;
}

std::string makeAccessToken() {
  std::random_device entropy;  // /dev/urandom on Linux
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string token;
  for (int word = 0; word < 4; ++word) {
    uint32_t bits = entropy();
    for (int nibble = 0; nibble < 8; ++nibble) token += kDigits[(bits >> (4 * nibble)) & 15u];
  }
  return token;
}

}  // namespace glint
