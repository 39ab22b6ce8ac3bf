// shadow_moments: the EVSM moments of the shadow atlas (shadow_filter evsm),
// blurred and mip-mapped, for the lighting passes' "shadow_moments" slot.
//
// Per atlas layer: the depths (perspective maps' linearised) warped by
// exp(+c x) and -exp(-c x), their squares beside them (4 moments), averaged
// over the atlas texels each moments texel covers into level 0 of
// `moments`; that box-blurred along x into `scratch`, and back along y; then
// the mip chain. (Converting first reads each atlas texel once: blurring the
// conversion along x read it 2 r + 1 times, 3x the time at 512 of 2048.)
// The exponents travel in the info buffer (the shadow_map pass's params),
// clamped to what the moments' format holds (shadows::evsmMaxExponent).
//
// Like shadow_map, the pass is a template: its adapt hook sizes `moments`
// and `scratch` for the scene (the expansion is one instance, "<name>.blur";
// the graph reshapes only what an expanded template binds) and removes it
// with nothing to shadow, as the atlas's writers are. The hook cannot see
// the shadow_map pass's max_lights and cascades, so it gives layers to every
// casting light in view (kMaxMaps at most) at four cascades for the sun: as
// many as the atlas or more, never fewer (execute() checks). The extra
// layers are never drawn nor sampled.
#include <GL/glcorearb.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/shadow_sampling.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;
using Kind = SceneFeatures::ShadowLight::Kind;

uint32_t layersOf(uint32_t texture) {
  GLint layers = 0;
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_DEPTH, &layers);
  return static_cast<uint32_t>(std::max(layers, 1));
}

class ShadowMomentsPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    if (ctx.params().getString("role") == "template")
      throw RuntimeError("shadow_moments pass '" + ctx.passName() +
                         "' was not expanded: it is a template the scene sizes (render with scene adaptation on, "
                         "as rgraph render does)");
    convert_ = ctx.program(0), blur_ = ctx.program(1);
    triangle_ = ctx.emptyVertexArray() ? std::make_unique<gl::FullscreenTriangle>(ctx.emptyVertexArray())
                                       : std::make_unique<gl::FullscreenTriangle>();
  }

  void execute(PassContext& ctx) override {
    const uint32_t atlasLayers = layersOf(ctx.texture("atlas"));
    const uint32_t momentLayers = layersOf(ctx.texture("moments"));
    if (momentLayers < atlasLayers || layersOf(ctx.texture("scratch")) < atlasLayers)
      throw RuntimeError("shadow_moments pass '" + ctx.passName() + "': the atlas has " +
                         std::to_string(atlasLayers) + " layers but 'moments' or 'scratch' has fewer (" +
                         std::to_string(momentLayers) + "): bind resources the pass sizes, not imported ones");
    const Extent size = ctx.extent("moments");
    const int radius = static_cast<int>(ctx.params().getInt("blur"));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shadows::kInfoBinding, ctx.buffer("info"));
    for (uint32_t program : {convert_, blur_})
      glProgramUniform2i(program, glGetUniformLocation(program, "u_momentsSize"), static_cast<GLint>(size.width),
                         static_cast<GLint>(size.height));
    glProgramUniform1f(convert_, glGetUniformLocation(convert_, "u_evsmMaxExponent"),
                       shadows::evsmMaxExponent(ctx.format("moments")));
    glProgramUniform1i(blur_, glGetUniformLocation(blur_, "u_radius"), radius);
    const GLint direction = glGetUniformLocation(blur_, "u_direction");
    // atlas -> moments level 0 (the atlas is on unit 0, bound by the executor).
    gl::useProgram(ctx, convert_);
    drawLayers(ctx, convert_, "moments", atlasLayers);
    // Along x: moments level 0 -> scratch; along y: scratch -> moments level 0.
    // Neither draw samples what it writes.
    gl::useProgram(ctx, blur_);
    glProgramUniform2i(blur_, direction, 1, 0);
    glBindTextureUnit(1, ctx.texture("moments"));  // texelFetch reads level 0; no level is attached meanwhile
    drawLayers(ctx, blur_, "scratch", atlasLayers);
    glProgramUniform2i(blur_, direction, 0, 1);
    glBindTextureUnit(1, ctx.texture("scratch"));
    drawLayers(ctx, blur_, "moments", atlasLayers);
    glBindTextureUnit(1, 0);
    // Each level the 2x2 average of the one above (GL's box filter), so a
    // receiver far from the camera reads the moments of its pixel's footprint.
    glGenerateTextureMipmap(ctx.texture("moments"));
  }
  // Binds go through ctx.bindings(); no blend, depth or other state is set.
  uint32_t changedState() const override { return 0; }

 private:
  void drawLayers(PassContext& ctx, uint32_t program, const char* slot, uint32_t layers) {
    const GLint at = glGetUniformLocation(program, "u_layer");
    for (uint32_t layer = 0; layer < layers; ++layer) {
      gl::bindPassFramebuffer(ctx, {{slot, 0, layer}});
      glProgramUniform1i(program, at, static_cast<GLint>(layer));
      triangle_->draw(ctx);
    }
  }

  uint32_t convert_ = 0, blur_ = 0;
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
};

// Layers for every casting light in view: the atlas's count, or more when the
// shadow_map pass gives fewer lights maps or the sun fewer cascades.
uint32_t layersFor(const SceneFeatures& f) {
  uint32_t layers = 0;
  for (size_t i = 0; i < f.shadowLights.size() && i < shadows::kMaxMaps; ++i)
    layers += f.shadowLights[i].kind == Kind::directional ? 4u : f.shadowLights[i].kind == Kind::point ? 6u : 1u;
  return std::max(layers, 2u);  // as the atlas: one layer would not be an array
}

void expand(const SceneFeatures& f, PassAdaptation& a) {
  if (a.params.getString("role") != "template") return;
  a.expand.emplace();
  if (!f.shadowCasters) {
    a.notes.push_back("no primitive casts a shadow: no shadow moments");
    return;
  }
  if (f.shadowLights.empty()) {
    a.notes.push_back("no casting light reaches the view: no shadow moments");
    return;
  }
  const uint32_t layers = layersFor(f);
  const uint32_t size = static_cast<uint32_t>(a.params.getInt("size"));
  ExpandedPass blur{"blur", a.params, {{"atlas", std::nullopt}, {"info", std::nullopt}, {"scratch", std::nullopt},
                                       {"moments", std::nullopt}}};
  blur.params.set("role", std::string("blur"));
  a.expand->push_back(std::move(blur));
  a.reshape.push_back({"moments", layers, size, 0});
  a.reshape.push_back({"scratch", layers, size, 0});
  // 16 bytes a texel at rgba32f: every mip level of the moments, and the scratch's one.
  uint64_t chain = 0;
  for (uint64_t s = size; s > 0; s /= 2) chain += s * s;
  const uint64_t moments = chain * layers * 16, scratch = uint64_t(size) * size * layers * 16;
  a.notes.push_back(std::to_string(layers) + " moments layer(s) of " + std::to_string(size) + "^2: " +
                    std::to_string(moments) + " bytes with mips and " + std::to_string(scratch) +
                    " of scratch at rgba32f");
}

PassTypeDesc makeShadowMomentsPass() {
  using namespace rgraph::decl;
  PassTypeDesc d = passType("shadow_moments",
                            "EVSM moments of the shadow atlas (4 moments, exponential warps), box-blurred in two "
                            "separable draws per layer and mip-mapped, for shadow_filter evsm");
  SamplerState raw;
  raw.filter = SamplerState::Filter::nearest;
  const std::vector<Format> moments = {Format::rgba32f, Format::rgba16f};
  d.slots = {
      sampledWith(slot("atlas", Access::sampled, true, SlotDecl::Load::never,
                       "the shadow_map pass's depth atlas (raw depths)", depthFormats()),
                  raw),
      slot("info", Access::storage_read, true, SlotDecl::Load::never,
           "the shadow_map pass's info buffer (which layers are perspective; the exponents)"),
      slot("scratch", Access::color_attachment, true, SlotDecl::Load::never,
           "the moments blurred along x (a 2D array as 'moments', one level; sized by the expansion)", moments),
      slot("moments", Access::color_attachment, true, SlotDecl::Load::never,
           "the moments, blurred, every mip level (declare \"mips\": \"full\"; sized by the expansion). rgba32f "
           "holds exponents to 42, rgba16f to 5.5 (more light leaks)",
           moments),
  };
  d.params = {
      ranged("size", ParamType::integer, int64_t{512}, 16.0, 16384.0,
             "moments texels per side of each layer (the atlas's size or less: each texel averages the depths it "
             "covers)"),
      ranged("blur", ParamType::integer, int64_t{2}, 0.0, 8.0,
             "box blur radius in moments texels (2 r + 1 taps along x, then along y)"),
      param("role", ParamType::enumeration, std::string("template"),
            "template (sized at adapt time) or blur (set by the expansion)", {"template", "blur"}),
  };
  d.needsScene = true;
  d.adapt = expand;
  d.programs = [](const ParamSet&) {
    const std::vector<std::string> defines = {"SHADOW_INFO_ONLY",
                                              "SHADOW_MAX_MAPS=" + std::to_string(shadows::kMaxMaps)};
    ShaderProgramSpec convert = gl::fullscreenProgram("shadow_moments.frag", {{"atlas", "u_depths", 0}}, defines);
    convert.defines.push_back("MOMENTS_CONVERT");
    ShaderProgramSpec blur = gl::fullscreenProgram("shadow_moments.frag", {}, defines);
    blur.ownSamplers = {"u_source"};
    // Each draws into one layer of a framebuffer of its own choosing.
    convert.drawsToAttachments = blur.drawsToAttachments = false;
    return std::vector<ShaderProgramSpec>{convert, blur};
  };
  d.create = [] { return std::make_unique<ShadowMomentsPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeShadowMomentsPass);
}  // namespace
