// shadow_map: depth-only draws of the shadow casters from each shadowed
// light into layers of one depth atlas (a 2D array), and the per-frame shadow
// data the lighting passes sample it with.
//
// A pipeline names one shadow_map pass, the template: "shadows for every
// casting light, at most max_lights, into this atlas". At adapt time its hook
// expands it from the scene's shadow facts (SceneFeatures::shadowLights) into
//   <name>.info            writes the info buffer (matrices, splits, texel sizes)
//   <name>.directional0.c0 one pass per cascade of the sun ..
//   <name>.spot3           one per spot light ..
//   <name>.point5          one per point light: its six cube faces in one layered draw
// each bound to its own layers of the atlas (reshaped to their total), so the
// graph orders, culls and aliases them like any pass, and `rgraph plan
// --scene` lists them. Which light owns which layers is fixed then (the
// "lights" param, shadow_views.h); the matrices are recomputed every frame
// from the camera and the lights, so a moving camera or light never rebuilds
// the graph. No caster or no casting light in view: no instance at all, and
// the lighting passes' own hooks compile their shadow code out.
#include <GL/glcorearb.h>

#include <algorithm>

#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/shadow_budget.h"
#include "rgraph/passes/shadow_sampling.h"
#include "rgraph/passes/shadow_views.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;
using shadows::LightKind;
using shadows::ShadowedLight;

shadows::ShadowSettings settingsOf(const ParamSet& p) {
  shadows::ShadowSettings s;
  s.cascades = static_cast<uint32_t>(p.getInt("cascades"));
  s.lambda = static_cast<float>(p.getNumber("lambda"));
  s.maxDistance = static_cast<float>(p.getNumber("max_distance"));
  s.stabilize = p.getBool("stabilize");
  return s;
}

std::vector<shadows::ShadowView> viewsOf(PassContext& ctx, const std::vector<ShadowedLight>& lights, uint32_t size) {
  const GpuScene& scene = *ctx.gpuScene();
  const Extent vp = scene.viewport().width ? scene.viewport() : ctx.outputExtent();
  const float aspect = static_cast<float>(std::max(vp.width, 1u)) / static_cast<float>(std::max(vp.height, 1u));
  shadows::ShadowSettings s = settingsOf(ctx.params());
  s.resolution = size;
  return shadows::shadowViews(scene.scene(), scene.camera(), aspect, s, lights);
}

class ShadowMapPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    role_ = p.getString("role");
    if (role_ == "template")
      throw RuntimeError("shadow_map pass '" + ctx.passName() +
                         "' was not expanded: it is a template the scene expands into one pass per shadow map "
                         "(render with scene adaptation on, as rgraph render does)");
    lights_ = shadows::decode(p.getString("lights"));
    firstLayer_ = static_cast<uint32_t>(p.getInt("first_layer"));
    layerCount_ = static_cast<uint32_t>(p.getInt("layer_count"));
    if (role_ == "map") {
      // A map pass fits only the views of the light that owns its layers:
      // every light's would make each frame cost maps x lights fits.
      std::erase_if(lights_, [&](const ShadowedLight& l) {
        return l.firstLayer + l.layers <= firstLayer_ || l.firstLayer >= firstLayer_ + layerCount_;
      });
      flat_ = ctx.program(0);
      layered_ = ctx.program(1);
    }
  }

  void execute(PassContext& ctx) override {
    if (role_ == "info") return writeInfo(ctx);
    GpuScene& scene = *ctx.gpuScene();
    // The param, not the atlas's extent: the info pass fits the same views
    // without binding the atlas (the expansion sized the atlas from it).
    const uint32_t size = static_cast<uint32_t>(ctx.params().getInt("size"));
    std::vector<GpuScene::View> views;
    bool clamp = false;
    for (const shadows::ShadowView& v : viewsOf(ctx, lights_, size)) {
      if (v.layer < firstLayer_ || v.layer >= firstLayer_ + layerCount_) continue;
      GpuScene::View view;
      view.view = v.view;
      view.proj = v.proj;
      view.filter = GpuScene::Filter::shadowCasters;
      view.cull = cull_(ctx.params().getString("cull"));
      view.eye = v.kind == LightKind::directional ? std::nullopt : std::optional<glm::vec3>(v.lightPosition);
      clamp = clamp || v.depthClamp;
      views.push_back(view);
    }
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(static_cast<float>(ctx.params().getNumber("slope_bias")),
                    static_cast<float>(ctx.params().getNumber("constant_bias")));
    // Casters between the light and a cascade's near plane still shadow it.
    if (clamp) glEnable(GL_DEPTH_CLAMP);
    const float one = 1.0f;
    if (views.size() > 1 && scene.supportsLayeredDraw()) {
      const PassFramebuffer fb = gl::bindPassFramebuffer(ctx, {{"atlas", 0, AttachmentRef::kAllLayers}});
      glClearNamedFramebufferfv(fb.id, GL_DEPTH, 0, &one);
      scene.drawLayered(layered_, views);
    } else {
      for (size_t i = 0; i < views.size(); ++i) {
        const PassFramebuffer fb = gl::bindPassFramebuffer(ctx, {{"atlas", 0, static_cast<uint32_t>(i)}});
        glClearNamedFramebufferfv(fb.id, GL_DEPTH, 0, &one);
        scene.drawView(flat_, views[i]);
      }
    }
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(0.0f, 0.0f);
    glDisable(GL_DEPTH_TEST);
  }
  // Depth test, offset and clamp put back; culling is left off by the scene's
  // draws; everything binds through ctx.bindings().
  uint32_t changedState() const override { return 0; }

 private:
  static GpuScene::Cull cull_(const std::string& name) {
    return name == "front" ? GpuScene::Cull::front : name == "none" ? GpuScene::Cull::none : GpuScene::Cull::back;
  }

  void writeInfo(PassContext& ctx) {
    const uint32_t size = static_cast<uint32_t>(ctx.params().getInt("size"));
    shadows::InfoOptions o;
    o.normalOffset = static_cast<float>(ctx.params().getNumber("normal_offset"));
    o.pcssLightSize = static_cast<float>(ctx.params().getNumber("pcss_light_size"));
    o.evsmPositive = static_cast<float>(ctx.params().getNumber("evsm_positive_exponent"));
    o.evsmNegative = static_cast<float>(ctx.params().getNumber("evsm_negative_exponent"));
    const std::vector<uint8_t> bytes = shadows::packInfo(ctx.gpuScene()->scene(), lights_, viewsOf(ctx, lights_, size), o);
    glNamedBufferSubData(ctx.buffer("info"), 0, static_cast<GLsizeiptr>(bytes.size()), bytes.data());
  }

  std::string role_;
  std::vector<ShadowedLight> lights_;  // info: every shadowed light; map: the one owning its layers
  uint32_t firstLayer_ = 0, layerCount_ = 0;
  uint32_t flat_ = 0, layered_ = 0;
};

std::string lightName(const SceneFeatures::ShadowLight& l) { return shadows::lightLabel(l.kind, l.light); }

// "; does not cast: point0, point1, point2, point3 and 28 more; outside the
// view: spot4": the unshadowed lights grouped by reason, a few named each.
std::string byReason(const std::vector<SceneFeatures::UnshadowedLight>& lights) {
  std::vector<std::pair<std::string, std::vector<std::string>>> groups;
  for (const auto& u : lights) {
    auto g = std::find_if(groups.begin(), groups.end(), [&](const auto& x) { return x.first == u.reason; });
    if (g == groups.end()) g = groups.insert(groups.end(), {u.reason, {}});
    g->second.push_back(lightName(u.light));
  }
  std::string text;
  for (const auto& [reason, names] : groups) {
    text += "; " + reason + ": ";
    for (size_t i = 0; i < names.size() && i < 4; ++i) text += (i ? ", " : "") + names[i];
    if (names.size() > 4) text += " and " + std::to_string(names.size() - 4) + " more";
  }
  return text;
}

// The shadow budget (shadow_budget.h) of this expansion, as table lines.
std::vector<std::string> budgetReport(const SceneFeatures& f, const ParamSet& p, const std::vector<ShadowedLight>& lights,
                                      uint32_t layers) {
  shadows::ShadowSettings s = settingsOf(p);
  s.resolution = static_cast<uint32_t>(p.getInt("size"));
  // 4 bytes a texel: depth24 and depth32f (the atlas's format is the
  // pipeline's; depth32f_stencil8 would double it).
  shadows::Budget b = shadows::budget(*f.scene, f.camera, f.aspect, s, lights, layers, 4);
  const size_t maxLights = static_cast<size_t>(p.getInt("max_lights"));
  for (size_t i = maxLights; i < f.shadowLights.size(); ++i)
    b.unshadowed.push_back({lightName(f.shadowLights[i]), "budget (max_lights " + std::to_string(maxLights) + ")"});
  for (const auto& u : f.unshadowedLights) b.unshadowed.push_back({lightName(u.light), u.reason});
  return shadows::budgetTable(b);
}

// The expansion: which lights get maps (the first max_lights of the scene's
// ranking), their layers, and one instance per info buffer, cascade, spot
// light and point light.
void expand(const SceneFeatures& f, PassAdaptation& a) {
  if (a.params.getString("role") != "template") return;
  a.expand.emplace();
  if (!f.shadowCasters) {
    a.notes.push_back("no primitive casts a shadow: no shadow maps");
    return;
  }
  if (f.shadowLights.empty()) {
    a.notes.push_back("no casting light reaches the view" + byReason(f.unshadowedLights) + ": no shadow maps");
    return;
  }
  const size_t maxLights = static_cast<size_t>(a.params.getInt("max_lights"));
  const uint32_t cascades = static_cast<uint32_t>(a.params.getInt("cascades"));
  std::vector<ShadowedLight> lights;
  uint32_t layer = 0;
  for (size_t i = 0; i < f.shadowLights.size(); ++i) {
    const SceneFeatures::ShadowLight& l = f.shadowLights[i];
    if (i >= maxLights) {
      a.notes.push_back(lightName(l) + " left unshadowed: budget (max_lights " + std::to_string(maxLights) + ")");
      continue;
    }
    const uint32_t n = l.kind == LightKind::directional ? cascades : l.kind == LightKind::point ? 6u : 1u;
    lights.push_back(ShadowedLight{l.kind, l.light, layer, n});
    layer += n;
  }
  ParamSet common = a.params;
  common.set("lights", shadows::encode(lights));
  uint32_t lightCount = 0;  // point and spot lights in the scene (the info buffer's per-light table)
  for (const auto& l : f.shadowLights) lightCount += l.kind != LightKind::directional;
  for (const auto& u : f.unshadowedLights) lightCount += u.light.kind != LightKind::directional;

  ExpandedPass info{"info", common, {{"info", std::nullopt}}};
  info.params.set("role", std::string("info"));
  a.expand->push_back(std::move(info));
  auto map = [&](std::string suffix, uint32_t first, uint32_t count) {
    ExpandedPass e{std::move(suffix), common, {{"atlas", Subresource{0, Subresource::kAll, first, count}}}};
    e.params.set("role", std::string("map"));
    e.params.set("first_layer", static_cast<int64_t>(first));
    e.params.set("layer_count", static_cast<int64_t>(count));
    a.expand->push_back(std::move(e));
  };
  std::string names;
  for (const ShadowedLight& l : lights) {
    const std::string base = lightName({l.kind, l.light});
    if (l.kind == LightKind::directional)
      for (uint32_t c = 0; c < l.layers; ++c) map(base + ".c" + std::to_string(c), l.firstLayer + c, 1);
    else
      map(base, l.firstLayer, l.layers);
    names += (names.empty() ? "" : ", ") + base + " (layers " + std::to_string(l.firstLayer) + ".." +
             std::to_string(l.firstLayer + l.layers - 1) + ")";
  }
  // At least two layers: one alone would make a plain 2D texture, which the
  // lighting passes' sampler2DArrayShadow cannot read.
  a.reshape.push_back({"atlas", std::max(layer, 2u), static_cast<uint32_t>(a.params.getInt("size")), 0});
  // A spare layer (one map alone) is bound by the last map pass, so that the
  // whole atlas has a writer; it is never drawn nor sampled.
  if (layer < 2) a.expand->back().bindings[0].part->layerCount = Subresource::kAll;
  a.reshape.push_back({"info", 0, 0, shadows::infoBytes(lightCount)});
  a.notes.push_back(std::to_string(lights.size()) + " shadowed light(s) in " + std::to_string(layer) +
                    " atlas layer(s): " + names);
  if (f.scene) a.report = budgetReport(f, a.params, lights, std::max(layer, 2u));
}

PassTypeDesc makeShadowMapPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = decl::passType(
      "shadow_map",
      "Shadow maps: a template expanded per casting light (cascades, spot maps, point cube faces) into layers of "
      "one depth atlas, with the per-frame shadow data the lighting passes read");
  d.slots.push_back(slot("atlas", Access::depth_attachment, false, SlotDecl::Load::never,
                         "depth array the maps are drawn into (its layers: set by the expansion)", depthFormats()));
  d.slots.push_back(slot("info", Access::storage_write, false, SlotDecl::Load::never,
                         "buffer of per-frame shadow data (matrices, splits, texel sizes; sized by the expansion)"));
  d.params = {
      ranged("max_lights", ParamType::integer, int64_t{8}, 1.0, static_cast<double>(shadows::kMaxMaps),
             "lights given maps, most important first (the first directional light, then by distance to the view)"),
      ranged("cascades", ParamType::integer, int64_t{4}, 1.0, 4.0, "cascades of the directional light"),
      ranged("lambda", ParamType::number, 0.75, 0.0, 1.0,
             "cascade splits: 0 uniform, 1 logarithmic (the practical split scheme between)"),
      ranged("max_distance", ParamType::number, 0.0, 0.0, 1e6,
             "view depth the cascades reach (0: the camera's far plane)"),
      param("stabilize", ParamType::boolean, true,
            "fit cascades to bounding spheres and snap them to whole texels (no shimmering edges)"),
      param("cull", ParamType::enumeration, std::string("none"),
            "faces culled in the maps: none (a light inside a closed caster, one-sided walls facing the light: both "
            "cast), back (fewer fragments) or front (a closed caster's far side)",
            {"none", "back", "front"}),
      ranged("slope_bias", ParamType::number, 1.5, 0.0, 64.0, "depth bias scaled by the depth slope (glPolygonOffset factor)"),
      ranged("constant_bias", ParamType::number, 2.0, 0.0, 4096.0, "constant depth bias (glPolygonOffset units)"),
      ranged("normal_offset", ParamType::number, 1.0, 0.0, 16.0,
             "receivers looked up this many texels along their normal (normal-offset bias)"),
      ranged("pcss_light_size", ParamType::number, 4.0, 0.0, 64.0, "pcss: the light's size, in texels"),
      ranged("evsm_positive_exponent", ParamType::number, 40.0, 0.0, 100.0,
             "evsm: exponent of the positive warp exp(c x) (clamped to the moments' format: 42 rgba32f, 5.5 rgba16f)"),
      ranged("evsm_negative_exponent", ParamType::number, 5.0, 0.0, 100.0,
             "evsm: exponent of the negative warp -exp(-c x) (clamped likewise)"),
      ranged("size", ParamType::integer, int64_t{2048}, 16.0, 16384.0,
             "texels per side of each map (the expansion sizes the atlas's layers so)"),
      param("role", ParamType::enumeration, std::string("template"),
            "template (expanded at adapt time), info or map (set by the expansion)", {"template", "info", "map"}),
      param("lights", ParamType::string, std::string(""), "the expansion's assignment of lights to layers"),
      ranged("first_layer", ParamType::integer, int64_t{0}, 0.0, 4096.0, "map: first atlas layer it draws"),
      ranged("layer_count", ParamType::integer, int64_t{1}, 1.0, 6.0, "map: layers it draws"),
  };
  d.needsScene = true;
  d.adapt = expand;
  d.programs = [](const ParamSet&) {
    ShaderProgramSpec flat = programSpec("scene.vert", "shadow_depth.frag");
    flat.ownSamplers = {"u_baseColorTex"};
    ShaderProgramSpec layered = flat;
    layered.defines.push_back("LAYERED");
    return std::vector<ShaderProgramSpec>{flat, layered};
  };
  d.create = [] { return std::make_unique<ShadowMapPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeShadowMapPass);
}  // namespace
