// rgraph view --script: one command per line, parsed before the window opens
// (so a bad script exits 1 with FILE:LINE and opens nothing). GL-free.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rgraph::view {

struct ScriptCommand {
  enum class Kind { Camera, Wait, WaitFile, Screenshot, Ui, Param, Resize, Inspect, Panel, Pick, Time, Play, Pause, Quit };
  Kind kind = Kind::Quit;
  int line = 0;
  // camera: 6 (or 7 with fov); wait: 1; resize: 2; inspect: layer, mip; pick: x, y; time: seconds
  std::vector<float> numbers;
  // screenshot, waitfile: file; ui: on|off; param: pass, name, JSON value; inspect: resource; panel: its tab
  std::vector<std::string> words;
};

// Parses script text; `name` is the file named in messages. On the first
// error returns {} and sets error to "NAME:LINE: error: ...".
std::vector<ScriptCommand> parseScript(std::string_view text, const std::string& name, std::string& error);
// Reads and parses a script file ("FILE: error: cannot read" when unreadable).
std::vector<ScriptCommand> loadScript(const std::string& path, std::string& error);

}  // namespace rgraph::view
