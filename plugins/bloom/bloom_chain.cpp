// bloom_blur, method "mip_chain": Jimenez's (2014) bloom. Program 0 of the
// pass (bloom_down.frag) downsamples, program 1 (bloom_up.frag) upsamples;
// the order of programs is bloom.cpp's blurPrograms().
//
// The pass reads and writes the same texture ('temp', the atlas) in one frame:
// each draw reads rectangles other draws wrote and writes a rectangle no tap
// of its own reads (taps are clamped inside their level), which OpenGL 4.5
// allows when a glTextureBarrier separates the draws (section 9.3.1).
#include "bloom_chain.h"

#include <GL/glcorearb.h>

#include <algorithm>

#include "bloom_chain_layout.h"
#include "rgraph/error.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/uniform.h"

namespace rgraph::bloom {
namespace {

// The uniforms both chain programs share (bloom_chain.glsl).
struct RectUniforms {
  gl::Uniform imageSize, srcRect, dstRect;
  explicit RectUniforms(uint32_t program = 0)
      : imageSize(program, "u_imageSize"), srcRect(program, "u_srcRect"), dstRect(program, "u_dstRect") {}
  void set(Extent image, const Rect& src, const Rect& dst) const {
    imageSize.set(float(image.width), float(image.height));
    srcRect.set(float(src.x), float(src.y), float(src.width), float(src.height));
    dstRect.set(float(dst.x), float(dst.y), float(dst.width), float(dst.height));
  }
};

class ChainBlur final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    down_ = ctx.program(0), up_ = ctx.program(1);
    downRects_ = RectUniforms(down_), upRects_ = RectUniforms(up_);
    karis_ = gl::Uniform(down_, "u_karis");
    radius_ = gl::Uniform(up_, "u_radius"), scale_ = gl::Uniform(up_, "u_scale");
    tempFbo_ = ctx.framebuffer({{"temp"}}).id;
    dstFbo_ = ctx.framebuffer({{"dst"}}).id;
    triangle_ = std::make_unique<gl::FullscreenTriangle>();
  }

  void execute(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    const int levels = int(std::clamp<int64_t>(p.getInt("levels", 6), 1, kMaxLevels));
    const Extent src = ctx.extent("src"), temp = ctx.extent("temp"), dst = ctx.extent("dst");
    const std::vector<Rect> rects = chainLayout(src, levels);
    const uint32_t atlas = ctx.texture("temp");
    auto viewport = [](const Rect& r) { glViewport(GLint(r.x), GLint(r.y), GLsizei(r.width), GLsizei(r.height)); };

    // Down: src -> level 1 (Karis's average when asked) -> level 2 -> ...
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, tempFbo_);
    glUseProgram(down_);
    for (int k = 0; k < levels; ++k) {
      const bool first = k == 0;
      if (!first) glTextureBarrier();  // the previous level, written by the last draw
      glBindTextureUnit(0, first ? ctx.texture("src") : atlas);
      downRects_.set(first ? src : temp, first ? Rect{0, 0, src.width, src.height} : rects[k - 1], rects[k]);
      karis_.set(first && p.getBool("karis", true));
      viewport(rects[k]);
      triangle_->draw();
    }

    // Up: each level's tent added into the next larger one, which holds its
    // own downsample; the last draw writes level 1's tent, times 1 / levels,
    // into dst.
    glUseProgram(up_);
    glBindTextureUnit(0, atlas);
    radius_.set(float(p.getNumber("radius", 1.0)));
    scale_.set(1.0f);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE);  // add rgb, keep alpha
    for (int k = levels - 1; k >= 1; --k) {
      glTextureBarrier();
      upRects_.set(temp, rects[k], rects[k - 1]);
      viewport(rects[k - 1]);
      triangle_->draw();
    }
    glDisable(GL_BLEND);
    glTextureBarrier();
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, dstFbo_);
    upRects_.set(temp, rects[0], Rect{0, 0, dst.width, dst.height});
    scale_.set(1.0f / float(levels));
    viewport(Rect{0, 0, dst.width, dst.height});
    triangle_->draw();
  }

 private:
  uint32_t down_ = 0, up_ = 0;
  RectUniforms downRects_, upRects_;
  gl::Uniform karis_, radius_, scale_;
  uint32_t tempFbo_ = 0, dstFbo_ = 0;  // the executor's (PassContext::framebuffer)
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
};

}  // namespace

std::unique_ptr<PassInstance> createChainBlur() { return std::make_unique<ChainBlur>(); }

}  // namespace rgraph::bloom
