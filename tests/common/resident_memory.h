// The resident memory of the test process, for tests that bound what a workload may grow.
#pragma once

#include <cstdlib>
#include <fstream>
#include <string>

namespace glint::test {

// VmRSS of /proc/self/status in kB (-1 when unreadable).
inline long residentKilobytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  return -1;
}

}  // namespace glint::test
