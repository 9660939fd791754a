// Issue 19: small edit inputs must not grow without bound. A 2.7 kB edit file of 40
// duplications asked for 2^40 Gaussians, and a chain of 10^5 combined selections took
// memory growing with the square of its length (the cycle check copied the chain at every
// level) and recursed 10^5 deep. Now the duplication is refused before it allocates, with
// the file and the limit named, and a selection chain is checked and evaluated in linear
// time and memory.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "common/expect_error.h"
#include "common/resident_memory.h"
#include "edit/edit_file.h"
#include "edit/gaussian_edits.h"
#include "edit/gaussian_selection.h"
#include "io/temp_folder.h"

namespace glint {
namespace {

GaussianScene lineOfGaussians(size_t count) {
  GaussianScene scene;
  scene.resize(count);
  for (size_t i = 0; i < count; ++i) scene.position[i] = Vec3f(0.01f * float(i), 0, 0);
  return scene;
}

TEST(EditLimits, FortyDuplicationsAreRefusedNamingTheFileAndTheLimit) {
  nlohmann::json document = {
      {"glint_edits", 1}, {"selections", {{"all", "everything"}}}, {"operations", nlohmann::json::array()}};
  for (int i = 0; i < 40; ++i)
    document["operations"].push_back({{"op", "duplicate"}, {"selection", "all"}, {"offset", {0, 0, 0.001 * i}}});
  test::TempFolder folder;
  std::filesystem::path file = folder / "forty.json";
  std::ofstream(file) << document.dump();
  EditDocument edits = readEditFile(file);

  // 100 Gaussians double at each operation: the 7th would make 12800, over 10000.
  GaussianScene scene = lineOfGaussians(100);
  test::expectErrorNaming([&] { applyEdits(edits, scene, 10000); }, file,
                          {"operations[6] duplicate", "12800", "limit of 10000", "--max-gaussians"});
  EXPECT_EQ(scene.size(), 6400u);  // the operations before the refused one
  GaussianScene again = lineOfGaussians(100);
  EXPECT_THROW(applyEdits(edits, again, 10000), GaussianLimitError);  // the type the viewer answers 413 for
}

TEST(EditLimits, OperationsThatAddNothingApplyAboveTheLimit) {
  EditDocument edits = parseEditDocument(
      {{"glint_edits", 1}, {"selections", {{"all", "everything"}}},
       {"operations",
        {{{"op", "roughness"}, {"selection", "all"}, {"set", 0.5}}, {{"op", "delete"}, {"selection", "all"}}}}},
      "inline");
  GaussianScene scene = lineOfGaussians(50);
  EditReport report = applyEdits(edits, scene, 10);
  EXPECT_EQ(report.countAfter, 0u);
}

// A chain s1 = union(s0), s2 = union(s1), ... and a ladder d_k = union(d_{k-1}, d_{k-1}),
// which a plain recursive evaluation walks 2^k times.
nlohmann::json chainDocument(int length, int ladder) {
  nlohmann::json selections;
  selections["s0"]["box"] = {{"min", {-1, -1, -1}}, {"max", {0.5, 1, 1}}};
  for (int k = 1; k < length; ++k)
    selections["s" + std::to_string(k)] = {{"union", {"s" + std::to_string(k - 1)}}};
  selections["d0"] = {{"union", {"s" + std::to_string(length - 1)}}};
  for (int k = 1; k < ladder; ++k) {
    std::string previous = "d" + std::to_string(k - 1);
    selections["d" + std::to_string(k)] = {{"union", {previous, previous}}};
  }
  return {{"glint_edits", 1},
          {"selections", selections},
          {"operations",
           {{{"op", "translate"}, {"selection", "d" + std::to_string(ladder - 1)}, {"offset", {0, 1, 0}}}}}};
}

// Parses and applies a chain of 10^5 selections ending in a ladder of 60; exits 0 when it
// took under 5 s and 256 MB and selected the right Gaussians.
[[noreturn]] void applyLongChainAndExit() {
  rlimit cap{2L << 30, 2L << 30};
  setrlimit(RLIMIT_AS, &cap);
  nlohmann::json json = chainDocument(100000, 60);
  long before = test::residentKilobytes();
  auto start = std::chrono::steady_clock::now();
  EditDocument edits = parseEditDocument(json, "chain.json");
  GaussianScene scene = lineOfGaussians(1000);
  EditReport report = applyEdits(edits, scene);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  long grown = test::residentKilobytes() - before;
  size_t selected = report.operations.empty() ? 0 : report.operations[0].selected;
  std::fprintf(stderr, "chain of 10^5: %.2f s, %ld kB more resident, %zu selected\n", seconds, grown, selected);
  // The box holds x <= 0.5: Gaussians 0..50.
  std::exit(selected == 51 && seconds < 5.0 && grown < 256 * 1024 ? 0 : 1);
}

// In a child process whose address space is capped at 2 GB, so that a quadratic
// regression fails this test instead of exhausting the machine.
TEST(EditLimits, ALongSelectionChainIsCheckedAndEvaluatedInLinearTimeAndMemory) {
  if (!test::kMemoryIsMeasurable) GTEST_SKIP() << "an address-space cap cannot hold under AddressSanitizer";
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(applyLongChainAndExit(), ::testing::ExitedWithCode(0), "chain of 10\\^5");
}

TEST(EditLimits, ACycleIsStillNamedAlongItsChain) {
  nlohmann::json json = chainDocument(1000, 2);
  json["selections"]["s0"] = {{"union", {"s999"}}};
  try {
    parseEditDocument(json, "cycle.json");
    ADD_FAILURE() << "a cycle was accepted";
  } catch (const Error& e) {
    std::string message = e.what();
    EXPECT_NE(message.find("cycle"), std::string::npos) << message.substr(0, 200);
    EXPECT_NE(message.find("s1 -> s0 -> s999"), std::string::npos) << message.substr(0, 200);
  }
}

}  // namespace
}  // namespace glint
