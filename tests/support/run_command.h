// Runs a shell command and captures what it prints: the CLI tests' one way
// to call the rgraph binary (header-only, so GL-free test programs use it too).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace rgraph::testsupport {

struct CommandResult {
  int exitCode = -1;  // -1: it could not start, or ended by a signal
  std::string out;    // stdout (append " 2>&1" to the command for stderr too)

  // The output's non-empty lines: a one-line error is lines().size() == 1.
  std::vector<std::string> lines() const {
    std::vector<std::string> v;
    std::istringstream s(out);
    for (std::string l; std::getline(s, l);)
      if (!l.empty()) v.push_back(l);
    return v;
  }
  bool has(const std::string& text) const { return out.find(text) != std::string::npos; }
};

inline CommandResult runCommand(const std::string& command) {
  CommandResult r;
  FILE* p = popen(command.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(p);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace rgraph::testsupport
