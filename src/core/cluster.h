// The processes of one job started by an MPI launcher (mpirun, srun): which one this is, how
// many there are, and the few collective operations training, rendering and synthesis use.
// A process that no launcher started, or a build without MPI, is a job of one process, and
// every operation below is then the identity (docs/cluster.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace glint::cluster {

// Joins the job when a launcher started this process (its environment says so: OpenMPI's
// OMPI_COMM_WORLD_SIZE, PMIx's PMIX_RANK or PMI's PMI_RANK), else does nothing. Call once,
// first thing in main. On a rank other than 0, also silences stdout and stderr: rank 0 speaks
// for the job, and errors go to reportError, which writes to the original stderr.
void join(int* argc, char*** argv);
// Leaves the job (MPI_Finalize) after the last collective; from main, on success.
void leave();
// Writes `message` and a newline to this process's original stderr, prefixed with the rank
// in a job of several ("rank 1 of 2: ").
void reportError(const std::string& message);
// Ends every process of the job with `code` (MPI_Abort): after an error on one rank, the
// others may be waiting in a collective forever. Exits normally in a job of one.
[[noreturn]] void abortJob(int code);

int rank();
int size();
inline bool isRoot() { return rank() == 0; }
inline bool distributed() { return size() > 1; }
// Whether this build can join an MPI job at all.
bool builtWithMpi();

// Sums `values` element-wise over the ranks, adding in rank order ((v_0 + v_1) + v_2 ...), and
// leaves the sum on every rank: the same bits on every rank and in every run. Each rank sends
// and receives about 2 (N-1)/N of the array (a reduce-scatter, then an all-gather).
void sumInRankOrder(std::span<float> values);
void sumInRankOrder(std::span<double> values);
void sumInRankOrder(std::span<int64_t> values);

// Every rank's bytes, in rank order, on every rank.
std::vector<std::vector<std::byte>> allGather(std::span<const std::byte> mine);
// Every rank's bytes, in rank order, on rank 0 (an empty list elsewhere).
std::vector<std::vector<std::byte>> gatherToRoot(std::span<const std::byte> mine);
// Rank 0's bytes on every rank (any size; the other ranks' contents are replaced).
void broadcast(std::vector<std::byte>* bytes);
// Rank 0's value of a flag, on every rank (e.g. a stop request that only rank 0 heard).
bool broadcastFlag(bool value);
// Waits for every rank.
void barrier();

// Rank 0's vector of trivially copyable values, on every rank.
template <typename T>
void broadcastVector(std::vector<T>* values) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (!distributed()) return;
  std::vector<std::byte> bytes;
  if (isRoot()) {
    bytes.resize(values->size() * sizeof(T));
    if (!bytes.empty()) std::memcpy(bytes.data(), values->data(), bytes.size());
  }
  broadcast(&bytes);
  values->resize(bytes.size() / sizeof(T));
  if (!bytes.empty()) std::memcpy(values->data(), bytes.data(), bytes.size());
}

// The share of `count` items (views, rays) that rank `r` of `n` takes: the contiguous range
// [count r / n, count (r + 1) / n).
struct Share {
  int64_t begin = 0, end = 0;
};
inline Share shareOf(int64_t count, int r, int n) {
  return {count * r / n, count * (r + 1) / n};
}
inline Share myShare(int64_t count) { return shareOf(count, rank(), size()); }

}  // namespace glint::cluster
