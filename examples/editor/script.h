// Scripted edits: what a user would do with the mouse, written down so that
// the editor runs the same session headless (tests) and interactively.
//
// One step a line, "FRAME COMMAND ARGUMENTS" ('#' starts a comment), applied
// before that frame is drawn:
//   move N X Y Z        model N's translation
//   turn N X Y Z        its rotation, degrees about X, then Y, then Z
//   scale N S | N X Y Z its scale
//   color N R G B [A]   its base colour (linear, 0..1)
//   hide N | show N     not drawn / drawn again
//   remove N            gone (its number stays taken)
//   duplicate N         a copy, numbered after the last model
//   select N | none     the gizmo's model
//   time SECONDS        the animation clock (advanceClock, level.h)
//   click X Y           select the model under window pixel X,Y, from the top
//                       left (selectAt, level.h: answered a frame or so later)
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "level.h"

namespace editor {

struct Step {
  long frame = 0;
  std::string command;
  std::vector<double> numbers;
  std::string where;  // "FILE:LINE" or "--do 'TEXT'", for messages
};

// Parses `text` (a script file's contents; `where` names it). Throws
// std::runtime_error "WHERE:LINE: what is wrong" on the first bad line.
std::vector<Step> parseScript(const std::string& text, const std::string& where);
// One step given on the command line (--do "FRAME COMMAND ...").
Step parseStep(const std::string& line, const std::string& where);

// What the steps act on.
struct Session {
  Level& level;
  rgraph::Renderer& renderer;
  std::optional<size_t> selected;
  std::optional<uint64_t> pickTaken;  // the frame of the last pick answer taken (pickedModel)
  double clock = 0.0;      // the animation clock's last setting (advanceClock), seconds
};

// Applies one step. Throws std::runtime_error "WHERE: message" when the step
// cannot be done (a removed model, a value rgraph refuses, ...).
void apply(const Step& step, Session& session);

}  // namespace editor
