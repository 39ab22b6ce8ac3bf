#include "cli_outputs.h"

#include <sys/stat.h>

#include <iostream>
#include <optional>

#include "rgraph/output_file.h"

namespace rgraph::cli {
namespace {

// What two names of one file share: the inode when the file exists, else the
// path a write would create (links followed, folder canonical).
struct FileKey {
  std::optional<std::pair<dev_t, ino_t>> inode;
  bool device = false;  // exists and is not a regular file (/dev/null): written in place, never replaced
  std::string target;
};

FileKey keyOf(const std::string& path) {
  FileKey key;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    key.inode = std::make_pair(st.st_dev, st.st_ino);
    key.device = !S_ISREG(st.st_mode);
  }
  key.target = outputFileTarget(path);
  return key;
}

bool sameFile(const FileKey& a, const FileKey& b) {
  if (a.inode || b.inode) return a.inode == b.inode;
  return !a.target.empty() && a.target == b.target;
}

std::string quoted(const NamedPath& p) { return p.role + " '" + p.path + "'"; }

}  // namespace

bool checkOutputs(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  std::vector<std::pair<const NamedPath*, FileKey>> in, out;
  for (const auto& p : inputs) {
    struct stat st {};
    // Only existing files can be destroyed; a scene name like "thin" is not one.
    if (!p.path.empty() && ::stat(p.path.c_str(), &st) == 0) in.emplace_back(&p, keyOf(p.path));
  }
  for (const auto& p : outputs) {
    if (p.path.empty()) continue;
    FileKey key = keyOf(p.path);
    for (const auto& [input, inputKey] : in)
      if (sameFile(key, inputKey)) {
        std::cerr << "error: " << quoted(p) << " is " << quoted(*input)
                  << ": an output never replaces an input (write it elsewhere)\n";
        return false;
      }
    for (const auto& [earlier, earlierKey] : out)
      if (!(p.repeatable && earlier->repeatable) && !key.device && sameFile(key, earlierKey)) {
        std::cerr << "error: " << quoted(p) << " is " << quoted(*earlier)
                  << ": each output needs a file of its own\n";
        return false;
      }
    if (const std::string problem = outputFileProblem(p.path); !problem.empty()) {
      std::cerr << "error: " << quoted(p) << ": cannot be written: " << problem << "\n";
      return false;
    }
    out.emplace_back(&p, std::move(key));
  }
  return true;
}

}  // namespace rgraph::cli
