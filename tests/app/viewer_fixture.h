// A viewer server on a small scene for the tests of its HTTP routes: a temporary folder
// that stands for a run (with a web folder holding index.html and a symbolic link pointing
// out of it, and beside it a file the server must never serve), the server's output going
// to its viewer/ folder as `glint view RUN` sets it.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <httplib.h>

#include "app/viewer/access_policy.h"
#include "app/viewer/viewer_server.h"
#include "math/rng.h"

namespace glint::test {

constexpr const char* kSecret = "top-secret-contents";
// The fixture's cap on Gaussians: its 300 may be duplicated once, not twice.
constexpr size_t kFixtureMaxGaussians = 1000;

// A small scene: a cloud of Gaussians in the unit cube, some rough, some smooth.
inline GaussianScene smallScene(int count) {
  GaussianScene scene;
  scene.resize(size_t(count));
  Rng rng(7);
  for (int i = 0; i < count; ++i) {
    scene.position[size_t(i)] = Vec3f(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f - Vec3f(1.0f);
    scene.logScale[size_t(i)] = Vec3f(std::log(0.08f));
    scene.opacityLogit[size_t(i)] = 2.0f;
    scene.diffuse[size_t(i)] = Rgb(rng.uniform(), rng.uniform(), rng.uniform());
    scene.normal[size_t(i)] = Vec3f(0, 1, 0);
    scene.roughness[size_t(i)] = rng.uniform();
    scene.f0[size_t(i)] = Rgb(0.04f);
  }
  return scene;
}

class ServerFixture : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::temp_directory_path() /
            ("glint_viewer_test_" + std::to_string(::getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(root_);
    std::filesystem::create_directories(root_ / "web");
    std::ofstream(root_ / "web" / "index.html") << "<html>viewer</html>";
    std::ofstream(root_ / "secret.txt") << kSecret;
    std::filesystem::create_directory_symlink(root_, root_ / "web" / "outside");
    ViewerOptions options;
    options.width = 32, options.height = 24;
    options.maxSamples = 8;
    options.webRoot = root_ / "web";
    options.outputFolder = root_ / "viewer";
    options.lockFolder = root_;  // the run folder, as `glint view RUN` locks it while saving
    options.initialCamera.eye = Vec3d(0, 0, 4);
    options.maxGaussians = kFixtureMaxGaussians;
    server_ = std::make_unique<ViewerServer>(options, smallScene(300), TraceSettings{});
    port_ = server_->bind();
    server_->start();
  }
  void TearDown() override {
    server_.reset();
    std::filesystem::remove_all(root_);
  }

  // A client as the viewer's page is: it sends the token of the page's URL.
  httplib::Client pageClient() const {
    httplib::Client client("127.0.0.1", port_);
    client.set_default_headers({{kTokenHeader, server_->token()}});
    return client;
  }

  std::filesystem::path root_;
  std::unique_ptr<ViewerServer> server_;
  int port_ = 0;
};

}  // namespace glint::test
