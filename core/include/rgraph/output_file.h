// Writing output files (images, statistics, bench results, status lines) so
// that a failure is reported with the operating system's reason and never
// leaves a truncated file or a damaged earlier one. No GL.
#pragma once

#include <string>
#include <string_view>

namespace rgraph {

// Replaces the content of the file at `path` with `bytes`.
// - A new or regular file: the bytes go to a temporary file in the folder the
//   file really lives in (a symbolic link is followed, the link itself stays),
//   every write, the fsync and the close are checked, then the temporary is
//   renamed over the file (keeping an existing file's permission bits). On any
//   failure the temporary is removed and an earlier file is left as it was.
// - An existing file that is not regular (/dev/null, /dev/full, /dev/stdout,
//   a FIFO) is opened and written in place, every write and the close
//   checked: renaming would replace the device node or pipe itself.
// Throws rgraph::RuntimeError "cannot write WHAT PATH: REASON" (REASON as the
// OS says it, e.g. "No space left on device").
void writeOutputFile(const std::string& path, std::string_view bytes, const std::string& what = "file");

// Appends `bytes` to the file at `path` (created when missing), every write
// and the close checked; throws as writeOutputFile.
void appendToFile(const std::string& path, std::string_view bytes, const std::string& what = "file");

// Why writeOutputFile(path) would fail before anything is computed: "" when
// it looks writable, else the reason ("no such folder '/a/b'", "is a folder",
// "Permission denied", ...). A new file's folder is probed by creating and
// removing a temporary file in it.
std::string outputFileProblem(const std::string& path);

// The absolute path that writing `path` changes: symbolic links followed
// (dangling ones too), the folder canonical. Two names of one output give the
// same string even before the file exists. "" when it cannot be resolved (a
// link loop, an unreadable folder).
std::string outputFileTarget(const std::string& path);

}  // namespace rgraph
