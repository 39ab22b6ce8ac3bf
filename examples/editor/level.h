// The level the editor edits: a scene file (scenes/README.md) whose models
// become objects of a RenderScene (rgraph/renderer.h), edited per frame
// through RenderScene's objects API, and written back as a scene file that
// `rgraph render --scene` draws the same.
//
// Model N is the level's models[N]; a duplicate is appended as a new model.
// Removed models keep their number (editing one is an error), so a script's
// numbers mean the same models from its first line to its last.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "rgraph/renderer.h"

namespace editor {

// A model's placement as scene files give it: translation * Rz * Ry * Rx * scale.
struct Placement {
  glm::vec3 translation{0.0f};
  glm::vec3 rotationDeg{0.0f};  // about X, then Y, then Z (fixed axes)
  glm::vec3 scale{1.0f};
  glm::mat4 matrix() const;
};

class Level {
 public:
  // Reads a scene file (.json). Throws std::runtime_error (rgraph::RuntimeError
  // for rgraph's own messages: file:line:column and the JSON pointer).
  explicit Level(const std::string& path);

  const std::shared_ptr<rgraph::RenderScene>& scene() const { return scene_; }
  size_t modelCount() const { return models_.size(); }
  bool exists(size_t model) const { return model < models_.size() && !models_[model].removed; }

  // The edits. Each throws std::runtime_error naming the model when it is
  // out of range or removed; values are checked by rgraph (RuntimeError).
  const Placement& placement(size_t model) const;
  void setPlacement(size_t model, const Placement& placement);  // moves, turns, scales
  void color(size_t model, const glm::vec4& baseColor);
  void setHidden(size_t model, bool hidden);
  void remove(size_t model);
  size_t duplicate(size_t model);  // the copy's number

  // Which model an object is part of (for picking).
  std::optional<size_t> modelOf(rgraph::InstanceId object) const;

  // The level as it is now, with `camera`, as a scene file: models removed
  // or hidden left out, every model's transform and changed colour written,
  // relative paths made absolute (the file may be written anywhere).
  nlohmann::ordered_json state(const rgraph::Camera& camera) const;

 private:
  struct Model {
    nlohmann::ordered_json source;          // the level's entry: what `state` writes back
    Placement placement;
    std::vector<rgraph::InstanceId> parts;  // its primitives' objects
    std::vector<glm::mat4> local;           // each part's matrix under the model's transform
    std::optional<glm::vec4> baseColor;     // set by color()
    bool hidden = false, removed = false;
  };
  Model& live(size_t model);
  const Model& live(size_t model) const;
  void place(Model& m);

  std::string folder_;  // the level's folder: relative paths start there
  nlohmann::ordered_json level_;
  std::vector<Model> models_;
  std::shared_ptr<rgraph::RenderScene> scene_;
};

// ---- The animation clock and picking: one rgraph call each.

// Sets the scene's clock (RenderScene::setTime: skinned and animated glTF
// models play at it).
void advanceClock(rgraph::RenderScene& scene, double seconds);

// Asks which model is under window pixel (x, y), counted from the top left
// (Renderer::requestPick; main.cpp's makeRenderer turns RendererOptions::
// picking on). The answer comes a frame or so later, from pickedModel.
void selectAt(rgraph::Renderer& renderer, int x, int y);
// After each frame: the answer to the last selectAt once it is in and not yet
// taken (`taken`: the frame of the last answer taken): a model, or nullopt
// inside for the background; nullopt while there is none.
std::optional<std::optional<size_t>> pickedModel(rgraph::Renderer& renderer, const Level& level,
                                                 std::optional<uint64_t>& taken);

}  // namespace editor
