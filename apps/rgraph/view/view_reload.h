// Live reload for rgraph view: polls file modification times and appends one
// JSON line per load or reload to the --status file (docs/viewer.md).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace rgraph::view {

// Remembers the modification time of each watched file; changed() says
// whether any differs now (a file that appears, disappears or is replaced counts).
class FileWatcher {
 public:
  // Watches exactly `files`: new ones with their current times as the baseline, known ones keep theirs
  // (so calling it every poll misses no change).
  void watch(const std::vector<std::string>& files);
  // true when a file changed since watch() or the last changed() that returned true (which takes the new times).
  bool changed();

 private:
  using Time = std::filesystem::file_time_type;
  static Time timeOf(const std::string& file);
  std::map<std::string, Time> times_;
};

// `{"event": EVENT, "result": "ok"|"error", "diagnostics": [...], "gl_objects": N}` lines, appended and flushed.
class StatusFile {
 public:
  explicit StatusFile(std::string path) : path_(std::move(path)) {}
  // Throws RuntimeError naming the file and the OS's reason when it cannot be written.
  void write(const std::string& event, bool ok, const std::vector<std::string>& diagnostics) const;

 private:
  std::string path_;
};

}  // namespace rgraph::view
