// The MPI job, or a job of one process (see cluster.h). Every MPI call of Glint is in this file.
#include "core/cluster.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/error.h"

#ifdef GLINT_HAVE_MPI
#include <mpi.h>
#endif

namespace glint::cluster {

namespace {

int gRank = 0;
int gSize = 1;
[[maybe_unused]] bool gJoined = false;  // MPI_Init was called (builds with MPI only)
int gErrorFd = STDERR_FILENO;  // the stderr this process started with

bool launchedByMpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

#ifdef GLINT_HAVE_MPI
// Collectives take int counts: larger arrays go in pieces of this many elements.
constexpr int64_t kPiece = int64_t(1) << 27;

template <typename T>
MPI_Datatype mpiType();
template <>
MPI_Datatype mpiType<float>() { return MPI_FLOAT; }
template <>
MPI_Datatype mpiType<double>() { return MPI_DOUBLE; }
template <>
MPI_Datatype mpiType<int64_t>() { return MPI_INT64_T; }

void check(int code, const char* what) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw Error(std::string("MPI ") + what + " failed: " + std::string(text, size_t(length)));
}

// The reduce-scatter and all-gather of sumInRankOrder, on one piece (fewer than 2^31 elements):
// block b of the piece, [n b / N, n (b + 1) / N), is summed by rank b from every rank's copy,
// in rank order, and then sent to all.
template <typename T>
void sumPiece(T* values, int64_t n) {
  const int N = gSize;
  std::vector<int> counts(static_cast<size_t>(N), 0), offsets(static_cast<size_t>(N), 0);
  for (int b = 0; b < N; ++b) {
    Share s = shareOf(n, b, N);
    offsets[size_t(b)] = int(s.begin);
    counts[size_t(b)] = int(s.end - s.begin);
  }
  const int mine = counts[size_t(gRank)];
  // Every rank's copy of my block, one after another in rank order.
  std::vector<T> copies(size_t(mine) * size_t(N));
  std::vector<int> receiveCounts(size_t(N), mine), receiveOffsets(static_cast<size_t>(N), 0);
  for (int s = 0; s < N; ++s) receiveOffsets[size_t(s)] = s * mine;
  check(MPI_Alltoallv(values, counts.data(), offsets.data(), mpiType<T>(), copies.data(), receiveCounts.data(),
                      receiveOffsets.data(), mpiType<T>(), MPI_COMM_WORLD),
        "all-to-all");
  T* block = values + offsets[size_t(gRank)];
  for (int i = 0; i < mine; ++i) {
    T sum = copies[size_t(i)];
    for (int s = 1; s < N; ++s) sum += copies[size_t(s) * size_t(mine) + size_t(i)];
    block[i] = sum;
  }
  check(MPI_Allgatherv(MPI_IN_PLACE, 0, mpiType<T>(), values, counts.data(), offsets.data(), mpiType<T>(),
                       MPI_COMM_WORLD),
        "all-gather");
}
#endif

template <typename T>
void sumAll(std::span<T> values) {
  if (!distributed()) return;
#ifdef GLINT_HAVE_MPI
  for (int64_t first = 0; first < int64_t(values.size()); first += kPiece)
    sumPiece(values.data() + first, std::min<int64_t>(kPiece, int64_t(values.size()) - first));
#endif
}

}  // namespace

void join(int* argc, char*** argv) {
#ifdef GLINT_HAVE_MPI
  if (gJoined || !launchedByMpi()) return;
  // Only the main thread calls MPI; the oneTBB workers never do.
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &gRank);
  MPI_Comm_size(MPI_COMM_WORLD, &gSize);
  // Errors come back as codes (check() turns them into Error), not as an abort inside MPI.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  gJoined = true;
  if (gRank != 0) {
    gErrorFd = dup(STDERR_FILENO);
    int quiet = open("/dev/null", O_WRONLY);
    if (quiet >= 0) {
      dup2(quiet, STDOUT_FILENO);
      dup2(quiet, STDERR_FILENO);
      close(quiet);
    }
  }
#else
  (void)argc;
  (void)argv;
  // Started by a launcher as one of several processes, each would run the whole job alone
  // and write the same files: refuse.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_NTASKS"}) {
    const char* value = std::getenv(name);
    if (value != nullptr && std::atoi(value) > 1 && launchedByMpi()) {
      std::fprintf(stderr, "glint: error: started as one of %s processes by an MPI launcher, but this glint was built "
                   "without MPI (install libopenmpi-dev and rebuild, or run it without mpirun)\n", value);
      std::exit(2);
    }
  }
#endif
}

void leave() {
#ifdef GLINT_HAVE_MPI
  if (gJoined) MPI_Finalize();
  gJoined = false;
#endif
}

void reportError(const std::string& message) {
  std::string line = distributed() ? "rank " + std::to_string(gRank) + " of " + std::to_string(gSize) + ": " : "";
  line += message + "\n";
  std::fflush(stderr);
  // One write, so that the lines of several ranks do not interleave.
  ssize_t written = write(gErrorFd, line.data(), line.size());
  (void)written;
}

void abortJob(int code) {
#ifdef GLINT_HAVE_MPI
  if (gJoined && gSize > 1) MPI_Abort(MPI_COMM_WORLD, code);
  leave();
#endif
  std::exit(code);
}

int rank() { return gRank; }
int size() { return gSize; }

bool builtWithMpi() {
#ifdef GLINT_HAVE_MPI
  return true;
#else
  return false;
#endif
}

void sumInRankOrder(std::span<float> values) { sumAll(values); }
void sumInRankOrder(std::span<double> values) { sumAll(values); }
void sumInRankOrder(std::span<int64_t> values) { sumAll(values); }

namespace {

// Every rank's bytes in rank order, on every rank (toRoot false) or on rank 0 alone (true:
// the other ranks get an empty list).
std::vector<std::vector<std::byte>> gatherBytes(std::span<const std::byte> mine, bool toRoot) {
  std::vector<std::vector<std::byte>> all;
  if (!distributed()) {
    all.emplace_back(mine.begin(), mine.end());
    return all;
  }
#ifdef GLINT_HAVE_MPI
  GLINT_CHECK(mine.size() < size_t(INT_MAX), "cluster: more than 2 GB gathered from one rank");
  const bool receives = !toRoot || isRoot();
  int length = int(mine.size());
  std::vector<int> lengths(static_cast<size_t>(gSize), 0), offsets(static_cast<size_t>(gSize), 0);
  if (toRoot)
    check(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "gather");
  else
    check(MPI_Allgather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, MPI_COMM_WORLD), "all-gather");
  int64_t total = 0;
  for (int r = 0; r < gSize; ++r) {
    offsets[size_t(r)] = int(total);
    total += lengths[size_t(r)];
  }
  GLINT_CHECK(!receives || total < int64_t(INT_MAX), "cluster: more than 2 GB gathered in all");
  std::vector<std::byte> joined(receives ? size_t(total) : 0);
  if (toRoot)
    check(MPI_Gatherv(mine.data(), length, MPI_BYTE, joined.data(), lengths.data(), offsets.data(), MPI_BYTE, 0,
                      MPI_COMM_WORLD),
          "gather");
  else
    check(MPI_Allgatherv(mine.data(), length, MPI_BYTE, joined.data(), lengths.data(), offsets.data(), MPI_BYTE,
                         MPI_COMM_WORLD),
          "all-gather");
  if (receives)
    for (int r = 0; r < gSize; ++r)
      all.emplace_back(joined.begin() + offsets[size_t(r)], joined.begin() + offsets[size_t(r)] + lengths[size_t(r)]);
#endif
  return all;
}

}  // namespace

std::vector<std::vector<std::byte>> allGather(std::span<const std::byte> mine) { return gatherBytes(mine, false); }

std::vector<std::vector<std::byte>> gatherToRoot(std::span<const std::byte> mine) { return gatherBytes(mine, true); }

void broadcast(std::vector<std::byte>* bytes) {
  if (!distributed()) return;
#ifdef GLINT_HAVE_MPI
  int64_t length = int64_t(bytes->size());
  check(MPI_Bcast(&length, 1, MPI_INT64_T, 0, MPI_COMM_WORLD), "broadcast");
  bytes->resize(size_t(length));
  for (int64_t first = 0; first < length; first += kPiece)
    check(MPI_Bcast(bytes->data() + first, int(std::min<int64_t>(kPiece, length - first)), MPI_BYTE, 0,
                    MPI_COMM_WORLD),
          "broadcast");
#endif
}

bool broadcastFlag(bool value) {
  if (!distributed()) return value;
#ifdef GLINT_HAVE_MPI
  int flag = value ? 1 : 0;
  check(MPI_Bcast(&flag, 1, MPI_INT, 0, MPI_COMM_WORLD), "broadcast");
  return flag != 0;
#else
  return value;
#endif
}

void barrier() {
#ifdef GLINT_HAVE_MPI
  if (distributed()) check(MPI_Barrier(MPI_COMM_WORLD), "barrier");
#endif
}

}  // namespace glint::cluster
