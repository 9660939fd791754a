// The resident memory of the test process, for tests that bound what a workload may grow.
#pragma once

#include <cstdlib>
#include <fstream>
#include <string>

namespace glint::test {

// AddressSanitizer reserves terabytes of shadow address space and keeps freed memory in
// quarantine, so address-space caps fail and resident figures mean nothing under it
// (make test-sanitize): tests bounding memory check it in the plain build only.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kMemoryIsMeasurable = false;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kMemoryIsMeasurable = false;
#else
inline constexpr bool kMemoryIsMeasurable = true;
#endif
#else
inline constexpr bool kMemoryIsMeasurable = true;
#endif

// VmRSS of /proc/self/status in kB (-1 when unreadable).
inline long residentKilobytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  return -1;
}

}  // namespace glint::test
