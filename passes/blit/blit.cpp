// blit: copies (and scales, or resolves multisampling) one image into another
// with glBlitNamedFramebuffer. Depth/stencil images blit their depth (and
// stencil) with nearest filtering.
#include <GL/glcorearb.h>

#include "rgraph/format_sets.h"
#include "rgraph/gl/format.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class BlitPass final : public PassInstance {
 public:
  // The source as read framebuffer, the destination as draw framebuffer:
  // both from the executor's cache (a depth image at its depth point with no
  // colour buffers), so that passes drawing into the same images share them.
  void setup(PassContext& ctx) override {
    Format sf = ctx.format("src"), df = ctx.format("dst");
    srcExtent_ = ctx.extent("src");
    dstExtent_ = ctx.extent("dst");
    if (gl::isDepth(sf)) {
      mask_ = GL_DEPTH_BUFFER_BIT;
      if (gl::hasStencil(sf) && gl::hasStencil(df)) mask_ |= GL_STENCIL_BUFFER_BIT;
      filter_ = GL_NEAREST;
    } else {
      mask_ = GL_COLOR_BUFFER_BIT;
      filter_ = ctx.params().getString("filter") == "nearest" ? GL_NEAREST : GL_LINEAR;
    }
    // Same format: a raw copy. Otherwise sRGB images are decoded/encoded.
    rawCopy_ = sf == df;
    read_ = ctx.framebuffer({{"src"}}).id;
    draw_ = ctx.framebuffer({{"dst"}}).id;
  }

  void execute(PassContext& ctx) override {
    if (rawCopy_) glDisable(GL_FRAMEBUFFER_SRGB);
    glBlitNamedFramebuffer(read_, draw_, 0, 0, static_cast<GLint>(srcExtent_.width),
                           static_cast<GLint>(srcExtent_.height), 0, 0, static_cast<GLint>(dstExtent_.width),
                           static_cast<GLint>(dstExtent_.height), mask_, filter_);
    if (rawCopy_) glEnable(GL_FRAMEBUFFER_SRGB);
  }
  uint32_t changedState() const override { return 0; }  // sRGB put back

 private:
  uint32_t read_ = 0, draw_ = 0;  // the executor's
  Extent srcExtent_, dstExtent_;
  GLbitfield mask_ = GL_COLOR_BUFFER_BIT;
  GLenum filter_ = GL_LINEAR;
  bool rawCopy_ = true;
};

// What glBlitFramebuffer refuses, refused before the GPU (the graph itself
// refuses depth and colour mixed: depth_blit_format_mismatch).
std::vector<PassRule> blitRules() {
  PassRule single{"dst is not multisampled", [](const PassCheckContext& ctx, PassChecks& checks) {
                    if (ctx.samples("dst") > 1) checks.slotError("dst", "the destination may not be multisampled");
                  }};
  PassRule resolve{"a multisampled src (a resolve) and dst must have the same size",
                   [](const PassCheckContext& ctx, PassChecks& checks) {
                     const Extent se = ctx.extent("src"), de = ctx.extent("dst");
                     if (ctx.samples("src") > 1 && se.width > 0 && de.width > 0 && se != de)
                       checks.slotError("dst", "resolving a multisampled image needs equal sizes (src " +
                                                   extentText(se) + ", dst " + extentText(de) + ")");
                   }};
  return {single, resolve};
}

PassTypeDesc makeBlitPass() {
  PassTypeDesc d = decl::passType("blit", "Copies, scales or resolves an image into another (glBlitFramebuffer)");
  d.slots = {
      decl::slot("src", Access::blit_src, true, SlotDecl::Load::never,
               "source image (colour or depth; may be multisampled: resolved)", {}, true),
      decl::slot("dst", Access::blit_dst, true, SlotDecl::Load::optional,
               "destination image (same kind as src; depth needs the same format)"),
  };
  d.params = {decl::param("filter", ParamType::enumeration, std::string("linear"),
                        "filter when sizes differ (depth always uses nearest)", {"nearest", "linear"})};
  d.rules = blitRules();
  d.create = [] { return std::make_unique<BlitPass>(); };
  return d;
}

// depth_blit: the blit restricted to depth, named for what deferred pipelines
// use it for: copying the G-buffer depth into the depth buffer the forward pass
// draws with (LearnOpenGL's glBlitFramebuffer of GL_DEPTH_BUFFER_BIT). The
// graph refuses a depth blit between different formats before GL would.
PassTypeDesc makeDepthBlitPass() {
  PassTypeDesc d = makeBlitPass();
  d.name = "depth_blit";
  d.description = "Copies a depth (and stencil) image into another of the same format";
  d.slots[0].formats = depthFormats();
  d.slots[0].description = "source depth image (may be multisampled: resolved)";
  d.slots[1].formats = depthFormats();
  d.slots[1].description = "destination depth image (same format as src)";
  d.params.clear();
  return d;
}

RGRAPH_REGISTER_PASS(makeBlitPass);
RGRAPH_REGISTER_PASS(makeDepthBlitPass);
}  // namespace
