// Counts the GL calls this benchmark program makes, its own and those of
// librgraph, its passes and plugins: every GL entry point the sources name
// (bench/CMakeLists.txt lists them at configure time from core/, passes/,
// plugins/ and bench/, against GL/glcorearb.h) is defined in the program as a
// trampoline that adds one to its counter and jumps to libOpenGL's function
// (dlsym RTLD_NEXT), so calls from the shared library bind to it as well.
// Arguments and results pass through untouched (a tail jump). Only in this
// program; x86-64 ELF only (elsewhere available() is false and nothing is
// interposed). Cost: an add and an indirect jump per call, the same on every
// side a benchmark compares.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rgraph::bench {

struct GlCallCounter {
  static bool available();
  // Calls made since the program started, all entry points together.
  static uint64_t total();
  // Per entry point (those called at least once), for a breakdown.
  static std::vector<std::pair<std::string, uint64_t>> perFunction();
};

}  // namespace rgraph::bench
