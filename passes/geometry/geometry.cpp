// geometry: draws the scene's opaque and alpha-masked surfaces into the
// G-buffer with multiple render targets. Blended surfaces are left to the
// forward pass (a G-buffer holds one surface per pixel and cannot blend).
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/gbuffer_layout.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/passes/velocity.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"

namespace {
using namespace rgraph;

// The slot and the parameter that asks for it share the target's name.
const std::string kObjectId = gbuffer::objectIdTarget().slot;

class GeometryPass final : public PassInstance {
 public:
  // Model no more than the scene needs: without normal maps no tangent is
  // read and no normal map sampled.
  void setup(PassContext& ctx) override {
    program_ = ctx.program(lighting::normalMapVariant(ctx));
    velocity_ = ctx.bound("velocity");  // checkGeometry: bound exactly when the "velocity" param is on
    objectIds_ = ctx.bound(kObjectId);   // objectIdRule: bound exactly when the "object_id" param is on
  }

  void execute(PassContext& ctx) override {
    gl::bindPassFramebuffer(ctx);
    // Uncovered pixels read as zero everywhere (normal.w = 0: no surface).
    const float zero[4] = {0, 0, 0, 0};
    const float one = 1.0f;
    const GLuint fbo = ctx.framebuffer();
    GLint drawBuffers = 0;
    for (const auto& slot : gbuffer::colorSlots())
      if (ctx.bound(slot)) glClearNamedFramebufferfv(fbo, GL_COLOR, drawBuffers++, zero);
    // Background pixels keep velocity 0 (no camera-only motion for them yet).
    if (velocity_) glClearNamedFramebufferfv(fbo, GL_COLOR, drawBuffers++, zero);
    // Integer ids are cleared as integers (a float clear of one is undefined): 0, no object.
    const GLuint noObject[4] = {0, 0, 0, 0};
    if (objectIds_) glClearNamedFramebufferuiv(fbo, GL_COLOR, drawBuffers++, noObject);
    // Depth function GL_LESS, writes on, no blending: what every pass starts with (rgraph/pass.h).
    glEnable(GL_DEPTH_TEST);
    glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
    GpuScene::DrawOptions options;
    options.filter = GpuScene::Filter::opaque;
    ctx.gpuScene()->drawPrimitives(program_, options);
    glDisable(GL_DEPTH_TEST);
  }
  // Depth testing put back; the scene's draws bind through ctx.bindings().
  uint32_t changedState() const override { return 0; }

 private:
  uint32_t program_ = 0;
  bool velocity_ = false;
  bool objectIds_ = false;
};

// Picking's ids (gbuffer::objectIdTarget): bound exactly when the param is on.
PassRule objectIdRule() {
  PassRule rule;
  rule.text = "bind the object_id output exactly when \"object_id\" is true";
  rule.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    const bool wanted = ctx.params().getBool(kObjectId);
    if (ctx.bound(kObjectId) == wanted) return;
    checks.slotError(kObjectId, wanted ? "\"object_id\": true writes object ids: bind the 'object_id' output"
                                       : "an 'object_id' output needs the pass parameter \"object_id\": true");
  };
  return rule;
}

// The targets the layout writes are exactly the bound ones (gbuffer_layout.h),
// each sentence listing what every layout of the table asks.
PassRule targetsRule() {
  PassRule rule;
  rule.text = "bind the targets \"layout\" writes, and no other:";
  for (const auto& layout : gbuffer::layouts()) {
    rule.text += std::string(&layout == &gbuffer::layouts().front() ? " " : ", ") + layout.name + " (";
    for (size_t i = 0; i < layout.targets.size(); ++i) rule.text += (i ? ", " : "") + layout.targets[i].slot;
    rule.text += ")";
  }
  rule.text += "; no material with constant_material; emissive and reflectance exactly when their parameter is on";
  rule.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    const gbuffer::Layout& layout = gbuffer::of(ctx.params());
    auto require = [&](const std::string& slot, bool wanted) {
      if (ctx.bound(slot) != wanted)
        checks.slotError(slot, "layout '" + layout.name + "' " + (wanted ? "writes" : "does not write") + " a '" +
                                   slot + "' target; " + (wanted ? "bind it in outputs" : "remove it from outputs"));
    };
    require("position", layout.writes("position"));
    require("material", layout.uses("material", ctx.params()));
    lighting::checkOptionalTargets(ctx, checks, /*writes=*/true);
  };
  return rule;
}

PassRule normalRule() {
  PassRule rule;
  rule.text = "normal has the components \"layout\" needs:";
  const auto& table = gbuffer::layouts();
  for (size_t i = 0; i < table.size(); ++i)
    rule.text += (i ? ", " : " ") + table[i].name + " " + std::to_string(table[i].normalComponents);
  rule.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    const gbuffer::Layout& layout = gbuffer::of(ctx.params());
    if (auto normal = ctx.format("normal"); normal && formatInfo(*normal).components < layout.normalComponents)
      checks.slotError("normal", "layout '" + layout.name + "' needs " + std::to_string(layout.normalComponents) +
                                     " components in 'normal', got " + std::string(formatName(*normal)));
  };
  return rule;
}

PassTypeDesc makeGeometryPass() {
  using namespace rgraph::decl;
  const std::vector<Format> color = {Format::rgba8,  Format::srgb8_alpha8, Format::rgba16f, Format::rgba32f,
                                     Format::rg16f,  Format::rg8,          Format::r11g11b10f};
  PassTypeDesc d = passType("geometry",
      "Fills the G-buffer (multiple render targets) with the scene's opaque and masked surfaces");
  d.slots = {
      slot("position", Access::color_attachment, false, SlotDecl::Load::never,
           "world position (learnopengl, pbr, fp32 layouts)", {Format::rgba16f, Format::rgba32f}),
      slot("normal", Access::color_attachment, true, SlotDecl::Load::never,
           "world normal (xyz, or octahedral rg in the compact layout)", color),
      slot("albedo", Access::color_attachment, true, SlotDecl::Load::never, "albedo rgb + specular intensity", color),
      slot("material", Access::color_attachment, false, SlotDecl::Load::never,
           "metallic, roughness (, ao) (pbr, compact, fp32 layouts)", color),
      slot("emissive", Access::color_attachment, false, SlotDecl::Load::never,
           "emitted radiance (with the \"emissive\" parameter)", color),
      slot("reflectance", Access::color_attachment, false, SlotDecl::Load::never,
           "KHR_materials_specular dielectric F0 + F90 (with the \"reflectance\" parameter; pbr, compact, fp32)",
           color),
      slot("depth", Access::depth_attachment, true, SlotDecl::Load::never, "scene depth",
           depthFormats()),
      velocity::slot(),  // after the layouts' colour targets, so that they keep their attachment indices
      // Last: picking's ids, only when asked (gbuffer::objectIdTarget).
      slot(kObjectId, Access::color_attachment, false, SlotDecl::Load::never,
           gbuffer::objectIdTarget().stores + "; needs the object_id parameter", {gbuffer::objectIdTarget().format}),
  };
  for (auto& s : d.slots) s.gbufferTarget = true;  // what `rgraph plan --scene` counts as G-buffer bytes
  d.params = {param("layout", ParamType::enumeration, std::string(gbuffer::kDefaultLayout),
                    "G-buffer layout: " + gbuffer::nameList(true), gbuffer::names())};
  for (auto& p : lighting::constantMaterialParams()) d.params.push_back(std::move(p));
  d.adapt = lighting::adaptGBuffer;
  d.params.push_back(velocity::param());
  d.params.push_back(param(kObjectId, ParamType::boolean, false,
                           "write object ids for picking to the 'object_id' output (bind it too; "
                           "RendererOptions::picking adds both)"));
  // HAS_NORMAL_MAPS follows the scene (both variants), HAS_VELOCITY the param.
  d.programs = [](const ParamSet& p) {
    std::vector<std::string> defines = lighting::gbufferDefines(p);
    velocity::addDefine(p, defines);
    if (p.getBool(kObjectId)) defines.push_back("HAS_OBJECT_ID");
    ShaderProgramSpec s = programSpec("scene.vert", "gbuffer.frag", std::move(defines));
    s.ownSamplers = lighting::materialSamplers();
    return lighting::normalMapVariants(s);
  };
  d.rules = {targetsRule(), velocity::rule(), normalRule(), objectIdRule()};
  d.needsScene = true;
  d.create = [] { return std::make_unique<GeometryPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeGeometryPass);
}  // namespace
