#include "script.h"

#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace editor {
namespace {

// Each command's numbers after the frame: the counts it accepts.
const std::map<std::string, std::vector<size_t>> kArity = {
    {"move", {4}}, {"turn", {4}},      {"scale", {2, 4}},  {"color", {4, 5}}, {"hide", {1}},
    {"show", {1}}, {"remove", {1}},    {"duplicate", {1}}, {"select", {1}},   {"time", {1}},
    {"click", {2}}};

[[noreturn]] void fail(const std::string& where, const std::string& message) {
  throw std::runtime_error(where + ": " + message);
}

double numberFrom(const std::string& word, const std::string& where) {
  size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(word, &used);
  } catch (const std::exception&) {
  }
  if (used == 0 || used != word.size() || !std::isfinite(v)) fail(where, "'" + word + "' is not a number");
  return v;
}

size_t whole(double v, const std::string& what, const std::string& where) {
  if (v < 0 || v != std::floor(v) || v > 1e9) fail(where, what + " must be a whole number >= 0, not " + std::to_string(v));
  return size_t(v);
}

glm::vec3 vec3From(const std::vector<double>& n, size_t first) {
  return {float(n[first]), float(n[first + 1]), float(n[first + 2])};
}

}  // namespace

Step parseStep(const std::string& line, const std::string& where) {
  std::istringstream words(line);
  std::string frame, word;
  Step step;
  step.where = where;
  words >> frame >> step.command;
  if (step.command.empty()) fail(where, "expected FRAME COMMAND ARGUMENTS, got '" + line + "'");
  step.frame = long(whole(numberFrom(frame, where), "the frame", where));
  const auto arity = kArity.find(step.command);
  if (arity == kArity.end())
    fail(where, "unknown command '" + step.command +
                    "' (commands: move turn scale color hide show remove duplicate select time click)");
  std::vector<std::string> rest;
  while (words >> word) rest.push_back(word);
  if (step.command == "select" && rest == std::vector<std::string>{"none"}) return step;  // no numbers
  for (const std::string& w : rest) step.numbers.push_back(numberFrom(w, where));
  bool counted = false;
  for (size_t n : arity->second) counted = counted || n == step.numbers.size();
  if (!counted)
    fail(where, "'" + step.command + "' takes " + std::to_string(arity->second.front()) +
                    (arity->second.size() > 1 ? " or " + std::to_string(arity->second.back()) : "") +
                    " numbers, got " + std::to_string(step.numbers.size()));
  return step;
}

std::vector<Step> parseScript(const std::string& text, const std::string& where) {
  std::vector<Step> steps;
  std::istringstream lines(text);
  std::string line;
  for (int number = 1; std::getline(lines, line); ++number) {
    line = line.substr(0, line.find('#'));
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    steps.push_back(parseStep(line, where + ":" + std::to_string(number)));
  }
  return steps;
}

void apply(const Step& step, Session& s) {
  const std::vector<double>& n = step.numbers;
  try {
    if (step.command == "time") {
      advanceClock(*s.level.scene(), n[0]);
      s.clock = n[0];
      return;
    }
    if (step.command == "click") {
      selectAt(s.renderer, int(n[0]), int(n[1]));  // the selection follows a frame or so later
      return;
    }
    if (step.command == "select" && n.empty()) {
      s.selected.reset();
      return;
    }
    const size_t model = whole(n[0], "the model number", step.where);
    Placement p = step.command == "duplicate" || step.command == "remove" ? Placement{} : s.level.placement(model);
    if (step.command == "move") {
      p.translation = vec3From(n, 1);
      s.level.setPlacement(model, p);
    } else if (step.command == "turn") {
      p.rotationDeg = vec3From(n, 1);
      s.level.setPlacement(model, p);
    } else if (step.command == "scale") {
      p.scale = n.size() == 2 ? glm::vec3(float(n[1])) : vec3From(n, 1);
      s.level.setPlacement(model, p);
    } else if (step.command == "color") {
      s.level.color(model, {float(n[1]), float(n[2]), float(n[3]), n.size() == 5 ? float(n[4]) : 1.0f});
    } else if (step.command == "hide" || step.command == "show") {
      s.level.setHidden(model, step.command == "hide");
    } else if (step.command == "remove") {
      s.level.remove(model);
      if (s.selected == model) s.selected.reset();
    } else if (step.command == "duplicate") {
      s.selected = s.level.duplicate(model);
    } else if (step.command == "select") {
      s.level.placement(model);  // throws for a model that is not there
      s.selected = model;
    }
  } catch (const std::exception& e) {
    const std::string message = e.what();
    if (message.rfind(step.where, 0) == 0) throw;  // named already
    fail(step.where, message);
  }
}

}  // namespace editor
