// The bloom plugin: three pass types that a pipeline chains before tone
// mapping (LearnOpenGL's bloom chapter, with a soft threshold):
//
//   bloom_bright     HDR image -> its bright part (threshold, knee), at the
//                    size of the target the config binds (full or reduced)
//   bloom_blur       method "gaussian": separable 9-tap Gaussian,
//                    `iterations` times horizontal + vertical, ping-ponging
//                    between its two targets; method "mip_chain": Jimenez's
//                    downsample/upsample chain (bloom_chain.h), its levels
//                    in the mip levels of 'temp'
//   bloom_composite  HDR + intensity * blurred -> a new HDR image (or added
//                    into the HDR target it loads)
//
// Every intermediate texture is a slot the config binds to a transient
// resource, so the graph sees their lifetimes and aliases them (e.g. with
// G-buffer targets that are dead after lighting). The passes own no GL
// objects: the blur renders into each of its two targets in turn through
// the executor's framebuffers (PassContext::framebuffer).
#include <GL/glcorearb.h>

#include "bloom_chain.h"
#include "rgraph/error.h"
#include "rgraph/format_sets.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/plugin.h"

namespace {
using namespace rgraph;

// ------------------------------------------------------------ bloom_bright

class BrightPass final : public gl::FullscreenPass {
  void update(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    threshold_.set(static_cast<float>(p.getNumber("threshold")));
    knee_.set(static_cast<float>(p.getNumber("knee")));
    clamp_.set(static_cast<float>(p.getNumber("clamp")));
  }
  ProgramUniform threshold_{this, "u_threshold"}, knee_{this, "u_knee"}, clamp_{this, "u_clamp"};
};

// ------------------------------------------------------------ bloom_blur

class GaussianBlur final : public gl::FullscreenPass {
  // Draws into its two targets in turn, through the executor's framebuffers of each.
  void execute(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    const int iterations = static_cast<int>(p.getInt("iterations"));
    const float radius = static_cast<float>(p.getNumber("radius"));
    const Extent size = ctx.extent("dst");
    gl::useProgram(ctx, program());
    targetTexel_.set(1.0f / static_cast<float>(size.width), 1.0f / static_cast<float>(size.height));
    // One blur direction from `source` into `fbo`; taps `radius` source texels apart.
    auto direction = [&](uint32_t source, Extent sourceSize, std::string_view target, bool horizontal) {
      gl::bindPassFramebuffer(ctx, {{target}});
      glBindTextureUnit(0, source);  // the ping-pong reads a different target each draw
      step_.set(horizontal ? radius / static_cast<float>(sourceSize.width) : 0.0f,
                horizontal ? 0.0f : radius / static_cast<float>(sourceSize.height));
      drawTriangle();
    };
    // src -> temp -> dst, then dst -> temp -> dst for every further iteration.
    for (int i = 0; i < iterations; ++i) {
      if (i == 0)
        direction(ctx.texture("src"), ctx.extent("src"), "temp", true);
      else
        direction(ctx.texture("dst"), size, "temp", true);
      direction(ctx.texture("temp"), size, "dst", false);
    }
  }

  ProgramUniform targetTexel_{this, "u_targetTexel"}, step_{this, "u_step"};
};

// The method a bloom_blur pass runs, chosen from its parameters at setup
// (create() has no parameters).
class BlurPass final : public PassInstance {
  void setup(PassContext& ctx) override {
    if (!impl_)
      impl_ = ctx.params().getString("method") == "mip_chain" ? bloom::createChainBlur()
                                                                           : std::make_unique<GaussianBlur>();
    impl_->setup(ctx);
  }
  void execute(PassContext& ctx) override { impl_->execute(ctx); }
  std::unique_ptr<PassInstance> impl_;
};

// ------------------------------------------------------------ bloom_composite

class CompositePass final : public gl::FullscreenPass {
  void update(PassContext& ctx) override {
    const bool hasHdr = ctx.bound("hdr");
    if (!hasHdr) {
      glEnable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);  // add rgb, keep alpha
    }
    hasHdr_.set(hasHdr);
    intensity_.set(static_cast<float>(ctx.params().getNumber("intensity")));
  }
  ProgramUniform hasHdr_{this, "u_hasHdr"}, intensity_{this, "u_intensity"};
};

// ------------------------------------------------------------ registration

bool chainMethod(const ParamSet& p) { return p.getString("method") == "mip_chain"; }

// mip_chain: temp's mip level k - 1 holds the chain's level k, half the
// source's size k times (rounded up), so temp has the source's size (that dst
// and temp have one size, the graph checks: they are a pass's attachments)
// and at least `levels` mip levels.
void checkBlur(const PassCheckContext& ctx, PassChecks& checks) {
  if (!chainMethod(ctx.params())) return;
  const Extent src = ctx.extent("src"), temp = ctx.extent("temp");
  if (src.width == 0 || temp.width == 0) return;  // unresolved: reported elsewhere
  const int levels = int(ctx.params().getInt("levels"));
  const std::string draws = "method 'mip_chain' draws its " + std::to_string(levels) + " levels into temp's mip levels 0.." +
                            std::to_string(levels - 1) + ", halving the source's size: ";
  if (temp != src)
    checks.slotError("temp", draws + "temp must have the source's size, " + extentText(src) + ", and is " +
                                 extentText(temp) + " (give it the source's size and \"mips\": " +
                                 std::to_string(levels) + ")");
  else if (const CheckedSlot* t = ctx.find("temp"); t && t->mips != 0 && t->mips < uint32_t(levels))
    checks.slotError("temp", draws + "'" + t->resource + "' has " + std::to_string(t->mips) + " mip level" +
                                 (t->mips == 1 ? "" : "s") + " (give it \"mips\": " + std::to_string(levels) +
                                 ", or lower \"levels\" to " + std::to_string(t->mips) + ")");
}

// gaussian: one program; mip_chain: the downsample then the upsample (bloom_chain.cpp's order).
std::function<std::vector<ShaderProgramSpec>(const ParamSet&)> blurPrograms(const PluginHost& host) {
  ShaderProgramSpec gaussian = gl::fullscreenProgram(host.shaderPath("bloom_blur.frag"), {{"src", "u_image", 0}});
  gaussian.drawsToAttachments = false;  // draws into dst and temp in turn (PassContext::framebuffer)
  std::vector<ShaderProgramSpec> chain;
  for (const char* frag : {"bloom_down.frag", "bloom_up.frag"}) {
    ShaderProgramSpec s = gl::fullscreenProgram(host.shaderPath(frag));
    s.ownSamplers = {"u_image"};  // src or one level of 'temp', bound by the pass for each draw
    s.drawsToAttachments = false;
    chain.push_back(s);
  }
  return [gaussian, chain](const ParamSet& p) {
    return chainMethod(p) ? chain : std::vector<ShaderProgramSpec>{gaussian};
  };
}

// Either a separate HDR input or the bloom added into a loaded target.
std::vector<PassRule> compositeRules() {
  PassRule either{"bind either hdr or color in inputs (load: add the bloom into it), not both",
                  [](const PassCheckContext& ctx, PassChecks& checks) {
                    const bool loads = ctx.loads("color");
                    if (loads == ctx.bound("hdr"))
                      checks.slotError(loads ? "hdr" : "color",
                                       "bind either 'hdr' (writes hdr + bloom into 'color') or load 'color' (adds "
                                       "the bloom into it), not " + std::string(loads ? "both" : "neither"));
                  }};
  return {either, sameSizeRule({"hdr", "color"})};
}

void registerBloom(PluginHost& host) {
  using namespace rgraph::decl;
  {
    const std::string frag = host.shaderPath("bloom_bright.frag");
    PassTypeDesc d = passType("bloom_bright",
        "Bloom 1/3: the bright part of an HDR image (soft threshold), at the bright target's size");
    d.slots = {
        slot("hdr", Access::sampled, true, SlotDecl::Load::never, "HDR image", hdrFormats()),
        slot("bright", Access::color_attachment, true, SlotDecl::Load::never,
             "its bright part (any size: a smaller target is a 2x2 box downsample at half size)", hdrFormats()),
    };
    d.params = {
        ranged("threshold", ParamType::number, 1.0, 0.0, 1000.0, "brightness (max channel) where bloom starts"),
        ranged("knee", ParamType::number, 0.5, 0.0, 100.0, "soft transition below the threshold (0: hard cut)"),
        ranged("clamp", ParamType::number, 64.0, 0.0, 65504.0, "brightest value kept, against fireflies"),
    };
    d.programs = gl::fullscreenPrograms(frag, {{"hdr", "u_hdr", 0}});
    d.create = [] { return std::make_unique<BrightPass>(); };
    host.addPassType(std::move(d));
  }
  {
    PassTypeDesc d = passType("bloom_blur",
        "Bloom 2/3: a Gaussian ping-pong between 'temp' and 'dst' (LearnOpenGL), or a mip chain "
        "(Jimenez 2014) in the mip levels of 'temp'");
    d.slots = {
        slot("src", Access::sampled, true, SlotDecl::Load::never, "image to blur (e.g. bloom_bright's output)",
             hdrFormats()),
        slot("dst", Access::color_attachment, true, SlotDecl::Load::never, "the blurred image (temp's size)",
             hdrFormats()),
        slot("temp", Access::color_attachment, true, SlotDecl::Load::never,
             "scratch: gaussian, dst's twin (the other half of the ping-pong); mip_chain, the chain's levels in its "
             "mip levels 0..levels - 1 (the source's size, \"mips\": levels)",
             hdrFormats()),
    };
    d.params = {
        param("method", ParamType::enumeration, std::string("gaussian"),
              "gaussian: 9-tap ping-pong at dst's size; mip_chain: 13-tap downsamples from half the source's size, "
              "3x3 tent upsamples added level by level",
              {"gaussian", "mip_chain"}),
        ranged("iterations", ParamType::integer, int64_t{5}, 1.0, 64.0,
               "gaussian: horizontal + vertical passes (the blur widens with their square root)"),
        ranged("radius", ParamType::number, 1.0, 0.0, 16.0,
               "spacing of the taps in source texels (gaussian: the 9 taps; mip_chain: the tent's)"),
        ranged("levels", ParamType::integer, int64_t{6}, 1.0, double(bloom::kMaxLevels),
               "mip_chain: levels below the source (each half the last; the blur widens about twofold per level)"),
        param("karis", ParamType::boolean, true,
              "mip_chain: weight the first downsample's boxes by 1 / (1 + luma) against fireflies"),
    };
    d.programs = blurPrograms(host);
    d.rules = {PassRule{"method \"mip_chain\" draws its levels into temp's mip levels: give temp the size of src and "
                        "\"mips\": levels",
                        checkBlur}};
    d.create = [] { return std::make_unique<BlurPass>(); };
    host.addPassType(std::move(d));
  }
  {
    const std::string frag = host.shaderPath("bloom_composite.frag");
    PassTypeDesc d = passType("bloom_composite",
        "Bloom 3/3: HDR + intensity * bloom into a new HDR image (or added into a loaded 'color')");
    d.slots = {
        slot("hdr", Access::sampled, false, SlotDecl::Load::never,
             "HDR image (same size as 'color'); leave unbound to add into a loaded 'color' instead", hdrFormats()),
        // Scaled up to the HDR image's size: bilinear.
        sampledWith(slot("bloom", Access::sampled, true, SlotDecl::Load::never, "blurred bright image (any size)",
                         hdrFormats()),
                    bilinearClamped()),
        slot("color", Access::color_attachment, true, SlotDecl::Load::optional, "the HDR image with bloom",
             hdrFormats()),
    };
    d.params = {ranged("intensity", ParamType::number, 1.0, 0.0, 100.0, "bloom strength")};
    d.programs = gl::fullscreenPrograms(frag, {{"hdr", "u_hdr", 0, /*optional=*/true}, {"bloom", "u_bloom", 1}});
    d.rules = compositeRules();
    d.create = [] { return std::make_unique<CompositePass>(); };
    host.addPassType(std::move(d));
  }
}

}  // namespace

RGRAPH_PLUGIN("bloom", registerBloom)
