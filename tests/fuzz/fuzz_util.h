// Shared by the fuzz targets (RGRAPH_FUZZ=ON builds only; docs/fuzzing.md).
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <spdlog/spdlog.h>
#include <unistd.h>

namespace rgraph::fuzz {

// A bug, not a user error: print why and abort so libFuzzer keeps the input.
[[noreturn]] inline void fail(const std::string& why) {
  std::fprintf(stderr, "rgraph fuzz: %s\n", why.c_str());
  std::abort();
}

// RGRAPH_FUZZ_VERBOSE=1: the targets say what became of each input (refused
// with which message, or loaded), for looking at seeds and reproducers.
inline bool verbose() {
  static const bool on = [] {
    const char* v = std::getenv("RGRAPH_FUZZ_VERBOSE");
    return v && *v && std::string(v) != "0";
  }();
  return on;
}

// Warnings are expected for most inputs; printing them would cost more than
// the parse and bury libFuzzer's own output.
inline void quietLogs() { spdlog::set_level(spdlog::level::off); }

// A fresh directory of this process, removed at exit: the base directory for
// relative file references in fuzzed scenes and glTF files, so that they
// resolve to what the target puts there instead of to whatever the working
// directory holds.
inline const char* privateBaseDir() {
  // A plain array, not a std::string: the exit handler must not outlive it.
  static char dir[4096] = {0};
  if (dir[0] == 0) {
    const std::string pattern = (std::filesystem::temp_directory_path() / "rgraph-fuzz-XXXXXX").string();
    if (pattern.size() >= sizeof dir) fail("temp directory path too long: " + pattern);
    pattern.copy(dir, sizeof dir - 1);
    if (!mkdtemp(dir)) {
      std::perror("rgraph fuzz: mkdtemp");
      std::abort();
    }
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(dir, ec);
    });
  }
  return dir;
}

}  // namespace rgraph::fuzz
