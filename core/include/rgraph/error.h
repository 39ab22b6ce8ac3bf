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

// A RuntimeError whose message already starts with where and what it is
// (`FILE:LINE: error: ...`, e.g. a shader the driver refuses): front ends
// print it as it is, without an "error: " of their own in front.
class LocatedError : public RuntimeError {
 public:
  using RuntimeError::RuntimeError;
};
}  // namespace rgraph
