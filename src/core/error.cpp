// Failure path of GLINT_CHECK: reports the broken invariant and aborts.
#include "core/error.h"

#include <cstdio>
#include <cstdlib>

namespace glint {

void checkFailed(const char* condition, const char* file, int line, const std::string& message) {
  std::fprintf(stderr, "glint: internal check failed at %s:%d: %s%s%s\n", file, line, condition,
               message.empty() ? "" : ": ", message.c_str());
  std::abort();
}

}  // namespace glint
