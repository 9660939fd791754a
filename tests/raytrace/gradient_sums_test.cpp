// The GPU's per-Gaussian gradient sums (raytrace/gradient_sums.h) run on the CPU: records
// sorted by Gaussian and summed run by run, and hit by hit adds, both give the bits of
// GaussianGradients::add in record order, through the flat layout and its copy back.
#include "raytrace/gradient_sums.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <numeric>
#include <vector>

#include "math/rng.h"

namespace glint {
namespace {

HitGradient<float> randomGradient(Rng& rng) {
  auto u = [&] { return 2.0f * rng.uniform() - 1.0f; };
  HitGradient<float> g;
  g.v_position = {u(), u(), u()};
  g.v_rotation = {u(), u(), u(), u()};
  g.v_logScale = {u(), u(), u()};
  g.v_opacityLogit = u();
  g.v_diffuse = {u(), u(), u()};
  g.v_normal = {u(), u(), u()};
  g.v_roughness = u();
  g.v_f0 = {u(), u(), u()};
  g.weight = rng.uniform();
  return g;
}

template <typename V>
bool sameBytes(const std::vector<V>& a, const std::vector<V>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(V)) == 0;
}

struct Records {
  std::vector<HitGradient<float>> gradients;
  std::vector<uint32_t> ids;
  std::vector<float> sigmaMax;
};

// 20,000 hits on 300 Gaussians, recorded through RecordSink as jobs of 1 to 40 hits.
Records randomRecords(size_t gaussians) {
  Rng rng(91);
  Records r;
  r.gradients.resize(20000);
  r.ids.resize(20000);
  for (size_t i = 0; i < gaussians; ++i) r.sigmaMax.push_back(0.01f + rng.uniform());
  uint32_t first = 0;
  while (first < r.gradients.size()) {
    const uint32_t hits = std::min<uint32_t>(1 + rng.uniformInt(40), uint32_t(r.gradients.size()) - first);
    RecordSink sink{r.gradients.data(), r.ids.data(), first};
    for (uint32_t k = 0; k < hits; ++k) sink(rng.uniformInt(uint32_t(gaussians)), randomGradient(rng));
    EXPECT_EQ(sink.next, first + hits);
    first += hits;
  }
  return r;
}

TEST(GradientSums, SortedRunsGiveTheSumsInRecordOrder) {
  const size_t n = 300;
  const Records records = randomRecords(n);
  // The reference: GaussianGradients::add and the split score, in record order.
  GaussianGradients reference;
  reference.reset(n);
  std::vector<float> referenceScore(n, 0.0f);
  for (size_t k = 0; k < records.ids.size(); ++k) {
    reference.add(records.ids[k], records.gradients[k]);
    referenceScore[records.ids[k]] += splitScore(records.gradients[k], records.sigmaMax[records.ids[k]]);
  }
  // The GPU's sorted path, with std::stable_sort for CUB's (stable) radix sort.
  std::vector<uint32_t> order(records.ids.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return records.ids[a] < records.ids[b]; });
  std::vector<uint32_t> sortedIds(order.size());
  for (size_t r = 0; r < order.size(); ++r) sortedIds[r] = records.ids[order[r]];
  std::vector<float> flat(n * kSumFloatsPerGaussian, 0.0f);
  const GradientSums sums = GradientSums::in(flat.data(), n, records.sigmaMax.data());
  for (uint32_t r = 0; r < order.size(); ++r)
    sumSortedRun(sortedIds.data(), order.data(), records.gradients.data(), uint32_t(order.size()), r, sums);
  GaussianGradients sorted;
  std::vector<float> sortedScore;
  copySums(flat, n, /*scored=*/true, &sorted, &sortedScore);
  for (size_t p = 0; p < reference.values.size(); ++p)
    EXPECT_TRUE(sameBytes(sorted.values[p], reference.values[p])) << "parameter " << p;
  EXPECT_TRUE(sameBytes(sorted.weight, reference.weight));
  EXPECT_TRUE(sameBytes(sortedScore, referenceScore));

  // Hit by hit (the atomic path's adds, here in record order): the same bits.
  std::vector<float> flatHits(n * kSumFloatsPerGaussian, 0.0f);
  const GradientSums hitSums = GradientSums::in(flatHits.data(), n, records.sigmaMax.data());
  for (size_t k = 0; k < records.ids.size(); ++k) {
    const uint32_t id = records.ids[k];
    forEachSum(hitSums, id, records.gradients[k], hitScore(hitSums, id, records.gradients[k]),
               [](float* at, float value) { *at += value; });
  }
  EXPECT_TRUE(sameBytes(flatHits, flat));
}

TEST(GradientSums, WithoutSigmaMaxNoScoresAreKept) {
  const size_t n = 4;
  std::vector<float> flat(n * kSumFloatsPerGaussian, 0.0f);
  const GradientSums sums = GradientSums::in(flat.data(), n, nullptr);
  Rng rng(3);
  const HitGradient<float> g = randomGradient(rng);
  forEachSum(sums, 2, g, hitScore(sums, 2, g), [](float* at, float value) { *at += value; });
  GaussianGradients gradient;
  std::vector<float> score{7.0f};
  copySums(flat, n, /*scored=*/false, &gradient, &score);
  EXPECT_EQ(score, std::vector<float>(n, 0.0f));
  EXPECT_EQ(gradient.weight[2], g.weight);
  EXPECT_EQ(gradient.of(&GaussianScene::rotation)[8], g.v_rotation.w);
  EXPECT_EQ(gradient.of(&GaussianScene::f0)[8], g.v_f0.z);
  EXPECT_EQ(flat[n * (kSumFloatsPerGaussian - 1) + 2], 0.0f) << "no score summed";
}

}  // namespace
}  // namespace glint
