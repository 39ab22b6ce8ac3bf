// The level the editor edits: a scene file (scenes/README.md) whose models
// become objects of a RenderScene (rgraph/renderer.h), edited per frame
// through RenderScene's objects API, and written back as a scene file that
// `rgraph render --scene` draws the same.
//
// Model N is the level's models[N]; a duplicate is appended as a new model.
// Removed models keep their number (editing one is an error), so a script's
// numbers mean the same models from its first line to its last.
#pragma once

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

// ---- Waiting for rgraph features being added (issue 30); each is one call.

// Sets the scene's clock (skinned and animated glTF models play at it).
// Will call scene.setTime(seconds) (RenderScene::setTime); until then throws
// std::runtime_error saying this rgraph cannot play animations.
void advanceClock(rgraph::RenderScene& scene, double seconds);

// Picking, answered a frame late (the GPU is not waited for). selectAt asks
// which model is under window pixel (x, y), counted from the top left. Will
// call renderer.requestPick(uint32_t(x), uint32_t(y)) (Renderer::requestPick,
// with RendererOptions::picking on in main.cpp's makeRenderer); until then
// throws std::runtime_error saying this rgraph cannot pick.
void selectAt(rgraph::Renderer& renderer, int x, int y);
// After each frame: the answer to the last selectAt once it is in (a model,
// or nullopt inside: the background), nullopt while there is none. Will
// return level.modelOf(result->instance) for renderer.pickResult()'s result
// when there is one; until then there never is.
std::optional<std::optional<size_t>> pickedModel(rgraph::Renderer& renderer, const Level& level);

}  // namespace editor
