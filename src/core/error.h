// Typed errors for bad user input, and cheap always-on invariant checks.
#pragma once

#include <stdexcept>
#include <string>

namespace glint {

// An error the user can act on: names the file (if any) and what was wrong with it.
// Thrown at I/O and validation boundaries, caught once at the command line and printed
// without a stack trace. Never thrown inside per-ray kernels.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
  Error(const std::string& file, const std::string& problem)
      : std::runtime_error(file + ": " + problem), file_(file) {}

  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

[[noreturn]] void checkFailed(const char* condition, const char* file, int line, const std::string& message);

}  // namespace glint

// Always-on check for cheap invariants (programming errors, not user input).
#define GLINT_CHECK(cond, ...)                                                  \
  do {                                                                          \
    if (!(cond)) ::glint::checkFailed(#cond, __FILE__, __LINE__, std::string(__VA_ARGS__)); \
  } while (0)

// Debug-only check for hot loops.
#ifdef NDEBUG
#define GLINT_DCHECK(cond, ...) \
  do {                          \
  } while (0)
#else
#define GLINT_DCHECK(cond, ...) GLINT_CHECK(cond, __VA_ARGS__)
#endif
