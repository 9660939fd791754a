// Tests of ActivityScope: the innermost scope an exception leaves is remembered, new work
// forgets it, and unexpected exceptions become messages with that context.
#include "core/activity.h"

#include <gtest/gtest.h>

#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace glint {
namespace {

void failInside(const char* outer, const char* inner) {
  ActivityScope a(outer);
  ActivityScope b(inner);
  throw std::bad_alloc();
}

TEST(ActivityScope, RemembersTheInnermostScopeAnExceptionLeft) {
  try {
    failInside("training out/run", "reading out/run/scene.ply");
  } catch (const std::bad_alloc&) {
  }
  EXPECT_EQ(failedActivity(), "reading out/run/scene.ply");
}

TEST(ActivityScope, NewWorkForgetsAHandledFailure) {
  try {
    failInside("a", "b");
  } catch (const std::bad_alloc&) {
  }
  { ActivityScope next("rendering view 3"); }
  EXPECT_EQ(failedActivity(), "");
}

TEST(ActivityScope, DescribeRenamesThePhase) {
  try {
    ActivityScope loop("training step 0");
    loop.describe("training step 17");
    throw std::runtime_error("x");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(failedActivity(), "training step 17");
}

TEST(ActivityScope, ScopesLeftNormallyRecordNothing) {
  { ActivityScope done("loading"); }
  EXPECT_EQ(failedActivity(), "");
}

TEST(DescribeUnexpectedException, AllocationFailuresSayOutOfMemoryWithTheActivity) {
  std::string message;
  try {
    failInside("synth", "importing big.gltf");
  } catch (const std::bad_alloc& e) {
    message = describeUnexpectedException(e);
  }
  EXPECT_EQ(message.rfind("out of memory while importing big.gltf (this machine has ", 0), 0u) << message;
  EXPECT_EQ(message.find("bad_alloc"), std::string::npos) << message;
}

TEST(DescribeUnexpectedException, OversizedContainersCountAsOutOfMemory) {
  std::string message;
  try {
    ActivityScope scope("reading points.ply");
    std::vector<double> v;
    v.resize(v.max_size() + 1);  // throws length_error ("vector::_M_default_append")
  } catch (const std::length_error& e) {
    message = describeUnexpectedException(e);
  }
  EXPECT_EQ(message.rfind("out of memory while reading points.ply", 0), 0u) << message;
  EXPECT_EQ(message.find("_M_default_append"), std::string::npos) << message;
}

TEST(DescribeUnexpectedException, OtherExceptionsKeepTheirTextAndGainTheActivity) {
  std::string message;
  try {
    ActivityScope scope("resuming out/run");
    throw std::invalid_argument("stoll");
  } catch (const std::invalid_argument& e) {
    message = describeUnexpectedException(e);
  }
  EXPECT_EQ(message, "stoll (while resuming out/run)");
}

}  // namespace
}  // namespace glint
