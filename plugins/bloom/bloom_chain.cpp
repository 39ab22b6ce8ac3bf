// bloom_blur, method "mip_chain": Jimenez's (2014) bloom. Program 0 of the
// pass (bloom_down.frag) downsamples, program 1 (bloom_up.frag) upsamples;
// the order of programs is bloom.cpp's blurPrograms().
//
// The chain lives in the mip levels of 'temp' (a texture of the source's
// size with "mips": levels): level k, at the origin of temp's mip level
// k - 1 (coveredLevels() says why not level k), is drawn through the
// executor's framebuffer of that mip level (PassContext::framebuffer) with
// the viewport on the part it covers, while level k - 1 (or k + 1 going up)
// is sampled through PassContext::texture(slot, sub), which shows that mip
// level alone. A draw never samples the level it writes, so no texture
// barrier is needed between draws.
#include "bloom_chain.h"

#include <GL/glcorearb.h>

#include <algorithm>
#include <vector>

#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/uniform.h"

namespace rgraph::bloom {
namespace {

Extent levelExtent(Extent e, int level) {
  return {std::max(1u, e.width >> level), std::max(1u, e.height >> level)};
}

// The part of each mip level of 'temp' the chain covers: chain level k
// (1..levels) is level k - 1 halved and rounded up, as the atlas had it
// (1080 rows: 540, 270, 135, 68, 34, 17), so every level spans the whole
// source. GL rounds odd mip levels down (135, 67, 33, 16), and the ratio of
// those sizes stretches the coarse levels' texels (by 5.5% at 16 rows:
// error against the bench's reference 0.70% instead of 0.68%), so level k
// lies at the origin of temp's mip level k - 1, which always holds it
// (ceil(n / 2) <= n). Aligning every level exactly to factor 2 instead (17 *
// 2^k rows, the source read clamped beyond its edge) measured worse: 0.78%.
std::vector<Extent> coveredLevels(Extent src, int levels) {
  std::vector<Extent> covered(size_t(levels) + 1, src);
  for (size_t k = 1; k < covered.size(); ++k)
    covered[k] = {(covered[k - 1].width + 1) / 2, (covered[k - 1].height + 1) / 2};
  return covered;
}

// The uniforms both chain programs share (bloom_chain.glsl).
struct SourceUniforms {
  gl::Uniform scale, limit, size;
  explicit SourceUniforms(uint32_t program = 0)
      : scale(program, "u_srcScale"), limit(program, "u_srcLimit"), size(program, "u_srcSize") {}
  // Reading `from` (the chain's texels at the origin of a level of `level`
  // texels) into `to` pixels.
  void set(Extent from, Extent to, Extent level) const {
    scale.set(float(from.width) / float(to.width), float(from.height) / float(to.height));
    limit.set(float(from.width), float(from.height));
    size.set(float(level.width), float(level.height));
  }
};

int chainLevels(const ParamSet& p) { return int(std::clamp<int64_t>(p.getInt("levels"), 1, kMaxLevels)); }

// Binds level `level` of 'temp' (or 'dst' for -1) and draws into its first `covered` pixels.
void bindCovered(PassContext& ctx, int level, Extent covered) {
  const PassFramebuffer fb =
      level < 0 ? gl::bindPassFramebuffer(ctx, {{"dst"}}) : gl::bindPassFramebuffer(ctx, {{"temp", uint32_t(level)}});
  if (covered == fb.extent) return;
  glViewport(0, 0, GLsizei(covered.width), GLsizei(covered.height));
  if (GlBindings* b = ctx.bindings()) b->viewportWidth = covered.width, b->viewportHeight = covered.height;
}

class ChainBlur final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    down_ = ctx.program(0), up_ = ctx.program(1);
    downSource_ = SourceUniforms(down_), upSource_ = SourceUniforms(up_);
    karis_ = gl::Uniform(down_, "u_karis");
    radius_ = gl::Uniform(up_, "u_radius"), scale_ = gl::Uniform(up_, "u_scale");
    triangle_ = ctx.emptyVertexArray() ? std::make_unique<gl::FullscreenTriangle>(ctx.emptyVertexArray())
                                       : std::make_unique<gl::FullscreenTriangle>();
    // That temp has the levels, bloom.cpp's check says before setup (validate refuses too few).
  }

  void execute(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    const int levels = chainLevels(p);
    const Extent temp = ctx.extent("temp");
    const std::vector<Extent> covered = coveredLevels(ctx.extent("src"), levels);
    auto mip = [&](int k) { return Subresource{uint32_t(k), 1, 0, Subresource::kAll}; };

    // Down: src -> level 1 (Karis's average when asked) -> level 2 -> ...,
    // chain level k into temp's mip level k - 1.
    gl::useProgram(ctx, down_);
    for (int k = 1; k <= levels; ++k) {
      const bool first = k == 1;
      // The level's texels outside the covered part are never written, but
      // the next draw's edge taps filter them at weight 0: undefined memory
      // (NaN under check-hazards' poison, garbage in an aliased texture) would
      // still reach the result through 0 * NaN. Zero them.
      const Extent level = levelExtent(temp, k - 1);
      if (covered[size_t(k)] != level) {
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearTexImage(ctx.texture("temp"), k - 1, GL_RGBA, GL_FLOAT, zero);
      }
      bindCovered(ctx, k - 1, covered[size_t(k)]);
      glBindTextureUnit(0, first ? ctx.texture("src") : ctx.texture("temp", mip(k - 2)));
      downSource_.set(covered[size_t(k - 1)], covered[size_t(k)], first ? ctx.extent("src") : levelExtent(temp, k - 2));
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
      bindCovered(ctx, k - 2, covered[size_t(k - 1)]);
      glBindTextureUnit(0, ctx.texture("temp", mip(k - 1)));
      upSource_.set(covered[size_t(k)], covered[size_t(k - 1)], levelExtent(temp, k - 1));
      triangle_->draw(ctx);
    }
    glDisable(GL_BLEND);
    bindCovered(ctx, -1, ctx.extent("dst"));
    glBindTextureUnit(0, ctx.texture("temp", mip(0)));
    upSource_.set(covered[1], ctx.extent("dst"), temp);
    scale_.set(1.0f / float(levels));
    triangle_->draw(ctx);
  }

  // Blending is put back; binds go through ctx.bindings().
  uint32_t changedState() const override { return 0; }

 private:
  uint32_t down_ = 0, up_ = 0;
  SourceUniforms downSource_, upSource_;
  gl::Uniform karis_, radius_, scale_;
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
};

}  // namespace

std::unique_ptr<PassInstance> createChainBlur() { return std::make_unique<ChainBlur>(); }

}  // namespace rgraph::bloom
