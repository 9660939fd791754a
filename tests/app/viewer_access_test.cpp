// Issue 19: any web page could drive the viewer and destroy a run. Requests naming another
// Host or coming from another site's page are refused, so are POSTs without a JSON body or
// the launch's token, save and export never touch a file of the run, and an edit beyond
// the Gaussian cap is refused with the scene kept.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "app/viewer/access_policy.h"
#include "app/viewer_fixture.h"
#include "common/locking_child.h"
#include "core/folder_lock.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::ServerFixture;

constexpr const char* kDeleteEverything = R"({"selection": "everything", "operation": {"op": "delete"}})";

std::string errorOf(const httplib::Result& result) {
  if (!result) return "(no answer)";
  nlohmann::json body = nlohmann::json::parse(result->body, nullptr, /*allow_exceptions=*/false);
  return body.is_object() && body.contains("error") ? body["error"].get<std::string>() : "(not a JSON error)";
}

int gaussiansShown(httplib::Client& client) {
  httplib::Result state = client.Get("/api/state");
  return state && state->status == 200 ? nlohmann::json::parse(state->body)["gaussians"].get<int>() : -1;
}

std::string contents(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

TEST_F(ServerFixture, RefusesAForeignHostEvenForReading) {
  httplib::Client client = pageClient();
  // A rebinding DNS name resolves to 127.0.0.1 but the browser still names it in Host.
  for (const char* host : {"attacker.example", "attacker.example:80", "localhost.attacker.example"}) {
    httplib::Result state = client.Get("/api/state", {{"Host", host}});
    ASSERT_TRUE(state) << host;
    EXPECT_EQ(state->status, 403) << host;
    EXPECT_NE(errorOf(state).find("Host"), std::string::npos) << state->body;
    EXPECT_EQ(state->body.find("camera"), std::string::npos) << "the state leaked: " << state->body;
    httplib::Result page = client.Get("/", {{"Host", host}});
    ASSERT_TRUE(page);
    EXPECT_EQ(page->status, 403) << host;
  }
  // The server's own names answer.
  for (std::string host : {"127.0.0.1", "localhost", "LOCALHOST"}) {
    httplib::Result state = client.Get("/api/state", {{"Host", host + ":" + std::to_string(port_)}});
    ASSERT_TRUE(state) << host;
    EXPECT_EQ(state->status, 200) << host << ": " << state->body;
  }
}

TEST_F(ServerFixture, RefusesRequestsFromAnotherSitesPage) {
  httplib::Client client = pageClient();
  httplib::Result edit = client.Post("/api/edits/apply", {{"Origin", "https://attacker.example"}}, kDeleteEverything,
                                     "application/json");
  ASSERT_TRUE(edit);
  EXPECT_EQ(edit->status, 403);
  EXPECT_NE(errorOf(edit).find("origin"), std::string::npos) << edit->body;
  httplib::Result read = client.Get("/api/state", {{"Origin", "null"}});
  ASSERT_TRUE(read);
  EXPECT_EQ(read->status, 403);
  // The page's own origin is welcome.
  std::string own = "http://127.0.0.1:" + std::to_string(port_);
  httplib::Result mine = client.Post("/api/camera", {{"Origin", own}},
                                     R"({"eye": [0, 0, 4], "forward": [0, 0, -1], "up": [0, 1, 0], "fov_x": 0.9})",
                                     "application/json");
  ASSERT_TRUE(mine);
  EXPECT_EQ(mine->status, 200) << mine->body;
  EXPECT_EQ(gaussiansShown(client), 300);
}

// A cross-site form or fetch "no-cors" can send text/plain without a preflight: the
// request the issue used to delete every Gaussian.
TEST_F(ServerFixture, RefusesPostsThatAreNotJson) {
  httplib::Client client = pageClient();
  for (const char* type : {"text/plain", "application/x-www-form-urlencoded", "multipart/form-data; boundary=x", ""}) {
    httplib::Result edit = client.Post("/api/edits/apply", kDeleteEverything, type);
    ASSERT_TRUE(edit) << type;
    EXPECT_EQ(edit->status, 415) << type << ": " << edit->body;
    EXPECT_NE(errorOf(edit).find("application/json"), std::string::npos) << edit->body;
  }
  EXPECT_EQ(gaussiansShown(client), 300);
  httplib::Result charset = client.Post("/api/camera", R"({"eye": [0, 0, 4], "forward": [0, 0, -1], "up": [0, 1, 0],
                                         "fov_x": 0.9})", "application/json; charset=utf-8");
  ASSERT_TRUE(charset);
  EXPECT_EQ(charset->status, 200) << charset->body;
}

TEST_F(ServerFixture, StateChangingRequestsNeedTheLaunchToken) {
  httplib::Client anonymous("127.0.0.1", port_);
  httplib::Client wrong("127.0.0.1", port_);
  wrong.set_default_headers({{kTokenHeader, std::string(server_->token().size(), '0')}});
  for (httplib::Client* client : {&anonymous, &wrong}) {
    for (const char* path : {"/api/edits/apply", "/api/edits/undo", "/api/edits/save", "/api/edits/export",
                             "/api/camera", "/api/settings", "/api/edits/preview"}) {
      httplib::Result result = client->Post(path, path == std::string("/api/edits/apply") ? kDeleteEverything : "{}",
                                            "application/json");
      ASSERT_TRUE(result) << path;
      EXPECT_EQ(result->status, 403) << path << ": " << result->body;
      EXPECT_NE(errorOf(result).find(kTokenHeader), std::string::npos) << result->body;
    }
  }
  EXPECT_EQ(gaussiansShown(anonymous), 300);  // reading needs no token
  EXPECT_FALSE(fs::exists(root_ / "viewer"));
  // The printed URL carries the token the page sends back.
  EXPECT_NE(server_->url().find("?token=" + server_->token()), std::string::npos) << server_->url();
  EXPECT_EQ(server_->token().size(), 32u);
}

TEST_F(ServerFixture, SaveAndExportNeverReplaceTheRunsFiles) {
  // The files of a run beside the viewer's folder.
  const std::string scene = "ply of the trained scene", config = "{\"iters\": 30000}";
  std::ofstream(root_ / "scene.ply") << scene;
  std::ofstream(root_ / "config.json") << config;
  httplib::Client client = pageClient();
  using Request = std::pair<const char*, const char*>;  // the endpoint and the name asked for
  for (auto [path, name] : {Request{"/api/edits/save", "config.json"}, Request{"/api/edits/export", "scene.ply"},
                            Request{"/api/edits/save", "metrics.json"},
                            Request{"/api/edits/save", "transforms_train.json"},
                            Request{"/api/edits/save", "../config.json"}}) {
    httplib::Result result = client.Post(path, nlohmann::json{{"name", name}}.dump(), "application/json");
    ASSERT_TRUE(result) << name;
    EXPECT_TRUE(result->status == 403 || result->status == 400)
        << name << ": " << result->status << " " << result->body;
  }
  EXPECT_EQ(contents(root_ / "scene.ply"), scene);
  EXPECT_EQ(contents(root_ / "config.json"), config);
  EXPECT_FALSE(fs::exists(root_ / "viewer" / "config.json"));
  EXPECT_FALSE(fs::exists(root_ / "viewer" / "scene.ply"));

  // Other names go to the viewer's folder, and may be saved again.
  for (int i = 0; i < 2; ++i) {
    httplib::Result saved = client.Post("/api/edits/save", R"({"name": "mine.json"})", "application/json");
    ASSERT_TRUE(saved);
    EXPECT_EQ(saved->status, 200) << saved->body;
    httplib::Result exported = client.Post("/api/edits/export", "{}", "application/json");
    ASSERT_TRUE(exported);
    EXPECT_EQ(exported->status, 200) << exported->body;
  }
  EXPECT_TRUE(fs::exists(root_ / "viewer" / "mine.json"));
  EXPECT_TRUE(fs::exists(root_ / "viewer" / "viewer_edited.ply"));
  // A symbolic link planted in the viewer's folder is not followed.
  fs::create_symlink(root_ / "config.json", root_ / "viewer" / "link.json");
  httplib::Result linked = client.Post("/api/edits/save", R"({"name": "link.json"})", "application/json");
  ASSERT_TRUE(linked);
  EXPECT_EQ(linked->status, 403) << linked->body;
  EXPECT_EQ(contents(root_ / "config.json"), config);
}

// Issue 39: while another process (a `glint train --resume`) holds the run folder, a save
// or an export is refused with 409 naming it, and writes nothing.
TEST_F(ServerFixture, SavesAreRefusedWhileAnotherProcessHoldsTheRun) {
  const std::string lockFile = (root_ / kFolderLockName).string();
  // Another open of the lock file, as another program makes (a forked child would share this
  // process's lock); the fd stays open in the child, holding it.
  const test::LockingChild trainerProcess = test::holdLockInChild([&] {
    const int fd = open(lockFile.c_str(), O_RDWR | O_CREAT, 0644);
    return fd >= 0 && flock(fd, LOCK_EX | LOCK_NB) == 0;
  });
  const pid_t trainer = trainerProcess.pid;
  std::ofstream(lockFile) << "pid " << trainer << ", glint train, since now\n";  // what it says of itself
  httplib::Client client = pageClient();
  for (const char* path : {"/api/edits/save", "/api/edits/export"}) {
    httplib::Result result = client.Post(path, "{}", "application/json");
    ASSERT_TRUE(result) << path;
    EXPECT_EQ(result->status, 409) << path << ": " << result->body;
    EXPECT_NE(result->body.find("is in use by pid " + std::to_string(trainer)), std::string::npos) << result->body;
  }
  EXPECT_FALSE(fs::exists(root_ / "viewer" / "viewer_edits.json"));
  EXPECT_FALSE(fs::exists(root_ / "viewer" / "viewer_edited.ply"));
  test::finish(trainerProcess);
  httplib::Result saved = client.Post("/api/edits/save", "{}", "application/json");
  ASSERT_TRUE(saved);
  EXPECT_EQ(saved->status, 200) << saved->body;
}

TEST_F(ServerFixture, AnEditBeyondTheGaussianCapIsRefusedAndTheSceneKept) {
  httplib::Client client = pageClient();
  const char* duplicate = R"({"selection": "everything", "operation": {"op": "duplicate", "offset": [0, 0, 0.1]}})";
  httplib::Result once = client.Post("/api/edits/apply", duplicate, "application/json");
  ASSERT_TRUE(once);
  ASSERT_EQ(once->status, 200) << once->body;
  ASSERT_EQ(gaussiansShown(client), 600);
  httplib::Result twice = client.Post("/api/edits/apply", duplicate, "application/json");
  ASSERT_TRUE(twice);
  EXPECT_EQ(twice->status, 413) << twice->body;
  std::string message = errorOf(twice);
  EXPECT_NE(message.find("1200"), std::string::npos) << message;
  EXPECT_NE(message.find(std::to_string(test::kFixtureMaxGaussians)), std::string::npos) << message;
  EXPECT_EQ(gaussiansShown(client), 600);
  httplib::Result state = client.Get("/api/state");
  ASSERT_TRUE(state);
  EXPECT_EQ(nlohmann::json::parse(state->body)["edits"]["operations"], 1);
  // The viewer still renders and edits.
  httplib::Result frame = client.Get("/api/frame");
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->status, 200);
  httplib::Result undo = client.Post("/api/edits/undo", "{}", "application/json");
  ASSERT_TRUE(undo);
  EXPECT_EQ(undo->status, 200) << undo->body;
  EXPECT_EQ(gaussiansShown(client), 300);
}

}  // namespace
}  // namespace glint
