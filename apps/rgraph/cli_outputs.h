// The files a command writes, checked before it does any work: none may be one
// of its inputs or another of its outputs (after following links: the same
// inode, or the same resolved path for files that do not exist yet), and each
// must be writable (its folder exists and takes a new file). Writing itself is
// rgraph::writeOutputFile (rgraph/output_file.h).
#pragma once

#include <string>
#include <vector>

namespace rgraph::cli {

// A file named on the command line, with what named it ("--out", "the pipeline", "s.txt:3: screenshot").
struct NamedPath {
  std::string role;
  std::string path;
  // Outputs of a repeatable kind (screenshots) may name one file again among
  // themselves: the later one replaces the earlier, as asked.
  bool repeatable = false;
};

// Prints `error: ROLE 'PATH' ...` (both roles when two files are one) for the
// first problem and returns false; empty paths are skipped, inputs that are
// not files (a procedural scene name) too.
bool checkOutputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

}  // namespace rgraph::cli
