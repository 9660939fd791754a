// The launch shape every Glint kernel uses: blocks of kThreadsPerBlock threads, enough of
// them for n items (one thread each).
#pragma once

#include <cstddef>

namespace glint::cuda {

constexpr int kThreadsPerBlock = 128;

inline unsigned blocksFor(size_t n) { return unsigned((n + kThreadsPerBlock - 1) / kThreadsPerBlock); }

}  // namespace glint::cuda
