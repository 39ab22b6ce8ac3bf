// The SSAO plugin: screen-space ambient occlusion from the G-buffer
// (LearnOpenGL's SSAO chapter), for every G-buffer layout including compact.
//
//   ssao       G-buffer depth/position + normals -> ambient visibility (r8,
//              r16f or r32f; 1 open, 0 occluded), hemisphere kernel turned by
//              a 4x4 tile of random rotations
//   ssao_blur  box blur over the 4x4 tile, removing the rotation pattern
//   ssao_upsample  optional: SSAO run at a reduced size (ssao and ssao_blur
//              into smaller targets, e.g. {"scale": 0.5}) back to the
//              G-buffer's size, depth-aware (joint bilateral)
//
// The result goes to deferred_lighting's optional "ao" input, which scales
// the ambient term. Both outputs are slots the config binds to transient
// resources; the passes own only the 4x4 noise texture (constant data).
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/objects.h"
#include "rgraph/pass_decl.h"
#include "rgraph/passes/gbuffer_layout.h"
#include "rgraph/passes/lighting_options.h"
#include "rgraph/plugin.h"

namespace {
using namespace rgraph;

constexpr int kMaxKernel = 64;  // ssao.frag's u_kernel size
const std::vector<Format> kAoFormats = {Format::r8, Format::r16f, Format::r32f};

// Hemisphere samples (z >= 0), scaled so that more fall near the centre.
// A fixed seed: the same image every run.
std::vector<float> hemisphereKernel(int n) {
  std::mt19937 rng(0x55A0u);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> out;
  for (int i = 0; i < n; ++i) {
    float x = u(rng) * 2.0f - 1.0f, y = u(rng) * 2.0f - 1.0f, z = u(rng);
    float len = std::sqrt(x * x + y * y + z * z);
    if (len < 1e-4f) {
      x = 0.0f, y = 0.0f, z = 1.0f, len = 1.0f;
    }
    float scale = static_cast<float>(i) / static_cast<float>(n);
    scale = 0.1f + 0.9f * scale * scale;
    float r = u(rng) * scale / len;
    out.insert(out.end(), {x * r, y * r, z * r});
  }
  return out;
}

// 4x4 random rotation vectors around z.
gl::Texture noiseTexture() {
  std::mt19937 rng(0x4015Eu);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> texels;
  for (int i = 0; i < 16; ++i) texels.insert(texels.end(), {u(rng), u(rng), 0.0f, 0.0f});
  gl::Texture t = gl::createTexture(GL_TEXTURE_2D);
  glTextureStorage2D(t.id(), 1, GL_RGBA32F, 4, 4);
  glTextureSubImage2D(t.id(), 0, 0, 0, 4, 4, GL_RGBA, GL_FLOAT, texels.data());
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_REPEAT);
  return t;
}

std::vector<std::string> ssaoDefines(const ParamSet& p) { return {lighting::layoutDefine(p)}; }

// ------------------------------------------------------------ ssao

class SsaoPass final : public gl::FullscreenPass {
  void prepare(PassContext& ctx) override {
    noise_ = noiseTexture();
    const int n = static_cast<int>(std::clamp<int64_t>(ctx.params().getInt("kernel_size"), 1, kMaxKernel));
    kernel_ = hemisphereKernel(n);
    gbufferSize_ = ctx.extent("normal");
  }

  void update(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    const int n = static_cast<int>(kernel_.size() / 3);
    kernelU_.setVec3Array(kernel_.data(), n);
    kernelSize_.set(n);
    radius_.set(static_cast<float>(p.getNumber("radius")));
    bias_.set(static_cast<float>(p.getNumber("bias")));
    power_.set(static_cast<float>(p.getNumber("power")));
    gbufferSizeU_.set(static_cast<float>(gbufferSize_.width), static_cast<float>(gbufferSize_.height));
    const Extent target = ctx.framebufferExtent();
    targetTexel_.set(1.0f / static_cast<float>(target.width), 1.0f / static_cast<float>(target.height));
    ctx.gpuScene()->bindFrame();
    glBindTextureUnit(5, noise_.id());  // the pass's own constant texture (u_noise), not a slot
  }

  gl::Texture noise_;
  std::vector<float> kernel_;
  Extent gbufferSize_;
  ProgramUniform kernelU_{this, "u_kernel"}, kernelSize_{this, "u_kernelSize"}, radius_{this, "u_radius"};
  ProgramUniform bias_{this, "u_bias"}, power_{this, "u_power"}, gbufferSizeU_{this, "u_gbufferSize"};
  ProgramUniform targetTexel_{this, "u_targetTexel"};
};

// ------------------------------------------------------------ ssao_blur

class SsaoBlurPass final : public gl::FullscreenPass {
  void update(PassContext& ctx) override { size_.set(static_cast<int>(ctx.params().getInt("size"))); }
  ProgramUniform size_{this, "u_size"};
};

// ------------------------------------------------------------ ssao_upsample

class SsaoUpsamplePass final : public gl::FullscreenPass {
  void update(PassContext& ctx) override {
    const Extent g = ctx.framebufferExtent();
    gbufferSize_.set(static_cast<float>(g.width), static_cast<float>(g.height));
    tolerance_.set(static_cast<float>(ctx.params().getNumber("tolerance")));
    ctx.gpuScene()->bindFrame();
  }
  ProgramUniform gbufferSize_{this, "u_gbufferSize"}, tolerance_{this, "u_tolerance"};
};

// ------------------------------------------------------------ registration

// The G-buffer slot the layout reads positions from must be bound.
void checkPositionSlot(const PassCheckContext& ctx, PassChecks& checks) {
  const gbuffer::Layout& layout = gbuffer::of(ctx.params());
  const std::string needed = layout.positionSlot();
  if (!ctx.bound(needed))
    checks.slotError(needed, "input '" + needed + "' is required by layout '" + layout.name + "' but not bound");
}

// The rule `rgraph passes` prints for checkPositionSlot, naming each layout's slot.
PassRule positionRule() {
  PassRule position;
  position.text = "bind where \"layout\" keeps the position:";
  for (const auto& layout : gbuffer::layouts())
    position.text += (position.text.back() == ':' ? " " : ", ") + layout.name + " " + layout.positionSlot();
  position.check = checkPositionSlot;
  return position;
}

void registerUpsample(PluginHost& host) {
  using namespace rgraph::decl;
  const std::string frag = host.shaderPath("ssao_upsample.frag");
  PassTypeDesc d = passType("ssao_upsample",
      "SSAO at a reduced size back to the G-buffer's size, depth-aware (joint bilateral upsample)");
  d.slots = {
      slot("src", Access::sampled, true, SlotDecl::Load::never, "ssao_blur's output at the reduced size", kAoFormats),
      slot("position", Access::sampled, false, SlotDecl::Load::never,
           "G-buffer world position (every layout but compact)"),
      slot("depth", Access::sampled, false, SlotDecl::Load::never, "G-buffer depth (compact)", depthFormats()),
      slot("ao", Access::color_attachment, true, SlotDecl::Load::never,
           "ambient visibility at the G-buffer's size (for deferred_lighting's 'ao')", kAoFormats),
  };
  d.params = {
      lighting::layoutParam(),
      ranged("tolerance", ParamType::number, 0.05, 1e-4, 10.0,
             "relative view-depth difference at which a low-resolution texel's weight falls to 1/e"),
  };
  d.programs = [frag](const ParamSet& p) {
    return std::vector<ShaderProgramSpec>{
        gl::fullscreenProgram(frag, {{"src", "u_src", 0}, {"position", "g_position", 1}, {"depth", "g_depth", 4}},
                              ssaoDefines(p))};
  };
  PassRule sameSize;
  sameSize.text = "ao has the size of the G-buffer's position target";
  sameSize.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    const std::string g = gbuffer::of(ctx.params()).positionSlot();
    if (ctx.bound(g)) checkSameSize(ctx, checks, g, "ao");
  };
  d.rules = {positionRule(), sameSize, gbuffer::sameLayoutAsWriterRule()};
  d.needsScene = true;  // for the camera
  d.create = [] { return std::make_unique<SsaoUpsamplePass>(); };
  host.addPassType(std::move(d));
}

void registerSsao(PluginHost& host) {
  using namespace rgraph::decl;
  {
    const std::string frag = host.shaderPath("ssao.frag");
    PassTypeDesc d = passType("ssao",
        "Screen-space ambient occlusion (hemisphere kernel) from G-buffer depth/position and normals");
    d.slots = {
        slot("position", Access::sampled, false, SlotDecl::Load::never,
             "G-buffer world position (every layout but compact)"),
        slot("normal", Access::sampled, true, SlotDecl::Load::never, "G-buffer normal"),
        slot("depth", Access::sampled, false, SlotDecl::Load::never, "G-buffer depth (compact: rebuilds position)",
             depthFormats()),
        slot("ao", Access::color_attachment, true, SlotDecl::Load::never,
             "ambient visibility, 1 open .. 0 occluded (any size; noisy until ssao_blur)", kAoFormats),
    };
    d.params = {
        lighting::layoutParam(),
        ranged("radius", ParamType::number, 0.5, 1e-4, 1000.0, "hemisphere radius in scene units"),
        ranged("bias", ParamType::number, 0.025, 0.0, 100.0, "depth bias against self-occlusion (scene units)"),
        ranged("kernel_size", ParamType::integer, int64_t{32}, 1.0, static_cast<double>(kMaxKernel),
               "samples per pixel"),
        ranged("power", ParamType::number, 1.0, 0.0, 16.0, "visibility = (1 - occlusion)^power: contrast"),
    };
    d.programs = [frag](const ParamSet& p) {
      ShaderProgramSpec s = gl::fullscreenProgram(
          frag, {{"position", "g_position", 0}, {"normal", "g_normal", 1}, {"depth", "g_depth", 4}}, ssaoDefines(p));
      s.ownSamplers = {"u_noise"};  // the 4x4 rotation texture the pass binds on unit 5
      return std::vector<ShaderProgramSpec>{s};
    };
    d.rules = {positionRule(), gbuffer::sameLayoutAsWriterRule()};
    d.needsScene = true;  // for the camera
    d.create = [] { return std::make_unique<SsaoPass>(); };
    host.addPassType(std::move(d));
  }
  {
    const std::string frag = host.shaderPath("ssao_blur.frag");
    PassTypeDesc d = passType("ssao_blur", "SSAO 2/2: box blur over the 4x4 noise tile");
    d.slots = {
        slot("src", Access::sampled, true, SlotDecl::Load::never, "raw ssao output", kAoFormats),
        slot("ao", Access::color_attachment, true, SlotDecl::Load::never, "blurred ambient visibility (src's size)",
             kAoFormats),
    };
    d.params = {ranged("size", ParamType::integer, int64_t{2}, 0.0, 8.0,
                       "half width: averages 2*size x 2*size texels (2 matches the 4x4 noise tile; 0 copies)")};
    d.programs = gl::fullscreenPrograms(frag, {{"src", "u_src", 0}});
    d.rules = {sameSizeRule({"src", "ao"})};
    d.create = [] { return std::make_unique<SsaoBlurPass>(); };
    host.addPassType(std::move(d));
  }
  registerUpsample(host);
}

}  // namespace

RGRAPH_PLUGIN("ssao", registerSsao)
