// Dense and sparse exchanges of per-Gaussian sums over the ranks of an MPI job.
#include "train/gradient_exchange.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <vector>

#include "core/cluster.h"
#include "core/parallel.h"

namespace glint {

namespace {

// One array that travels: `components` floats per Gaussian.
struct Column {
  std::span<float> values;
  int components = 1;
};

std::vector<Column> columnsOf(GaussianGradients& gradient, std::span<float> extra) {
  std::vector<Column> columns;
  forEachParameter([&](const auto& p) { columns.push_back({gradient.values[p.index], p.components}); });
  columns.push_back({gradient.weight, 1});
  if (!extra.empty()) columns.push_back({extra, 1});
  return columns;
}

// Whether Gaussian i has a non-zero entry in some column (a ray of this rank touched it).
bool touched(const std::vector<Column>& columns, size_t i) {
  for (const Column& c : columns)
    for (int k = 0; k < c.components; ++k)
      if (c.values[i * size_t(c.components) + size_t(k)] != 0.0f) return true;
  return false;
}

// This rank's touched Gaussians as rows of a uint32 index and `width` floats.
std::vector<std::byte> touchedRows(const std::vector<Column>& columns, size_t n, int width) {
  // The touched indices in increasing order: each chunk of Gaussians counts its own, then
  // writes them after the chunks before it.
  constexpr int64_t kChunk = 16384;
  const int64_t chunks = (int64_t(n) + kChunk - 1) / kChunk;
  std::vector<size_t> firstOfChunk(size_t(chunks) + 1, 0);
  parallelFor(chunks, 1, [&](int64_t c) {
    size_t count = 0;
    for (size_t i = size_t(c * kChunk); i < std::min(n, size_t((c + 1) * kChunk)); ++i) count += touched(columns, i);
    firstOfChunk[size_t(c) + 1] = count;
  });
  for (size_t c = 0; c < size_t(chunks); ++c) firstOfChunk[c + 1] += firstOfChunk[c];
  std::vector<uint32_t> ids(firstOfChunk.back());
  parallelFor(chunks, 1, [&](int64_t c) {
    size_t at = firstOfChunk[size_t(c)];
    for (size_t i = size_t(c * kChunk); i < std::min(n, size_t((c + 1) * kChunk)); ++i)
      if (touched(columns, i)) ids[at++] = uint32_t(i);
  });
  const size_t rowBytes = sizeof(uint32_t) + size_t(width) * sizeof(float);
  std::vector<std::byte> rows(ids.size() * rowBytes);
  parallelForChunks(int64_t(ids.size()), 4096, [&](int64_t begin, int64_t end) {
    for (int64_t r = begin; r < end; ++r) {
      std::byte* row = rows.data() + size_t(r) * rowBytes;
      const uint32_t i = ids[size_t(r)];
      std::memcpy(row, &i, sizeof(i));
      float* out = reinterpret_cast<float*>(row + sizeof(uint32_t));
      for (const Column& c : columns)
        for (int k = 0; k < c.components; ++k) *out++ = c.values[size_t(i) * size_t(c.components) + size_t(k)];
    }
  });
  return rows;
}

// Every rank's rows added, rank after rank, into the zeroed columns. Rows of one rank name
// distinct Gaussians, so each rank's rows are added in parallel.
void addRows(const std::vector<std::vector<std::byte>>& perRank, std::vector<Column>& columns, int width) {
  for (Column& c : columns) std::fill(c.values.begin(), c.values.end(), 0.0f);
  const size_t rowBytes = sizeof(uint32_t) + size_t(width) * sizeof(float);
  for (const std::vector<std::byte>& rows : perRank) {
    const int64_t count = int64_t(rows.size() / rowBytes);
    parallelForChunks(count, 4096, [&](int64_t begin, int64_t end) {
      for (int64_t r = begin; r < end; ++r) {
        const std::byte* row = rows.data() + size_t(r) * rowBytes;
        uint32_t i;
        std::memcpy(&i, row, sizeof(i));
        const float* in = reinterpret_cast<const float*>(row + sizeof(uint32_t));
        for (Column& c : columns)
          for (int k = 0; k < c.components; ++k) c.values[size_t(i) * size_t(c.components) + size_t(k)] += *in++;
      }
    });
  }
}

}  // namespace

int exchangeWidth(bool withExtra) {
  int width = 1;  // the blend weight
  forEachParameter([&](const auto& p) { width += p.components; });
  return width + (withExtra ? 1 : 0);
}

ExchangeStats sumOverRanks(GaussianGradients& gradient, std::span<float> extra, ExchangeMode mode) {
  ExchangeStats stats;
  if (!cluster::distributed()) return stats;
  const auto start = std::chrono::steady_clock::now();
  const size_t n = gradient.size();
  const int width = exchangeWidth(!extra.empty());
  const int N = cluster::size();
  std::vector<Column> columns = columnsOf(gradient, extra);

  stats.sparse = mode == ExchangeMode::Sparse;
  if (stats.sparse) {
    const uint64_t rowBytes = sizeof(uint32_t) + uint64_t(width) * sizeof(float);
    const std::vector<std::byte> rows = touchedRows(columns, n, width);
    const std::vector<std::vector<std::byte>> all = cluster::allGather(rows);
    for (const std::vector<std::byte>& r : all) stats.touched += r.size() / rowBytes;
    stats.bytesIn = (stats.touched - rows.size() / rowBytes) * rowBytes;
    addRows(all, columns, width);
  } else {
    for (Column& c : columns) cluster::sumInRankOrder(c.values);
    stats.bytesIn = 2 * uint64_t(N - 1) * uint64_t(n) * uint64_t(width) * sizeof(float) / uint64_t(N);
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace glint
