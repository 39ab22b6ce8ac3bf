// The median of frame or pass times, as render --stats, the bench and the
// viewer's --stats report them (0 for none; the mean of the middle two for an
// even count).
#pragma once

#include <algorithm>
#include <vector>

namespace rgraph::cli {

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace rgraph::cli
