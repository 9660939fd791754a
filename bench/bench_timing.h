// Wall-clock timing shared by the benchmark programs.
#pragma once

#include <chrono>
#include <functional>

namespace glint {

// Seconds f takes to run, by the steady clock.
inline double secondsOf(const std::function<void()>& f) {
  auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace glint
