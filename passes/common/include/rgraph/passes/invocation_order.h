// The compute passes' invocation permutation (shaders/include/invocation.glsl):
// a test gives a pass's parameters kPermuteParam = 1..kPermutations (or
// kOrderDependent) and the pass compiles its compute programs with
// RGRAPH_PERMUTE_INVOCATIONS set to it, so that each invocation does another's
// work; the output must not change (tests/tiled/invocation_order_test.cpp).
// The parameter is not declared: a pipeline file cannot set it (validate
// refuses an unknown parameter), only C++ that edits PipelineConfig::params.
#pragma once

#include <string>
#include <vector>

#include "rgraph/params.h"

namespace rgraph::invocations {

constexpr const char* kPermuteParam = "permute_invocations";
constexpr int kPermutations = 4;     // 1..4: bijections (reverse, rotate, transpose, groups reversed)
constexpr int kOrderDependent = 5;   // rotated, lists appended in atomic order: changes the output

// Adds RGRAPH_PERMUTE_INVOCATIONS=<n> when `p` sets the parameter to n != 0.
inline void addPermuteDefine(const ParamSet& p, std::vector<std::string>& defines) {
  if (const int64_t n = p.getInt(kPermuteParam, 0)) defines.push_back("RGRAPH_PERMUTE_INVOCATIONS=" + std::to_string(n));
}

}  // namespace rgraph::invocations
