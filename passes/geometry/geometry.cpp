// geometry: draws the scene's opaque and alpha-masked surfaces into the
// G-buffer with multiple render targets. Blended surfaces are left to the
// forward pass (a G-buffer holds one surface per pixel and cannot blend).
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/lighting_options.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"
#include "rgraph/scene.h"

namespace {
using namespace rgraph;

struct Layout {
  const char* name;
  const char* define;
  bool position, material;  // which optional slots the layout writes
  uint32_t normalComponents;
};
constexpr Layout kLayouts[] = {
    {"learnopengl", "GBUFFER_LEARNOPENGL", true, false, 3},
    {"pbr", "GBUFFER_PBR", true, true, 3},
    {"compact", "GBUFFER_COMPACT", false, true, 2},
    {"fp32", "GBUFFER_FP32", true, true, 3},
};

const Layout& findLayout(const std::string& name) {
  for (const auto& l : kLayouts)
    if (name == l.name) return l;
  return kLayouts[1];
}

class GeometryPass final : public PassInstance {
 public:
  // Model no more than the scene needs: without normal maps no tangent is
  // read and no normal map sampled.
  void setup(PassContext& ctx) override { program_ = ctx.program(lighting::normalMapVariant(ctx)); }

  void execute(PassContext& ctx) override {
    gl::bindPassFramebuffer(ctx);
    // Uncovered pixels read as zero everywhere (normal.w = 0: no surface).
    const float zero[4] = {0, 0, 0, 0};
    const float one = 1.0f;
    const GLuint fbo = ctx.framebuffer();
    GLint drawBuffers = 0;
    for (const char* slot : {"position", "normal", "albedo", "material"})
      if (ctx.bound(slot)) glClearNamedFramebufferfv(fbo, GL_COLOR, drawBuffers++, zero);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
    glDisable(GL_BLEND);
    GpuScene::DrawOptions options;
    options.filter = GpuScene::Filter::opaque;
    ctx.gpuScene()->drawPrimitives(program_, options);
    glDisable(GL_DEPTH_TEST);
  }

 private:
  uint32_t program_ = 0;
};

// The targets the layout writes are exactly the bound ones.
void checkGeometry(const PassCheckContext& ctx, PassChecks& checks) {
  const Layout& layout = findLayout(ctx.params().getString("layout", "pbr"));
  auto require = [&](const char* slot, bool wanted) {
    if (ctx.bound(slot) != wanted)
      checks.slotError(slot, std::string("layout '") + layout.name + "' " + (wanted ? "writes" : "does not write") +
                                 " a '" + slot + "' target; " +
                                 (wanted ? "bind it in outputs" : "remove it from outputs"));
  };
  require("position", layout.position);
  require("material", layout.material && !ctx.params().getBool("constant_material", false));
  if (auto normal = ctx.format("normal"); normal && formatInfo(*normal).components < layout.normalComponents)
    checks.slotError("normal", std::string("layout '") + layout.name + "' needs " +
                                   std::to_string(layout.normalComponents) + " components in 'normal', got " +
                                   std::string(formatName(*normal)));
}

PassTypeDesc makeGeometryPass() {
  using namespace rgraph::decl;
  const std::vector<Format> color = {Format::rgba8,  Format::srgb8_alpha8, Format::rgba16f, Format::rgba32f,
                                     Format::rg16f,  Format::rg8,          Format::r11g11b10f};
  PassTypeDesc d;
  d.name = "geometry";
  d.description = "Fills the G-buffer (multiple render targets) with the scene's opaque and masked surfaces";
  d.slots = {
      slot("position", Access::color_attachment, false, SlotDecl::Load::never,
           "world position (learnopengl, pbr, fp32 layouts)", {Format::rgba16f, Format::rgba32f}),
      slot("normal", Access::color_attachment, true, SlotDecl::Load::never,
           "world normal (xyz, or octahedral rg in the compact layout)", color),
      slot("albedo", Access::color_attachment, true, SlotDecl::Load::never, "albedo rgb + specular intensity", color),
      slot("material", Access::color_attachment, false, SlotDecl::Load::never,
           "metallic, roughness (, ao) (pbr, compact, fp32 layouts)", color),
      slot("depth", Access::depth_attachment, true, SlotDecl::Load::never, "scene depth",
           {Format::depth24, Format::depth32f, Format::depth24_stencil8, Format::depth32f_stencil8}),
  };
  d.params = {param("layout", ParamType::enumeration, std::string("pbr"),
                    "G-buffer layout: learnopengl, pbr (4x rgba16f), compact (no position, octahedral normal), fp32",
                    {"learnopengl", "pbr", "compact", "fp32"})};
  for (auto& p : lighting::constantMaterialParams()) d.params.push_back(std::move(p));
  d.adapt = lighting::adaptGBuffer;
  d.programs = [](const ParamSet& p) {  // HAS_NORMAL_MAPS follows the scene: both variants
    ShaderProgramSpec s = programSpec("scene.vert", "gbuffer.frag", lighting::gbufferDefines(p));
    s.ownSamplers = lighting::materialSamplers();
    return lighting::normalMapVariants(s);
  };
  d.check = checkGeometry;
  d.needsScene = true;
  d.create = [] { return std::make_unique<GeometryPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeGeometryPass);
}  // namespace
