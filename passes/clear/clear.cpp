// clear: fills one colour attachment with a constant colour.
#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

class ClearPass final : public PassInstance {
 public:
  void execute(PassContext& ctx) override {
    std::vector<double> c = ctx.params().getVector("color");
    float v[4] = {0, 0, 0, 1};
    for (size_t i = 0; i < 4 && i < c.size(); ++i) v[i] = static_cast<float>(c[i]);
    glClearNamedFramebufferfv(ctx.framebuffer(), GL_COLOR, 0, v);
  }
};

PassTypeDesc makeClearPass() {
  PassTypeDesc d = decl::passType("clear", "Fills a colour image with a constant colour");
  d.slots = {decl::slot("color", Access::color_attachment, true, SlotDecl::Load::never,
                      "the image to fill (any colour format)")};
  d.params = {decl::param("color", ParamType::vec4, std::vector<double>{0.0, 0.0, 0.0, 1.0},
                        "RGBA fill colour (linear; encoded for srgb8_alpha8 images)")};
  d.create = [] { return std::make_unique<ClearPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeClearPass);
}  // namespace
