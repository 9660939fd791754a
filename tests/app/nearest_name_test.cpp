// Edit distance and the "did you mean" suggestions of the command line.
#include "app/nearest_name.h"

#include <gtest/gtest.h>

namespace glint {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsSubstitutionsAndSwaps) {
  EXPECT_EQ(editDistance("", ""), 0u);
  EXPECT_EQ(editDistance("--iter", "--iters"), 1u);
  EXPECT_EQ(editDistance("kitten", "sitting"), 3u);
  EXPECT_EQ(editDistance("train", "trian"), 1u);  // one swap of neighbours
  EXPECT_EQ(editDistance("ab", "ba"), 1u);
  EXPECT_EQ(editDistance("abc", ""), 3u);
}

TEST(NearestName, SuggestsOnlyALikelyTypo) {
  const std::vector<std::string> flags = {"--iters", "--seed", "--threads", "--holdout", "-o"};
  EXPECT_EQ(nearestName("--iter", flags), "--iters");
  EXPECT_EQ(nearestName("--thread", flags), "--threads");
  EXPECT_EQ(nearestName("--sede", flags), "--seed");
  EXPECT_EQ(nearestName("--bogus-flag", flags), std::nullopt);
  EXPECT_EQ(nearestName("trian", {"synth", "train", "render"}), "train");
}

TEST(UnknownFlagMessage, NamesTheNearestFlagOfTheCommand) {
  CLI::App app;
  CLI::App* cmd = app.add_subcommand("train");
  int iters = 0;
  cmd->add_option("--iters", iters);
  cmd->add_option("-o,--output", iters);
  EXPECT_EQ(unknownFlagMessage(*cmd, "--iter=5"),
            "unknown flag --iter; did you mean --iters? (see glint train --help)");
  EXPECT_EQ(unknownFlagMessage(*cmd, "--zzzzzz"), "unknown flag --zzzzzz (see glint train --help)");
}

}  // namespace
}  // namespace glint
