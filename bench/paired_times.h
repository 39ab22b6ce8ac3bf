// Two ways of doing one thing timed turn about (a, b, a, b, ...), so that
// both see the same load on a shared machine: the figure to quote is the
// median of the per-pair ratios, not either one's time.
#pragma once

#include <benchmark/benchmark.h>

#include <algorithm>
#include <string>
#include <vector>

#include "../apps/rgraph/median.h"

namespace rgraph::bench {

struct PairedTimes {
  std::vector<double> a, b, ratio;  // milliseconds, and a / b per pair

  // One pair; the iteration's manual time is both together.
  void add(benchmark::State& state, double msA, double msB) {
    a.push_back(msA);
    b.push_back(msB);
    ratio.push_back(msA / msB);
    state.SetIterationTime((msA + msB) / 1000.0);
  }
  // Counters NAME_A_ms and NAME_B_ms (medians), speedup (the median a / b:
  // above 1, b is faster) and speedup_min (the smallest pair's).
  void report(benchmark::State& state, const std::string& nameA, const std::string& nameB) const {
    state.counters[nameA + "_ms"] = cli::median(a);
    state.counters[nameB + "_ms"] = cli::median(b);
    state.counters["speedup"] = cli::median(ratio);
    state.counters["speedup_min"] = ratio.empty() ? 0.0 : *std::min_element(ratio.begin(), ratio.end());
  }
};

}  // namespace rgraph::bench
