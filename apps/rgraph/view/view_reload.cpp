// File watching and the status file (view_reload.h).
#include "view_reload.h"

#include <nlohmann/json.hpp>

#include "rgraph/error.h"
#include "rgraph/gl/objects.h"
#include "rgraph/output_file.h"

namespace rgraph::view {

FileWatcher::Time FileWatcher::timeOf(const std::string& file) {
  std::error_code ec;
  const Time t = std::filesystem::last_write_time(file, ec);
  return ec ? Time::min() : t;  // a missing file has its own "time": its return is a change
}

void FileWatcher::watch(const std::vector<std::string>& files) {
  std::map<std::string, Time> times;
  for (const auto& f : files) {
    auto known = times_.find(f);
    times[f] = known != times_.end() ? known->second : timeOf(f);  // known files keep their baseline
  }
  times_ = std::move(times);
}

bool FileWatcher::changed() {
  bool any = false;
  for (auto& [file, time] : times_) {
    const Time now = timeOf(file);
    if (now != time) {
      time = now;
      any = true;
    }
  }
  return any;
}

void StatusFile::write(const std::string& event, bool ok, const std::vector<std::string>& diagnostics) const {
  if (path_.empty()) return;
  nlohmann::json line = {{"event", event}, {"result", ok ? "ok" : "error"}};
  if (!ok) line["diagnostics"] = diagnostics;
  line["gl_objects"] = gl::liveObjectsTotal();
  // Every line checked (a full disk once went unnoticed); the first failure
  // ends the viewer with the reason, once.
  appendToFile(path_, line.dump() + "\n", "the status file");
}

}  // namespace rgraph::view
