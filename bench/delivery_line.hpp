// The one line both sides of the radio link benchmark print
// (bench/radio_link.cpp, latsim's model; bench/radio_link_ns3.cpp, ns-3's):
//   frames=N mean_ms=M p50_ms=... p99_ms=... max_ms=... incomplete=K
// The quantiles are taken the same way on both sides, so that the lines
// compare. C++17: the ns-3 peer is built with g++ -std=c++17.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <vector>

namespace bench {

/// Prints the delivery times `ms` (milliseconds, one a frame delivered whole)
/// and the count of frames never delivered whole to stdout.
inline void print_delivery_line(std::vector<double> ms, unsigned long long incomplete) {
  std::sort(ms.begin(), ms.end());
  double sum = 0;
  for (double v : ms) sum += v;
  auto q = [&](double p) { return ms.empty() ? 0.0 : ms[std::min(ms.size() - 1, static_cast<size_t>(p * ms.size()))]; };
  std::printf("frames=%zu mean_ms=%.4f p50_ms=%.4f p99_ms=%.4f max_ms=%.4f incomplete=%llu\n", ms.size(),
              ms.empty() ? 0.0 : sum / static_cast<double>(ms.size()), q(0.5), q(0.99), ms.empty() ? 0.0 : ms.back(),
              incomplete);
}

}  // namespace bench
