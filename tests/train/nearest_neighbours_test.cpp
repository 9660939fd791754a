// The k-d tree's neighbour distances against brute force, on spread, clustered and
// degenerate point sets, and their independence of the thread count.
#include "train/nearest_neighbours.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "math/rng.h"

namespace glint {
namespace {

std::vector<float> bruteForce(const std::vector<Vec3f>& points, int k) {
  std::vector<float> result(points.size(), 0.0f);
  for (size_t i = 0; i < points.size(); ++i) {
    std::vector<double> distances;
    for (size_t j = 0; j < points.size(); ++j)
      if (j != i) distances.push_back(length(Vec3d(points[j]) - Vec3d(points[i])));
    std::sort(distances.begin(), distances.end());
    size_t count = std::min(distances.size(), size_t(k));
    double sum = 0.0;
    for (size_t j = 0; j < count; ++j) sum += distances[j];
    result[i] = count == 0 ? 0.0f : float(sum / double(count));
  }
  return result;
}

void expectMatchesBruteForce(const std::vector<Vec3f>& points, int k) {
  std::vector<float> fast = meanNeighbourDistances(points, k), slow = bruteForce(points, k);
  ASSERT_EQ(fast.size(), slow.size());
  for (size_t i = 0; i < fast.size(); ++i) EXPECT_NEAR(fast[i], slow[i], 1e-6f * (1.0f + slow[i])) << i;
}

std::vector<Vec3f> randomBox(int count, uint64_t seed) {
  Rng rng = Rng::forKeys({seed});
  std::vector<Vec3f> points;
  for (int i = 0; i < count; ++i) points.push_back(Vec3f(rng.uniform(), 2.0f * rng.uniform(), 0.5f * rng.uniform()));
  return points;
}

TEST(MeanNeighbourDistances, MatchesBruteForceOnRandomPoints) {
  expectMatchesBruteForce(randomBox(1500, 1), 3);
  expectMatchesBruteForce(randomBox(700, 2), 1);
  expectMatchesBruteForce(randomBox(700, 3), 8);
}

TEST(MeanNeighbourDistances, MatchesBruteForceOnSurfacesWithOutliers) {
  // Points on two planes (as depth samples are) plus a few far-away strays and duplicates.
  Rng rng = Rng::forKeys({4});
  std::vector<Vec3f> points;
  for (int i = 0; i < 800; ++i) points.push_back(Vec3f(4.0f * rng.uniform(), 4.0f * rng.uniform(), 0.0f));
  for (int i = 0; i < 400; ++i) points.push_back(Vec3f(0.0f, 4.0f * rng.uniform(), 3.0f * rng.uniform()));
  for (int i = 0; i < 5; ++i) points.push_back(Vec3f(100.0f + 30.0f * float(i), -50.0f, 7.0f));
  points.push_back(points[10]);
  points.push_back(points[10]);
  expectMatchesBruteForce(points, 3);
}

TEST(MeanNeighbourDistances, SmallAndDegenerateSets) {
  EXPECT_TRUE(meanNeighbourDistances({}, 3).empty());
  EXPECT_EQ(meanNeighbourDistances({Vec3f(1.0f)}, 3), std::vector<float>{0.0f});
  // Fewer than k others: the mean over all of them.
  std::vector<Vec3f> three = {Vec3f(0.0f), Vec3f(1.0f, 0.0f, 0.0f), Vec3f(3.0f, 0.0f, 0.0f)};
  std::vector<float> d = meanNeighbourDistances(three, 3);
  EXPECT_FLOAT_EQ(d[0], 2.0f);
  EXPECT_FLOAT_EQ(d[1], 1.5f);
  EXPECT_FLOAT_EQ(d[2], 2.5f);
  // All points at one place.
  std::vector<Vec3f> same(50, Vec3f(0.25f));
  for (float v : meanNeighbourDistances(same, 3)) EXPECT_EQ(v, 0.0f);
}

TEST(MeanNeighbourDistances, IndependentOfTheThreadCount) {
  std::vector<Vec3f> points = randomBox(20000, 5);
  std::vector<float> one, two;
  {
    ThreadLimit limit(1);
    one = meanNeighbourDistances(points, 3);
  }
  {
    ThreadLimit limit(2);
    two = meanNeighbourDistances(points, 3);
  }
  EXPECT_EQ(one, two);
}

}  // namespace
}  // namespace glint
