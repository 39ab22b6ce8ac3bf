// rgraph view's panels (issue 12): the plan, parameter editing, the resource
// inspector. Each draws with Dear ImGui inside a frame the viewer started
// (view_app.cpp); what is not drawing (editing a pipeline's JSON, copying a
// resource out after its last write, mapping its values) works without a
// window and is tested headless.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "rgraph/renderer.h"
#include "view_panels_map.h"

namespace rgraph::view {

// Passes in execution order (culled ones greyed, with their reasons),
// resources with lifetime bars and the physical texture each uses (aliasing
// visible), memory allocated vs naive, per-pass times and what they measure
// (Renderer::cpuTimed()) and, with GPU timer queries, which frame they are of.
void drawPlanPanel(Renderer& renderer);

// The shadows panel (view_panels_shadows.cpp): per shadow_map template the
// shadow budget it reported at adapt time (Renderer::adaptTables: per light
// its map size, atlas layers and texel footprints, the atlas's occupancy and
// bytes, the lights left unshadowed and why), "no shadow maps" when there is
// none, then the adaptation's notes. The lines are the panel's text.
std::vector<std::string> shadowPanelLines(const Renderer& renderer);
void drawShadowsPanel(const Renderer& renderer);

class ParamEditor;
class ResourceInspector;

// The viewer's panel windows, placed for the display size at their first
// appearance so that each lies within it from 960x540 up: "rgraph" on the
// left (tabs: plan, parameters, shadows) above the camera window that
// view_main.cpp keeps in the lower left, "Inspector" on the right (folded
// when it first appears with nothing picked). Returns the
// parameter editor's edit (ParamEditor::draw). A non-empty `showTab`
// ("plan", "parameters", "shadows": the script's `panel`) brings that tab to
// the front, and is cleared.
std::optional<std::string> drawPanels(Renderer& renderer, ParamEditor& editor, ResourceInspector& inspector,
                                      std::string* showTab = nullptr);

// Every pass parameter with a widget from its declaration (type, range, enum
// values). An edit gives new pipeline JSON text for Renderer::reloadJson; the
// file is written only by save().
class ParamEditor {
 public:
  // The pipeline file's text, parsed keeping key order. Throws RuntimeError
  // when it cannot be read or parsed.
  explicit ParamEditor(std::string pipelinePath);
  // Re-reads the file (after a reload from disk). false when it cannot be parsed.
  bool reread();
  // Draws the widgets; returns the new JSON text when the user changed a value.
  std::optional<std::string> draw(const Renderer& renderer);
  // The script command `param PASS NAME JSON-VALUE`: the new JSON text, or
  // nullopt with `error` set (unknown pass, a parameter the pass type does
  // not declare, value not JSON). Value types and ranges are checked by
  // Renderer::reloadJson, which locates them in the text. `types`: the
  // renderer's pass types (Renderer::passTypes: its plugins' too).
  std::optional<std::string> withParam(const std::string& pass, const std::string& name, const std::string& jsonValue,
                                       const PassRegistry& types, std::string& error);
  // The same with the built-in pass types only.
  std::optional<std::string> withParam(const std::string& pass, const std::string& name, const std::string& jsonValue,
                                       std::string& error);
  // Takes an edit that the renderer accepted as the current text.
  void accept(const std::string& text);
  // An edit the renderer refused: the panel shows `message` (the
  // diagnostics) until the next accepted edit; the text stays as it was.
  void reject(const std::string& message);
  // true after an accepted edit, until the text is saved to the pipeline file or reread.
  bool modified() const { return modified_; }
  // What the panel says while modified(): the pipeline running is not the file's, and what replaces it.
  std::string modifiedNote() const {
    return "edited in memory: differs from " + path_ + " until saved (a change of the file replaces these edits)";
  }
  // The renderer's diagnostics about an edit (text from withParam or draw) pointed at the same place
  // (the JSON path) in the pipeline file's own text, which is what the user has in front of them.
  Diagnostics inFile(const Diagnostics& diags) const;
  // Writes the current text (key order kept) to the pipeline file, or to
  // `path` ("Save as": the pipeline file stays as it was). Throws
  // RuntimeError naming the file when it cannot be written.
  void save(const std::string& path = {});
  const std::string& text() const;
  const std::string& path() const { return path_; }

 private:
  // doc_ with passes[passIndex].params[name] = value, as text.
  std::string edited(size_t passIndex, const std::string& name, const nlohmann::ordered_json& value) const;

  std::string path_;
  ConfigDocument file_;  // the file's text as last read, for locating places in it
  nlohmann::ordered_json doc_;
  std::string text_;
  bool modified_ = false;
  std::string error_;       // the last refused edit's diagnostics
  std::string saveAsPath_;  // the "Save as" field
};

// Pick any resource or version (G-buffer targets, aliased transients) and see
// it as it was right after its last write in this frame: attach() installs a
// Renderer::setAfterPass hook that copies it out then.
class ResourceInspector {
 public:
  ResourceInspector();
  ~ResourceInspector();
  ResourceInspector(const ResourceInspector&) = delete;
  ResourceInspector& operator=(const ResourceInspector&) = delete;

  // Installs the copy hook (Renderer::setAfterPass) on `renderer`, which
  // must outlive the inspector or be detach()ed first: the destructor
  // detaches. Attaching to another renderer leaves the old one's hook inert.
  void attach(Renderer& renderer);
  void detach();
  // A new name starts at layer 0 and mip level 0.
  void select(const std::string& resourceOrVersion);
  const std::string& selected() const;
  // Which array layer and mip level of the selection is copied. Layers count
  // as the graph counts them (rgraph/graph.h arrayLayers): a cube's faces are
  // layers (+x -x +y -y +z -z), cube c's face f is layer 6c + f. One the
  // resource lacks copies nothing, and draw() says why.
  void setLayer(uint32_t layer);
  void setMip(uint32_t mip);
  uint32_t layer() const;
  uint32_t mip() const;
  // Why this frame copied nothing ("" when it did or nothing is picked): no
  // pass that runs writes it, a buffer, a layer or level it lacks. draw() shows it.
  const std::string& problem() const;
  // One label per array layer of the resource `name` belongs to, in the
  // pipeline as adapted: for a shadow atlas what each layer holds
  // ("directional0 cascade 1", "spot0", "point2 face +y", from the
  // shadow_map expansion's assignment), for a cube map its faces ("face +y";
  // "cube 1 face -x" in a cube array), "" where nothing is known. Empty for
  // an unknown name or a buffer.
  static std::vector<std::string> layerLabels(const Renderer& renderer, const std::string& name);
  // Every name select() takes, for the plan of `renderer`: each resource
  // (meaning its last write), then its later versions (that version's write).
  static std::vector<std::string> selectableNames(const Plan& plan);
  // The execution step after which `name` is copied: the last executed pass
  // that writes the resource (or, for a later version name, the pass that
  // writes that version); invalid when no executed pass writes it.
  static StepIndex captureStep(const Plan& plan, const std::string& name);
  // The copy made this frame (0 before one was made); RGBA32F readback of it,
  // rows top-down, depth in R (G = B = 0, A = 1), as Renderer::readResourceRGBA32F.
  uint32_t capturedTexture() const;
  Extent capturedExtent() const;
  std::vector<float> readCaptured() const;
  // One texel of the copy (x from the left, y from the top), as readCaptured().
  glm::vec4 readCapturedTexel(uint32_t x, uint32_t yTop) const;
  // The display: the copy drawn through mapping() into an RGBA8 texture of
  // its size (0 when nothing was copied). draw() shows it.
  ValueMapping& mapping();
  uint32_t renderDisplay();
  // Sets the mapping's range to the copy's values (raw mode): depth maps,
  // whose values crowd near 1, spread over the display. Depth texels at 1 (a
  // map's clear: nothing drawn there) are left out. false without a copy.
  bool fitRange();
  // How many frames copied the selection (tests: one copy per frame).
  uint64_t captureCount() const;
  // How many times the copy texture was (re)created: only when the selection's format or size changes.
  uint64_t textureCreations() const;
  void draw(Renderer& renderer);

 private:
  void drawSubresourcePickers(const Renderer& renderer);
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rgraph::view
