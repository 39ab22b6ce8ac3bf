#include "rgraph/passes/gbuffer_layout.h"

#include <algorithm>
#include <cstddef>

namespace rgraph::gbuffer {

namespace {
// What gbuffer.frag writes to each target, once for every layout that has it.
constexpr const char* kPosition = "world position xyz, w 1 where covered (0 where nothing was drawn)";
constexpr const char* kNormal = "world normal xyz (unit length), w 1 where covered: the coverage flag readers test";
constexpr const char* kAlbedo = "albedo rgb, specular intensity a";
constexpr const char* kMaterial = "metallic r, roughness g, ambient occlusion b";
constexpr const char* kOctahedral =
    "world normal, octahedral rg (encodeOctahedral / decodeOctahedral in include/gbuffer.glsl); no coverage flag";
constexpr const char* kEmissive =
    "emitted radiance rgb (emissiveFactor x strength x sRGB emissiveTexture; unlit: the base colour), added once "
    "after lighting; optional: only for scenes with an emitting material";
constexpr const char* kReflectance =
    "dielectric F0 rgb (KHR_materials_specular: min(0.04 x specular colour, 1) x specular weight), specular weight a "
    "(the dielectric F90); optional: only for scenes with non-default reflectance";
constexpr const char* kDepth = "window-space depth, non-linear (0 near .. 1 far), 1 where nothing was drawn";
constexpr const char* kDepthOnly =
    "window-space depth, non-linear (0 near .. 1 far): covered where < 1; readers rebuild the world position from it "
    "with u_invProj and u_invView (positionFromDepth in include/gbuffer.glsl)";
}  // namespace

// clang-format off
// One row per layout: name, define, summary, targets in slot order, depth,
// normal components, position rebuilt from depth, what the depth holds.
const std::vector<Layout>& layouts() {
  static const std::vector<Layout> table = {
      {"learnopengl", "GBUFFER_LEARNOPENGL", "",
       {{"position", Format::rgba16f, kPosition}, {"normal", Format::rgba16f, kNormal},
        {"albedo", Format::rgba8, kAlbedo}, {"emissive", Format::r11g11b10f, kEmissive, true}},
       Format::depth24_stencil8, 3, false, kDepth},
      {"pbr", "GBUFFER_PBR", "4x rgba16f, + rgba16f emissive, + rgba16f reflectance",
       {{"position", Format::rgba16f, kPosition}, {"normal", Format::rgba16f, kNormal},
        {"albedo", Format::rgba16f, kAlbedo}, {"material", Format::rgba16f, kMaterial},
        {"emissive", Format::rgba16f, kEmissive, true}, {"reflectance", Format::rgba16f, kReflectance, true}},
       Format::depth24_stencil8, 3, false, kDepth},
      {"compact", "GBUFFER_COMPACT", "no position, octahedral normal, + r11g11b10f emissive, + rgba8 reflectance",
       {{"normal", Format::rg16f, kOctahedral}, {"albedo", Format::rgba8, kAlbedo},
        {"material", Format::rg8, "metallic r, roughness g"}, {"emissive", Format::r11g11b10f, kEmissive, true},
        {"reflectance", Format::rgba8, kReflectance, true}},
       Format::depth32f, 2, true, kDepthOnly},
      {"fp32", "GBUFFER_FP32", "",
       {{"position", Format::rgba32f, kPosition}, {"normal", Format::rgba32f, kNormal},
        {"albedo", Format::rgba32f, kAlbedo}, {"material", Format::rgba32f, kMaterial},
        {"emissive", Format::rgba32f, kEmissive, true}, {"reflectance", Format::rgba32f, kReflectance, true}},
       Format::depth32f, 3, false, kDepth},
  };
  return table;
}
// clang-format on

const Target& objectIdTarget() {
  static const Target target{
      "object_id", Format::rg32ui,
      "r: the drawn object's entry in the scene's Objects buffer + 1 (its index in Scene::primitives at that "
      "frame; 0 where nothing was drawn), g: the triangle within its draw (gl_PrimitiveID); only when asked "
      "(picking)"};
  return target;
}

const Target* Layout::target(std::string_view slot) const {
  for (const auto& t : targets)
    if (t.slot == slot) return &t;
  return nullptr;
}

uint32_t Layout::bytesPerPixel() const {
  uint32_t bytes = formatInfo(depth).bytesPerPixel;
  for (const auto& t : targets)
    if (!t.optional) bytes += formatInfo(t.format).bytesPerPixel;
  return bytes;
}

uint32_t Layout::optionalBytesPerPixel(std::string_view slot) const {
  const Target* t = target(slot);
  return t && t->optional ? formatInfo(t->format).bytesPerPixel : 0;
}

bool Layout::uses(std::string_view slot, const ParamSet& params) const {
  const Target* t = target(slot);
  if (!t) return false;
  if (slot == "material") return !params.getBool("constant_material");
  return !t->optional || params.getBool(std::string(slot));
}

std::vector<std::string> optionalSlots() {
  std::vector<std::string> out;
  for (const auto& slot : colorSlots())
    for (const auto& l : layouts())
      if (const Target* t = l.target(slot); t && t->optional) {
        out.push_back(slot);
        break;
      }
  return out;
}

std::vector<std::string> Layout::readerSlots(bool constantMaterial) const {
  std::vector<std::string> slots = {"normal", "albedo", positionSlot()};
  if (writes("material") && !constantMaterial) slots.push_back("material");
  return slots;
}

const Layout& find(std::string_view name) {
  const auto& table = layouts();
  for (const auto& l : table)
    if (l.name == name) return l;
  return name == kDefaultLayout ? table.front() : find(kDefaultLayout);
}

const Layout& of(const ParamSet& params) { return find(params.getString("layout")); }

std::vector<std::string> names() {
  std::vector<std::string> out;
  for (const auto& l : layouts()) out.push_back(l.name);
  return out;
}

std::string nameList(bool withSummaries) {
  std::string out;
  for (const auto& l : layouts()) {
    if (!out.empty()) out += ", ";
    out += l.name;
    if (withSummaries && !l.summary.empty()) out += " (" + l.summary + ")";
  }
  return out;
}

// Merged so that every layout's targets keep their order (learnopengl's
// emissive after albedo, pbr's after material: material comes first).
std::vector<std::string> colorSlots() {
  std::vector<std::string> out;
  for (const auto& l : layouts()) {
    size_t next = 0;  // where this layout's next unseen target goes
    for (const auto& t : l.targets) {
      auto it = std::find(out.begin(), out.end(), t.slot);
      if (it == out.end()) it = out.insert(out.begin() + static_cast<std::ptrdiff_t>(next), t.slot);
      next = static_cast<size_t>(it - out.begin()) + 1;
    }
  }
  return out;
}

PassRule sameLayoutAsWriterRule() {
  PassRule rule;
  rule.text = "\"layout\" is the layout of the pass that wrote the G-buffer it reads";
  rule.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    const std::string mine = of(ctx.params()).name;
    std::vector<std::string> slots = colorSlots(), reported;
    slots.push_back("depth");
    for (const auto& slot : slots) {
      const std::optional<SlotWriter> w = ctx.writer(slot);
      if (!w || w->slot != slot || !w->params->has("layout")) continue;
      const std::string theirs = of(*w->params).name;
      if (theirs == mine || std::find(reported.begin(), reported.end(), w->pass) != reported.end()) continue;
      reported.push_back(w->pass);
      const std::string at = locationText(w->paramWhere("layout"));
      checks.paramError("layout", "layout '" + mine + "' is not the layout of the G-buffer it reads: " + w->type +
                                      " pass '" + w->pass + "' writes '" + ctx.find(slot)->resource + "' ('" + slot +
                                      "') with layout '" + theirs + "'" + (at.empty() ? "" : " (" + at + ")") +
                                      "; give both passes the same \"layout\"");
    }
  };
  return rule;
}

}  // namespace rgraph::gbuffer
