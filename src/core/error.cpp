// Failure path of GLINT_CHECK: reports the broken invariant and aborts.
#include "core/error.h"

#include <cstdio>
#include <cstdlib>

#include "core/cluster.h"

namespace glint {

void checkFailed(const char* condition, const char* file, int line, const std::string& message) {
  // To the stderr this process started with: a rank other than 0 of an MPI job has its
  // own silenced (core/cluster.h).
  cluster::reportError(std::string("glint: internal check failed at ") + file + ":" + std::to_string(line) + ": " +
                       condition + (message.empty() ? "" : ": ") + message);
  std::abort();
}

}  // namespace glint
