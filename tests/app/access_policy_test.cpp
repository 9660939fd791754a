// The viewer's access policy on its own: which Host names are this server's (never a DNS
// name that could be rebound), which Origins are its page's, and what a POST must carry.
#include "app/viewer/access_policy.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

const AccessPolicy kLoopback{"127.0.0.1", "0123456789abcdef0123456789abcdef"};

RequestFacts get(const std::string& host) { return {"GET", host, std::nullopt, "", ""}; }

RequestFacts post(const std::string& type, const std::string& token) {
  return {"POST", "127.0.0.1:8123", "http://127.0.0.1:8123", type, token};
}

TEST(AccessPolicy, HostMustNameThisServer) {
  // Any port: a forwarded one (ssh -L 9000:127.0.0.1:8123) names its own.
  for (const char* host : {"127.0.0.1:8123", "localhost:8123", "LocalHost:8123", "[::1]:8123", "127.0.0.2:8123",
                           "localhost:9000", "127.0.0.1"})
    EXPECT_FALSE(checkAccess(kLoopback, get(host))) << host;
  for (const char* host : {"", "evil.example:8123", "127.0.0.1.nip.io:8123", "192.168.1.5:8123", "[::1",
                           "localhost:8123:8123", "[::1]x", "evil.example"}) {
    std::optional<AccessRefusal> refusal = checkAccess(kLoopback, get(host));
    ASSERT_TRUE(refusal) << host;
    EXPECT_EQ(refusal->status, 403) << host;
  }
}

TEST(AccessPolicy, NetworkBindsAcceptTheirAddressAndLiteralsOnly) {
  AccessPolicy lan{"192.168.1.5", "t"};
  EXPECT_FALSE(checkAccess(lan, get("192.168.1.5")));
  EXPECT_FALSE(checkAccess(lan, get("192.168.1.5:80")));
  EXPECT_TRUE(checkAccess(lan, get("10.0.0.1:80")));
  AccessPolicy any{"0.0.0.0", "t"};
  EXPECT_FALSE(checkAccess(any, get("10.0.0.1:9000")));
  EXPECT_FALSE(checkAccess(any, get("[fe80::1]:9000")));
  EXPECT_TRUE(checkAccess(any, get("workstation.lan:9000")));  // a name could be rebound
  AccessPolicy named{"workstation.lan", "t"};
  EXPECT_FALSE(checkAccess(named, get("workstation.lan:9000")));
}

TEST(AccessPolicy, OriginMustBeThePagesOwn) {
  RequestFacts request = get("127.0.0.1:8123");
  for (const char* origin : {"http://127.0.0.1:8123", "HTTP://127.0.0.1:8123"}) {
    request.origin = origin;
    EXPECT_FALSE(checkAccess(kLoopback, request)) << origin;
  }
  for (const char* origin : {"null", "https://127.0.0.1:8123", "http://localhost:8123", "http://evil.example", ""}) {
    request.origin = origin;
    std::optional<AccessRefusal> refusal = checkAccess(kLoopback, request);
    ASSERT_TRUE(refusal) << origin;
    EXPECT_EQ(refusal->status, 403);
  }
}

TEST(AccessPolicy, PostsNeedJsonAndTheToken) {
  EXPECT_FALSE(checkAccess(kLoopback, post("application/json", kLoopback.token)));
  EXPECT_FALSE(checkAccess(kLoopback, post("Application/JSON ; charset=utf-8", kLoopback.token)));
  for (const char* type : {"text/plain", "", "application/jsonx", "application/x-www-form-urlencoded"}) {
    std::optional<AccessRefusal> refusal = checkAccess(kLoopback, post(type, kLoopback.token));
    ASSERT_TRUE(refusal) << type;
    EXPECT_EQ(refusal->status, 415) << type;
  }
  for (const std::string& token : {std::string(), std::string("0123456789abcdef0123456789abcdeF"), std::string("x")}) {
    std::optional<AccessRefusal> refusal = checkAccess(kLoopback, post("application/json", token));
    ASSERT_TRUE(refusal) << token;
    EXPECT_EQ(refusal->status, 403) << token;
  }
}

TEST(AccessPolicy, TokensAreFreshAndLong) {
  std::string a = makeAccessToken(), b = makeAccessToken();
  EXPECT_EQ(a.size(), 32u);
  EXPECT_NE(a, b);
  EXPECT_EQ(a.find_first_not_of("0123456789abcdef"), std::string::npos);
}

}  // namespace
}  // namespace glint
