// The --script parser (view_script.h).
#include "view_script.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace rgraph::view {
namespace {

std::vector<std::string> splitWords(const std::string& line) {
  std::vector<std::string> words;
  std::istringstream in(line);
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

bool toNumber(const std::string& text, float& out) {
  char* end = nullptr;
  out = std::strtof(text.c_str(), &end);
  return !text.empty() && end != text.c_str() && *end == '\0' && std::isfinite(out);
}

// Parses one non-empty, non-comment line into `c`; returns the error text, or "" when fine.
std::string parseLine(const std::vector<std::string>& w, ScriptCommand& c) {
  using K = ScriptCommand::Kind;
  const std::string& op = w[0];
  const size_t args = w.size() - 1;
  auto numbers = [&](size_t lo, size_t hi, const char* usage) -> std::string {
    if (args < lo || args > hi)
      return "'" + op + "' expects " + usage + ", got " + std::to_string(args) + " argument(s)";
    for (size_t i = 1; i < w.size(); ++i) {
      float v = 0;
      if (!toNumber(w[i], v)) return "'" + op + "': '" + w[i] + "' is not a number (expected " + usage + ")";
      c.numbers.push_back(v);
    }
    return "";
  };
  auto whole = [&](float lo, float hi) -> std::string {
    for (float v : c.numbers)
      if (v != std::floor(v) || v < lo || v > hi)
        return "'" + op + "' needs whole numbers from " + std::to_string(int(lo)) + " to " + std::to_string(int(hi));
    return "";
  };
  if (op == "camera") {
    c.kind = K::Camera;
    std::string e = numbers(6, 7, "PX PY PZ TX TY TZ [FOV]");
    if (e.empty() && c.numbers.size() == 7 && !(c.numbers[6] > 0 && c.numbers[6] < 180))
      e = "'camera': the field of view must be between 0 and 180 degrees";
    return e;
  }
  if (op == "wait") {
    c.kind = K::Wait;
    std::string e = numbers(1, 1, "a frame count");
    return e.empty() ? whole(0, 1000000) : e;
  }
  if (op == "resize") {
    c.kind = K::Resize;
    std::string e = numbers(2, 2, "W H");
    return e.empty() ? whole(1, 16384) : e;
  }
  if (op == "screenshot") {
    c.kind = K::Screenshot;
    if (args != 1) return "'screenshot' expects one FILE.png";
    c.words = {w[1]};
    return "";
  }
  if (op == "waitfile") {  // for tests that edit files while the viewer runs: wait until FILE exists
    c.kind = K::WaitFile;
    if (args != 1) return "'waitfile' expects one FILE";
    c.words = {w[1]};
    return "";
  }
  if (op == "ui") {
    c.kind = K::Ui;
    if (args != 1 || (w[1] != "on" && w[1] != "off")) return "'ui' expects on or off";
    c.words = {w[1]};
    return "";
  }
  if (op == "param") {
    c.kind = K::Param;
    if (args < 3) return "'param' expects PASS NAME JSON-VALUE";
    std::string value = w[3];
    for (size_t i = 4; i < w.size(); ++i) value += " " + w[i];  // a JSON value may contain spaces
    c.words = {w[1], w[2], value};
    return "";
  }
  if (op == "inspect") {  // the inspector's resource (or version), array layer and mip level
    c.kind = K::Inspect;
    if (args < 1 || args > 3) return "'inspect' expects RESOURCE [LAYER [MIP]]";
    c.words = {w[1]};
    for (size_t i = 2; i < w.size(); ++i) {
      float v = 0;
      if (!toNumber(w[i], v)) return "'inspect': '" + w[i] + "' is not a number (expected RESOURCE [LAYER [MIP]])";
      c.numbers.push_back(v);
    }
    while (c.numbers.size() < 2) c.numbers.push_back(0.0f);
    return whole(0, 65535);
  }
  if (op == "panel") {
    c.kind = K::Panel;
    if (args != 1 || (w[1] != "plan" && w[1] != "parameters" && w[1] != "shadows"))
      return "'panel' expects plan, parameters or shadows";
    c.words = {w[1]};
    return "";
  }
  if (op == "pick") {  // selects the object under window pixel X Y (from the top-left), as a click does
    c.kind = K::Pick;
    std::string e = numbers(2, 2, "X Y");
    return e.empty() ? whole(0, 65535) : e;
  }
  if (op == "time") {  // the animation clock, in seconds (>= 0)
    c.kind = K::Time;
    std::string e = numbers(1, 1, "SECONDS");
    if (e.empty() && c.numbers[0] < 0.0f) e = "'time' needs seconds >= 0";
    return e;
  }
  if (op == "play" || op == "pause") {  // the animation clock runs with the frames' wall time, or stops
    c.kind = op == "play" ? K::Play : K::Pause;
    return args ? "'" + op + "' takes no arguments" : "";
  }
  if (op == "quit") {
    c.kind = K::Quit;
    return args ? "'quit' takes no arguments" : "";
  }
  return "unknown command '" + op +
         "' (commands: camera, wait, waitfile, screenshot, ui, param, resize, inspect, panel, pick, time, play, "
         "pause, quit)";
}

}  // namespace

std::vector<ScriptCommand> parseScript(std::string_view text, const std::string& name, std::string& error) {
  std::vector<ScriptCommand> commands;
  std::istringstream in{std::string(text)};
  int lineNo = 0;
  for (std::string line; std::getline(in, line);) {
    ++lineNo;
    const std::vector<std::string> words = splitWords(line);
    if (words.empty() || words[0][0] == '#') continue;
    ScriptCommand c;
    c.line = lineNo;
    const std::string e = parseLine(words, c);
    if (!e.empty()) {
      error = name + ":" + std::to_string(lineNo) + ": error: " + e;
      return {};
    }
    commands.push_back(std::move(c));
  }
  return commands;
}

std::vector<ScriptCommand> loadScript(const std::string& path, std::string& error) {
  // Only a regular file: a folder opens and reads as empty text (a script that never quits), a FIFO blocks.
  std::error_code ec;
  const auto type = std::filesystem::status(path, ec).type();
  if (type != std::filesystem::file_type::regular) {
    const std::string why = type == std::filesystem::file_type::not_found   ? "no such file"
                            : type == std::filesystem::file_type::directory ? "it is a folder"
                            : ec                                            ? ec.message()
                                                                            : "not a regular file";
    error = path + ": error: cannot read the script file (" + why + ")";
    return {};
  }
  std::ifstream f(path);
  if (!f) {
    error = path + ": error: cannot read the script file (" + std::strerror(errno) + ")";
    return {};
  }
  std::stringstream ss;
  ss << f.rdbuf();
  return parseScript(ss.str(), path, error);
}

}  // namespace rgraph::view
