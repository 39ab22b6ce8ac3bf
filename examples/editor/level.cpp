#include "level.h"

#include <charconv>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "rgraph/scene.h"

namespace editor {
namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// The same glm calls in the same order as rgraph's scene-file loader, so that
// a state file loaded by `rgraph render` gives bit-identical matrices (and so
// identical pixels, not merely close ones).
glm::mat4 Placement::matrix() const {
  glm::mat4 m(1.0f);
  m = glm::translate(m, translation);
  const glm::vec3 r = glm::radians(rotationDeg);
  m = glm::rotate(m, r.z, glm::vec3(0, 0, 1));
  m = glm::rotate(m, r.y, glm::vec3(0, 1, 0));
  m = glm::rotate(m, r.x, glm::vec3(1, 0, 0));
  return glm::scale(m, scale);
}

namespace {

// Scene-file numbers as the loader reads them (a double made a float). The
// loader has checked the level already, so the shapes are right here.
glm::vec3 vec3(const json& j) { return {float(j[0].get<double>()), float(j[1].get<double>()), float(j[2].get<double>())}; }
glm::vec3 vec3OrScalar(const json& j) { return j.is_number() ? glm::vec3(float(j.get<double>())) : vec3(j); }
// A float as the shortest decimal that reads back as the same float (0.9, not
// 0.8999999761581421): the state file stays readable and loads exactly.
double shortest(float f) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, f).ptr;
  return std::strtod(std::string(text, end).c_str(), nullptr);
}
json array(const glm::vec3& v) { return json::array({shortest(v.x), shortest(v.y), shortest(v.z)}); }

Placement placementOf(const json& model) {
  Placement p;
  if (!model.contains("transform")) return p;
  const json& t = model["transform"];
  if (t.contains("translation")) p.translation = vec3(t["translation"]);
  if (t.contains("rotation_euler_deg")) p.rotationDeg = vec3(t["rotation_euler_deg"]);
  if (t.contains("scale")) p.scale = vec3OrScalar(t["scale"]);
  return p;
}

std::string absolute(const std::string& folder, const std::string& path) {
  const fs::path p(path);
  return p.is_relative() ? (fs::path(folder) / p).lexically_normal().string() : path;
}

}  // namespace

Level::Level(const std::string& path) {
  if (fs::path(path).extension() != ".json")
    throw std::runtime_error("the editor edits scene files (.json), not '" + path +
                             "': wrap a glTF as {\"models\": [{\"file\": \"model.gltf\"}]}");
  // rgraph reads and checks it first: its messages give file:line:column and the JSON pointer.
  scene_ = rgraph::RenderScene::load(path);
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  level_ = json::parse(text.str());
  folder_ = fs::absolute(path).parent_path().string();

  // rgraph's loader appends each model's primitives in models order. Loading
  // each model alone without its transform gives how many it has and their
  // matrices under the model's transform (a glTF's node hierarchy), which
  // moves multiply as the loader does. (A glTF model is read twice, and its
  // warnings are logged twice: simple, for an example.)
  const std::vector<rgraph::InstanceId> objects = scene_->instances();
  size_t next = 0;
  for (const json& entry : level_.value("models", json::array())) {
    Model m;
    m.source = entry;
    m.placement = placementOf(entry);
    json alone = entry;
    alone.erase("transform");
    const json one = {{"models", json::array({alone})}, {"lights", json::array()}};
    const rgraph::Scene parts = rgraph::parseSceneText(one.dump(), path, folder_);
    for (const rgraph::Primitive& p : parts.primitives) {
      if (next >= objects.size()) throw std::runtime_error(path + ": its models and its objects do not line up");
      m.parts.push_back(objects[next++]);
      m.local.push_back(p.transform);
    }
    models_.push_back(std::move(m));
  }
  if (next != objects.size()) throw std::runtime_error(path + ": its models and its objects do not line up");
}

Level::Model& Level::live(size_t model) {
  return const_cast<Model&>(static_cast<const Level*>(this)->live(model));
}

const Level::Model& Level::live(size_t model) const {
  if (model >= models_.size())
    throw std::runtime_error("no model " + std::to_string(model) + " (the level has " +
                             std::to_string(models_.size()) + ")");
  if (models_[model].removed) throw std::runtime_error("model " + std::to_string(model) + " was removed");
  return models_[model];
}

// Every part at the model's transform times its own matrix, as the loader
// composes them (appendScene: transform * primitive's).
void Level::place(Model& m) {
  const glm::mat4 model = m.placement.matrix();
  for (size_t i = 0; i < m.parts.size(); ++i) scene_->setTransform(m.parts[i], model * m.local[i]);
}

void Level::setPlacement(size_t model, const Placement& placement) {
  Model& m = live(model);
  const Placement before = m.placement;
  m.placement = placement;
  try {
    place(m);
  } catch (...) {  // rgraph refused one part (a zero scale, beyond its range): all as before
    m.placement = before;
    place(m);
    throw;
  }
}

const Placement& Level::placement(size_t model) const { return live(model).placement; }

// Every part's own base colour, as a scene file's model "material" gives it
// (a glTF model's materials all take it; textures still multiply it).
void Level::color(size_t model, const glm::vec4& baseColor) {
  Model& m = live(model);
  for (rgraph::InstanceId part : m.parts) {
    rgraph::MaterialParameters look = scene_->materialParameters(part);
    look.baseColorFactor = baseColor;
    scene_->setMaterialParameters(part, look);  // values outside 0..1 throw, naming the object
  }
  m.baseColor = baseColor;
}

void Level::setHidden(size_t model, bool hidden) {
  Model& m = live(model);
  for (rgraph::InstanceId part : m.parts) scene_->setVisible(part, !hidden);
  m.hidden = hidden;
}

void Level::remove(size_t model) {
  Model& m = live(model);
  for (rgraph::InstanceId part : m.parts) scene_->removeInstance(part);
  m.parts.clear();
  m.removed = true;
}

// The copy draws the same meshes with the same materials: no geometry is
// uploaded again (RenderScene::addInstance shares them).
size_t Level::duplicate(size_t model) {
  Model copy = live(model);
  const glm::mat4 placed = copy.placement.matrix();
  for (size_t i = 0; i < copy.parts.size(); ++i) {
    const rgraph::Primitive& p = scene_->scene().primitives[scene_->primitiveIndex(copy.parts[i])];
    copy.parts[i] = scene_->addInstance(size_t(p.mesh), size_t(p.material), placed * copy.local[i], p.name);
    if (copy.hidden) scene_->setVisible(copy.parts[i], false);
  }
  models_.push_back(std::move(copy));
  return models_.size() - 1;
}

std::optional<size_t> Level::modelOf(rgraph::InstanceId object) const {
  for (size_t i = 0; i < models_.size(); ++i)
    for (rgraph::InstanceId part : models_[i].parts)
      if (part == object) return i;
  return std::nullopt;
}

json Level::state(const rgraph::Camera& camera) const {
  json out = level_;
  json models = json::array();
  for (const Model& m : models_) {
    if (m.removed || m.hidden) continue;  // not drawn (a hidden model still counts in rgraph's bounds: see README)
    json entry = m.source;
    if (entry.contains("file")) entry["file"] = absolute(folder_, entry["file"].get<std::string>());
    entry["transform"] = {{"translation", array(m.placement.translation)},
                          {"rotation_euler_deg", array(m.placement.rotationDeg)},
                          {"scale", array(m.placement.scale)}};
    if (m.baseColor) {
      if (!entry.contains("material")) entry["material"] = json::object();
      const glm::vec4& c = *m.baseColor;
      entry["material"]["baseColor"] = {shortest(c.r), shortest(c.g), shortest(c.b), shortest(c.a)};
    }
    models.push_back(std::move(entry));
  }
  out["models"] = std::move(models);
  if (out.contains("environment") && out["environment"].contains("hdr"))
    out["environment"]["hdr"] = absolute(folder_, out["environment"]["hdr"].get<std::string>());
  out["camera"] = {{"position", array(camera.position)}, {"target", array(camera.target)},
                   {"up", array(camera.up)},             {"fov", shortest(camera.fovY)},
                   {"near", shortest(camera.near)},      {"far", shortest(camera.far)}};
  return out;
}

// ---- The animation clock and picking.

void advanceClock(rgraph::RenderScene& scene, double seconds) {
  scene.setTime(seconds);  // poses glTF animations, skins and morph targets; RuntimeError when not finite
}

void selectAt(rgraph::Renderer& renderer, int x, int y) {
  if (x < 0 || y < 0) throw std::runtime_error("pixel " + std::to_string(x) + "," + std::to_string(y) + " is outside the window");
  renderer.requestPick(uint32_t(x), uint32_t(y));  // RuntimeError past the window's size
}

std::optional<std::optional<size_t>> pickedModel(rgraph::Renderer& renderer, const Level& level,
                                                 std::optional<uint64_t>& taken) {
  const std::optional<rgraph::PickResult> result = renderer.pickResult();
  // The answer stays until the next request: take each one once, so that the
  // keyboard's selection is not overridden every frame.
  if (!result || result->frame == taken) return std::nullopt;
  taken = result->frame;
  if (!result->problem.empty()) throw std::runtime_error("cannot pick: " + result->problem);
  return level.modelOf(result->instance);  // nullopt inside: the background
}

}  // namespace editor
