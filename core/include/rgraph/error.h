#pragma once
#include <stdexcept>
#include <string>

namespace rgraph {
// Runtime failures a user can cause (missing file, shader compile error, bad
// glTF, no GL context). Caught by the CLI, printed, exit code 1.
class RuntimeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
}  // namespace rgraph
