// Fuzz target: plugin file bytes -> "" (looks loadable) or a reason to refuse
// (rgraph::checkPluginImage, run before dlopen; never dlopens anything).
//
// Beyond "no crash, no sanitizer report, no exception": the verdict is
// deterministic (it depends on the bytes only).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include "fuzz_util.h"
#include "rgraph/plugin_file_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string verdict = rgraph::checkPluginImage(data, size);
  if (rgraph::checkPluginImage(data, size) != verdict) rgraph::fuzz::fail("two verdicts for the same bytes");
  if (rgraph::fuzz::verbose()) std::fprintf(stderr, "%s\n", verdict.empty() ? "accepted" : verdict.c_str());
  return 0;
}
