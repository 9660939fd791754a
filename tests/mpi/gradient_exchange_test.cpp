// Tests of the MPI collectives training relies on, run by CTest under `mpirun -np 3`: sums
// in rank order (uneven blocks included) and both gradient exchanges give, on every rank, the
// bits of adding every rank's values one rank after another. Every rank can make every other
// rank's values from its seed, so each checks the result alone.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/cluster.h"
#include "math/rng.h"
#include "train/gradient_exchange.h"

namespace glint {
namespace {

// Rank r's gradients of n Gaussians: about a third of them touched (non-zero), the rest 0.
GaussianGradients gradientsOf(int r, size_t n) {
  GaussianGradients g;
  g.reset(n);
  Rng rng(1234 + uint64_t(r));
  for (size_t i = 0; i < n; ++i) {
    if (rng.uniform() > 0.35f) continue;
    for (auto& values : g.values)
      for (size_t k = values.size() / n * i; k < values.size() / n * (i + 1); ++k) values[k] = rng.uniform() - 0.5f;
    g.weight[i] = rng.uniform();
  }
  return g;
}

// The sum one process would make: rank 0's values, plus rank 1's, plus rank 2's ...
GaussianGradients sequentialSum(size_t n) {
  GaussianGradients total = gradientsOf(0, n);
  for (int r = 1; r < cluster::size(); ++r) total.addRange(gradientsOf(r, n), 0, n);
  return total;
}

void expectSameBits(const GaussianGradients& a, const GaussianGradients& b) {
  for (size_t p = 0; p < a.values.size(); ++p) EXPECT_EQ(a.values[p], b.values[p]) << "parameter " << p;
  EXPECT_EQ(a.weight, b.weight);
}

TEST(ClusterMpi, RunsUnderALauncher) { EXPECT_GE(cluster::size(), 2) << "run this test with mpirun -np 2 or more"; }

TEST(ClusterMpi, SumsInRankOrderWithUnevenBlocks) {
  for (size_t n : {size_t(0), size_t(1), size_t(7), size_t(1001)}) {
    std::vector<double> mine(n), expected(n, 0.0);
    for (size_t i = 0; i < n; ++i) mine[i] = 1.0 / double(i + 1 + cluster::rank());
    for (size_t i = 0; i < n; ++i) {
      double sum = 1.0 / double(i + 1);
      for (int r = 1; r < cluster::size(); ++r) sum += 1.0 / double(i + 1 + r);
      expected[i] = sum;
    }
    cluster::sumInRankOrder(std::span<double>(mine));
    EXPECT_EQ(mine, expected) << n;
  }
}

TEST(ClusterMpi, DenseAndSparseExchangesGiveTheSequentialSum) {
  const size_t n = 5003;
  const GaussianGradients expected = sequentialSum(n);
  for (ExchangeMode mode : {ExchangeMode::Dense, ExchangeMode::Sparse}) {
    GaussianGradients mine = gradientsOf(cluster::rank(), n);
    ExchangeStats stats = sumOverRanks(mine, {}, mode);
    EXPECT_EQ(stats.sparse, mode == ExchangeMode::Sparse);
    EXPECT_GT(stats.bytesIn, 0u);
    expectSameBits(mine, expected);
  }
}

TEST(ClusterMpi, BroadcastsRankZerosBytes) {
  std::vector<int> values;
  if (cluster::isRoot()) values = {3, 1, 4, 1, 5};
  cluster::broadcastVector(&values);
  EXPECT_EQ(values, (std::vector<int>{3, 1, 4, 1, 5}));
  EXPECT_TRUE(cluster::broadcastFlag(cluster::isRoot()));
}

}  // namespace
}  // namespace glint

int main(int argc, char** argv) {
  glint::cluster::join(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int failed = RUN_ALL_TESTS();
  // The job fails when any rank's tests failed (rank 0's output is the one shown).
  int64_t failures[1] = {failed != 0 ? 1 : 0};
  glint::cluster::sumInRankOrder(std::span<int64_t>(failures, 1));
  glint::cluster::leave();
  return failures[0] != 0 ? 1 : 0;
}
