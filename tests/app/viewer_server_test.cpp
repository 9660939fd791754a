// The viewer server under abuse: thousands of malformed and random requests (bad JSON,
// oversized bodies, path traversal, out-of-range and non-finite numbers, unknown
// endpoints, wrong methods) must each get the right 4xx answer, never leak a file outside
// the web folder, and leave the server answering valid requests with bounded memory.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "app/viewer/static_files.h"
#include "app/viewer_fixture.h"
#include "common/resident_memory.h"
#include "math/rng.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::kSecret;
using test::residentKilobytes;
using test::ServerFixture;

std::string randomBytes(Rng& rng, size_t n) {
  std::string s(n, '\0');
  for (char& c : s) c = char(rng.uniformInt(256));
  return s;
}

TEST(StaticFiles, ResolvesOnlyPlainPathsInsideTheFolder) {
  fs::path root = fs::temp_directory_path() / ("glint_static_test_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "web" / "sub");
  std::ofstream(root / "web" / "index.html") << "x";
  std::ofstream(root / "web" / "sub" / "a.js") << "x";
  std::ofstream(root / "secret.txt") << "x";
  fs::create_symlink(root / "secret.txt", root / "web" / "link.txt");
  fs::path web = root / "web";
  EXPECT_EQ(resolveStaticFile(web, "/"), fs::canonical(web / "index.html"));
  EXPECT_EQ(resolveStaticFile(web, "/sub/a.js"), fs::canonical(web / "sub" / "a.js"));
  for (const char* bad : {"/../secret.txt", "/sub/../../secret.txt", "/link.txt", "//etc/passwd", "/sub/", "/.hidden",
                          "relative", "/sub\\a.js", "/%2e%2e/secret.txt", "/missing.html"})
    EXPECT_FALSE(resolveStaticFile(web, bad)) << bad;
  fs::remove_all(root);
}

TEST_F(ServerFixture, SurvivesTenThousandMalformedRequests) {
  httplib::Client client = pageClient();
  client.set_keep_alive(true);
  client.set_tcp_nodelay(true);
  client.set_read_timeout(10, 0);

  // Warm up (first frames, allocator pools), then take the memory baseline.
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(client.Get("/api/state"));
  long baseline = residentKilobytes();
  ASSERT_GT(baseline, 0);

  const std::string posts[] = {"/api/camera", "/api/settings", "/api/edits/apply", "/api/edits/preview",
                               "/api/edits/save", "/api/edits/export"};
  const std::string traversals[] = {"/../secret.txt", "/%2e%2e/secret.txt", "/..%2fsecret.txt",
                                    "/%2E%2E%2Fsecret.txt", "/outside/secret.txt", "/web/../../secret.txt",
                                    "/....//secret.txt", "/%252e%252e/secret.txt", "/.%2e/secret.txt"};
  const std::string badBodies[] = {
      "", "{", "[]", "null", "42", "\"x\"", "{\"eye\": [0, 0]}", "{\"eye\": [1e400, 0, 0]}",
      "{\"eye\": [NaN, 0, 0], \"forward\": [0,0,-1], \"up\": [0,1,0], \"fov_x\": 1}",
      "{\"eye\": [0,0,0], \"forward\": [0,0,0], \"up\": [0,1,0], \"fov_x\": 1}",
      "{\"eye\": [0,0,0], \"forward\": [0,1,0], \"up\": [0,1,0], \"fov_x\": 1}",
      "{\"eye\": [0,0,0], \"forward\": [0,0,-1], \"up\": [0,1,0], \"fov_x\": 100}",
      "{\"bounces\": -1}", "{\"bounces\": 1000000}", "{\"bounces\": 1.5}", "{\"exposure\": 1e308}",
      "{\"mode\": \"../../etc\"}", "{\"mode\": 3}", "{\"mode\": \"bounce9\"}", "{\"mode\": \"bounce0\"}",
      "{\"mode\": \"bounce-1\"}", "{\"mode\": \"bounce\"}", "{\"mode\": \"bounce8\"}", "{\"denoise\": \"yes\"}", "{\"unknown\": 1}",
      "{\"selection\": {\"box\": {\"min\": [0,0,0], \"max\": [1e400,1,1]}}, \"operation\": {\"op\": \"delete\"}}",
      "{\"selection\": {\"sphere\": {\"center\": [0,0,0], \"radius\": -1}}, \"operation\": {\"op\": \"delete\"}}",
      "{\"selection\": \"everything\", \"operation\": {\"op\": \"explode\"}}",
      "{\"selection\": \"everything\", \"operation\": {\"op\": \"roughness\", \"set\": \"high\"}}",
      "{\"selection\": \"everything\", \"attribute\": \"mass\"}",
      "{\"selection\": \"everything\", \"bins\": 100000}",
      "{\"name\": \"../../escape.json\"}", "{\"name\": \"/tmp/x.ply\"}", "{\"name\": \".hidden.json\"}",
  };

  Rng rng(2024);
  constexpr int kRequests = 10000;
  for (int i = 0; i < kRequests; ++i) {
    uint32_t kind = rng.uniformInt(8);
    std::optional<httplib::Result> result;
    int expected = 0;  // 0: any 4xx
    switch (kind) {
      case 0: {  // random bytes as a body
        const std::string& path = posts[rng.uniformInt(std::size(posts))];
        result = client.Post(path.c_str(), randomBytes(rng, 1 + rng.uniformInt(200)), "application/json");
        break;
      }
      case 1: {  // structurally wrong or out-of-range JSON
        const std::string& path = posts[rng.uniformInt(std::size(posts))];
        result = client.Post(path.c_str(), badBodies[rng.uniformInt(std::size(badBodies))], "application/json");
        break;
      }
      case 2: {  // oversized bodies (rarely: each is 100 kB)
        if (rng.uniformInt(10) != 0) continue;
        result = client.Post("/api/camera", std::string(100 * 1024, '['), "application/json");
        expected = 413;
        break;
      }
      case 3: {  // path traversal, plain and encoded
        result = client.Get(traversals[rng.uniformInt(std::size(traversals))].c_str());
        expected = 404;
        break;
      }
      case 4: {  // unknown endpoints and random paths
        std::string path = "/api/" + std::to_string(rng.nextUint());
        result = rng.uniformInt(2) ? client.Get(path.c_str()) : client.Post(path.c_str(), "{}", "application/json");
        expected = 404;
        break;
      }
      case 5: {  // wrong methods
        uint32_t which = rng.uniformInt(3);
        if (which == 0) result = client.Put("/api/camera", "{}", "application/json");
        if (which == 1) result = client.Delete("/api/settings");
        if (which == 2) result = client.Get("/api/edits/apply");
        break;
      }
      case 6: {  // bad query parameters of the frame endpoint
        const char* queries[] = {"/api/frame?after=-1", "/api/frame?after=abc", "/api/frame?format=gif",
                                 "/api/frame?after=999999999999999999999"};
        result = client.Get(queries[rng.uniformInt(4)]);
        expected = 400;
        break;
      }
      default: {  // valid requests in between must still work
        double x = rng.uniform() * 2 - 1;
        nlohmann::json camera = {{"eye", {x, 0.2, 4}}, {"forward", {-x * 0.2, 0, -1}}, {"up", {0, 1, 0}}, {"fov_x", 0.9}};
        httplib::Result valid = client.Post("/api/camera", camera.dump(), "application/json");
        ASSERT_TRUE(valid) << "request " << i;
        ASSERT_EQ(valid->status, 200) << valid->body;
        continue;
      }
    }
    ASSERT_TRUE(result && *result) << "request " << i << " of kind " << kind << " got no answer";
    const httplib::Response& answer = **result;
    if (expected != 0)
      ASSERT_EQ(answer.status, expected) << "request " << i << " of kind " << kind << ": " << answer.body;
    else
      ASSERT_TRUE(answer.status >= 400 && answer.status < 500)
          << "request " << i << " of kind " << kind << ": " << answer.status << " " << answer.body;
    ASSERT_EQ(answer.body.find(kSecret), std::string::npos);
    ASSERT_TRUE(nlohmann::json::accept(answer.body)) << "error answers are JSON: " << answer.body;
  }

  // Nothing escaped the output folder and the server still answers properly.
  EXPECT_FALSE(fs::exists(root_.parent_path() / "escape.json"));
  auto state = client.Get("/api/state");
  ASSERT_TRUE(state);
  EXPECT_EQ(state->status, 200);
  EXPECT_EQ(nlohmann::json::parse(state->body)["edits"]["operations"], 0);
  auto page = client.Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->body, "<html>viewer</html>");
  auto frame = client.Get("/api/frame?format=png");
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->status, 200);
  EXPECT_EQ(frame->get_header_value("Content-Type"), "image/png");
  long grown = residentKilobytes() - baseline;
  if (test::kMemoryIsMeasurable) {
    EXPECT_LT(grown, 64 * 1024) << "resident memory grew by " << grown << " kB over the requests";
  }
}

// Bounce modes exist up to the bounce count: beyond it, or beyond kMaxBounces, a request is
// refused with a JSON error and the settings stay; lowering the bounces below the shown
// bounce needs a new mode in the same request.
TEST_F(ServerFixture, BounceModesStayWithinTheBounceCount) {
  httplib::Client client = pageClient();
  auto post = [&](const char* body) {
    httplib::Result r = client.Post("/api/settings", body, "application/json");
    EXPECT_TRUE(r);
    return r ? std::pair{r->status, nlohmann::json::parse(r->body)} : std::pair{0, nlohmann::json()};
  };
  auto [ok, shown] = post(R"({"bounces": 2, "mode": "bounce2"})");
  ASSERT_EQ(ok, 200) << shown;
  EXPECT_EQ(shown["mode"], "bounce2");
  for (const char* bad : {R"({"mode": "bounce3"})", R"({"bounces": 1})", R"({"bounces": 8, "mode": "bounce9"})",
                          R"({"mode": "bounce02"})"}) {
    auto [status, error] = post(bad);
    EXPECT_EQ(status, 400) << bad;
    EXPECT_TRUE(error.contains("error") && error["error"].get<std::string>().find("bounce") != std::string::npos)
        << bad << ": " << error;
  }
  auto state = client.Get("/api/state");
  ASSERT_TRUE(state);
  nlohmann::json settings = nlohmann::json::parse(state->body)["settings"];
  EXPECT_EQ(settings["mode"], "bounce2");
  EXPECT_EQ(settings["bounces"], 2);
  auto [lowered, now] = post(R"({"bounces": 1, "mode": "bounce1"})");
  EXPECT_EQ(lowered, 200) << now;
  EXPECT_EQ(now["mode"], "bounce1");
  // A frame still arrives in the bounce mode.
  auto frame = client.Get("/api/frame?format=png");
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->status, 200);
}

// An edit that keeps the count lets the render thread go of the shown scene and refits it in
// place when that is measured cheaper; the answer says which update was kept and its costs.
TEST_F(ServerFixture, EditsReportTheTracerUpdateTheyChose) {
  httplib::Client client = pageClient();
  ASSERT_TRUE(client.Get("/api/frame"));  // the render thread is busy with the scene
  auto edit = [&](const char* body) {
    httplib::Result r = client.Post("/api/edits/apply", body, "application/json");
    EXPECT_TRUE(r);
    EXPECT_EQ(r ? r->status : 0, 200) << (r ? r->body : "");
    return r ? nlohmann::json::parse(r->body)["tracer_update"] : nlohmann::json();
  };
  nlohmann::json update = edit(R"({"selection": "everything", "operation": {"op": "roughness", "set": 0.2}})");
  EXPECT_TRUE(update["refit_possible"].get<bool>()) << update;
  EXPECT_TRUE(update["action"] == "refit" || update["action"] == "rebuild") << update;
  EXPECT_GT(update["rebuild_ms"].get<double>(), 0.0);
  EXPECT_GT(update["refit_probe_ms"].get<double>(), 0.0);
  update = edit(R"({"selection": "everything", "operation": {"op": "duplicate", "offset": [0, 0, 0.1]}})");
  EXPECT_FALSE(update["refit_possible"].get<bool>()) << update;
  EXPECT_EQ(update["action"], "rebuild");
  // The renderer shows the edited scene again.
  auto state = client.Get("/api/state");
  ASSERT_TRUE(state);
  EXPECT_EQ(nlohmann::json::parse(state->body)["gaussians"], 600);
  auto frame = client.Get("/api/frame");
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->status, 200);
}

TEST_F(ServerFixture, AccumulatesSamplesWhenTheCameraRests) {
  httplib::Client client = pageClient();
  uint64_t after = 0;
  int samples = 0;
  for (int i = 0; i < 100 && samples < 8; ++i) {
    auto frame = client.Get(("/api/frame?after=" + std::to_string(after)).c_str());
    ASSERT_TRUE(frame);
    ASSERT_EQ(frame->status, 200);
    after = std::stoull(frame->get_header_value("X-Glint-Frame"));
    samples = std::stoi(frame->get_header_value("X-Glint-Samples"));
  }
  EXPECT_EQ(samples, 8);  // the budget of the fixture
  // A camera change starts over: the next frames are low-resolution ones (0 samples).
  // The fixture's scene is so small that the renderer may have accumulated the whole budget
  // again before the next request arrives; it then has published at least a quarter-size,
  // a half-size and a full-size frame since `after`.
  auto moved = client.Post("/api/camera", R"({"eye": [0.5, 0, 4], "forward": [0, 0, -1], "up": [0, 1, 0], "fov_x": 0.9})",
                           "application/json");
  ASSERT_TRUE(moved);
  ASSERT_EQ(moved->status, 200);
  auto frame = client.Get(("/api/frame?after=" + std::to_string(after)).c_str());
  ASSERT_TRUE(frame);
  const int samplesNow = std::stoi(frame->get_header_value("X-Glint-Samples"));
  const uint64_t frameNow = std::stoull(frame->get_header_value("X-Glint-Frame"));
  EXPECT_GT(frameNow, after);
  EXPECT_TRUE(samplesNow < 8 || frameNow >= after + 3)
      << "frame " << frameNow << " with " << samplesNow << " samples, after frame " << after;
}

}  // namespace
}  // namespace glint
