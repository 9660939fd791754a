// The exchange of an MPI training job's gradients: every rank traced its share of the batch
// into its own per-Gaussian sums, and every rank needs their total, added in rank order so
// that every rank (and every run) holds the same bits and takes the same Adam step.
#pragma once

#include <cstdint>
#include <span>

#include "raytrace/gaussian_gradients.h"

namespace glint {

// Training uses Dense unless `glint train --exchange sparse`: bench/cluster_bench measured
// it faster at 100k and 500k Gaussians on one machine (the sparse exchange moves 2.4 to 4.4
// times fewer bytes, but finding, packing and adding the rows costs more than that saves
// through shared memory); its model has sparse ahead at 500k Gaussians on 10 Gbit/s links
// (README, "Running on a cluster").
enum class ExchangeMode {
  Dense,   // every Gaussian's entries: a reduce-scatter and an all-gather of the arrays
  Sparse,  // only the Gaussians some ray of the rank touched: an all-gather of (index, entries) rows
};

struct ExchangeStats {
  bool sparse = false;     // which exchange ran
  uint64_t touched = 0;    // Gaussians with a non-zero entry, summed over the ranks
  uint64_t bytesIn = 0;    // bytes this rank received (the model of the exchange, not MPI's count)
  double seconds = 0;      // wall time of the exchange on this rank
};

// Replaces `gradient` and `extra` (one float per Gaussian, e.g. the densification score; may
// be empty) by their sums over the ranks, added in rank order: the same bits whichever mode
// runs. In a job of one process it does nothing and reports nothing.
ExchangeStats sumOverRanks(GaussianGradients& gradient, std::span<float> extra, ExchangeMode mode);

// Floats per Gaussian that travel: every parameter's components, the blend weight, and the
// extra array when there is one.
int exchangeWidth(bool withExtra);

}  // namespace glint
