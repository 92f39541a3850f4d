#pragma once
// Wall-clock seconds for results, progress lines and summaries.
#include <chrono>

namespace strictmin {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace strictmin
