// `glint view RUN` shows a run with the path settings it was trained with: the page starts
// at the run's bounces (not the viewer's own default of 2).
#include <gtest/gtest.h>

#include <httplib.h>
#include <nlohmann/json.hpp>

#include "app/viewer_fixture.h"

namespace glint {
namespace {

TEST(ViewerRunSettings, ThePageStartsAtTheRunsBounces) {
  ViewerOptions options;
  options.width = 16, options.height = 12;
  options.maxSamples = 2;
  options.token = "run-settings-test";
  options.path.bounces = 3;
  options.path.invalidNormalLength = 0.2f;
  ViewerServer server(options, test::smallScene(50), TraceSettings{});
  int port = server.bind();
  server.start();
  httplib::Client client("127.0.0.1", port);
  client.set_default_headers({{kTokenHeader, server.token()}});
  httplib::Result state = client.Get("/api/state");
  ASSERT_TRUE(state);
  ASSERT_EQ(state->status, 200) << state->body;
  EXPECT_EQ(nlohmann::json::parse(state->body)["settings"]["bounces"], 3);
}

}  // namespace
}  // namespace glint
