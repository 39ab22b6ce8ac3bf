// bloom_blur, method "mip_chain": Jimenez's (2014) bloom. Program 0 of the
// pass (bloom_down.frag) downsamples, program 1 (bloom_up.frag) upsamples;
// the order of programs is bloom.cpp's blurPrograms().
//
// The chain lives in the mip levels of 'temp' (a texture of the source's
// size with "mips": levels + 1): level k is drawn through the executor's
// framebuffer of that level (PassContext::framebuffer) while level k - 1 (or
// k + 1 going up) is sampled through PassContext::texture(slot, sub), which
// shows that level alone. A draw never samples the level it writes, so no
// texture barrier is needed between draws.
#include "bloom_chain.h"

#include <GL/glcorearb.h>

#include <algorithm>

#include "rgraph/error.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/uniform.h"

namespace rgraph::bloom {
namespace {

Extent levelExtent(Extent e, int level) {
  return {std::max(1u, e.width >> level), std::max(1u, e.height >> level)};
}

// The uniforms both chain programs share (bloom_chain.glsl).
struct SizeUniforms {
  gl::Uniform srcSize, dstSize;
  explicit SizeUniforms(uint32_t program = 0) : srcSize(program, "u_srcSize"), dstSize(program, "u_dstSize") {}
  void set(Extent src, Extent dst) const {
    srcSize.set(float(src.width), float(src.height));
    dstSize.set(float(dst.width), float(dst.height));
  }
};

int chainLevels(const ParamSet& p) { return int(std::clamp<int64_t>(p.getInt("levels"), 1, kMaxLevels)); }

class ChainBlur final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    down_ = ctx.program(0), up_ = ctx.program(1);
    downSizes_ = SizeUniforms(down_), upSizes_ = SizeUniforms(up_);
    karis_ = gl::Uniform(down_, "u_karis");
    radius_ = gl::Uniform(up_, "u_radius"), scale_ = gl::Uniform(up_, "u_scale");
    triangle_ = ctx.emptyVertexArray() ? std::make_unique<gl::FullscreenTriangle>(ctx.emptyVertexArray())
                                       : std::make_unique<gl::FullscreenTriangle>();
    const int levels = chainLevels(ctx.params());
    try {
      ctx.framebuffer({{"temp", uint32_t(levels)}});  // its deepest level exists
    } catch (const RuntimeError& e) {
      throw RuntimeError(std::string(e.what()) + " (method 'mip_chain' draws its " + std::to_string(levels) +
                         " levels into temp's mip levels 1.." + std::to_string(levels) + ": give temp \"mips\": " +
                         std::to_string(levels + 1) + ")");
    }
  }

  void execute(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    const int levels = chainLevels(p);
    const Extent temp = ctx.extent("temp");
    auto level = [&](int k) { return Subresource{uint32_t(k), 1, 0, Subresource::kAll}; };

    // Down: src -> level 1 (Karis's average when asked) -> level 2 -> ...
    gl::useProgram(ctx, down_);
    for (int k = 1; k <= levels; ++k) {
      const bool first = k == 1;
      const PassFramebuffer fb = gl::bindPassFramebuffer(ctx, {{"temp", uint32_t(k)}});
      glBindTextureUnit(0, first ? ctx.texture("src") : ctx.texture("temp", level(k - 1)));
      downSizes_.set(first ? ctx.extent("src") : levelExtent(temp, k - 1), fb.extent);
      karis_.set(first && p.getBool("karis"));
      triangle_->draw(ctx);
    }

    // Up: each level's tent added into the next larger one, which holds its
    // own downsample; the last draw writes level 1's tent, times 1 / levels,
    // into dst.
    gl::useProgram(ctx, up_);
    radius_.set(float(p.getNumber("radius")));
    scale_.set(1.0f);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);  // add rgb, keep alpha
    for (int k = levels; k >= 2; --k) {
      const PassFramebuffer fb = gl::bindPassFramebuffer(ctx, {{"temp", uint32_t(k - 1)}});
      glBindTextureUnit(0, ctx.texture("temp", level(k)));
      upSizes_.set(levelExtent(temp, k), fb.extent);
      triangle_->draw(ctx);
    }
    glDisable(GL_BLEND);
    const PassFramebuffer fb = gl::bindPassFramebuffer(ctx, {{"dst"}});
    glBindTextureUnit(0, ctx.texture("temp", level(1)));
    upSizes_.set(levelExtent(temp, 1), fb.extent);
    scale_.set(1.0f / float(levels));
    triangle_->draw(ctx);
  }

  // Blending is put back; binds go through ctx.bindings().
  uint32_t changedState() const override { return 0; }

 private:
  uint32_t down_ = 0, up_ = 0;
  SizeUniforms downSizes_, upSizes_;
  gl::Uniform karis_, radius_, scale_;
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
};

}  // namespace

std::unique_ptr<PassInstance> createChainBlur() { return std::make_unique<ChainBlur>(); }

}  // namespace rgraph::bloom
