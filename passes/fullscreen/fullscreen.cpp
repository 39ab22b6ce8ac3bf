// fullscreen: runs a fragment shader over a fullscreen triangle into its
// colour attachment(s), with up to four sampled inputs.
#include <GL/glcorearb.h>

#include <array>

#include "rgraph/error.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"

namespace {
using namespace rgraph;

constexpr std::array<const char*, 4> kInputs = {"input0", "input1", "input2", "input3"};

struct DepthFunc {
  const char* name;
  GLenum func;
};
constexpr std::array<DepthFunc, 8> kDepthFuncs = {{{"always", GL_ALWAYS},
                                                  {"less", GL_LESS},
                                                  {"lequal", GL_LEQUAL},
                                                  {"greater", GL_GREATER},
                                                  {"gequal", GL_GEQUAL},
                                                  {"equal", GL_EQUAL},
                                                  {"never", GL_NEVER},
                                                  {"off", 0}}};

class FullscreenShaderPass final : public gl::FullscreenPass {
  // Parameters read once; update() only sets uniforms and state (the
  // program may be shared with other fullscreen passes).
  void prepare(PassContext& ctx) override {
    std::string df = ctx.params().getString("depth_func");
    depthFunc_ = GL_ALWAYS;
    for (const auto& f : kDepthFuncs)
      if (df == f.name) depthFunc_ = f.func;
    if (!ctx.bound("depth")) depthFunc_ = 0;
    std::string blend = ctx.params().getString("blend");
    blend_ = blend == "alpha" ? 1 : blend == "additive" ? 2 : 0;
    std::vector<double> c = ctx.params().getVector("color");
    c.resize(4, 1.0);
    for (size_t i = 0; i < 4; ++i) colorValue_[i] = static_cast<float>(c[i]);
    valueNumber_ = static_cast<float>(ctx.params().getNumber("value"));
    const Extent e = ctx.framebufferExtent();
    resolutionValue_[0] = static_cast<float>(e.width);
    resolutionValue_[1] = static_cast<float>(e.height);
  }

  void update(PassContext&) override {
    resolution_.set(resolutionValue_[0], resolutionValue_[1]);
    color_.set(colorValue_[0], colorValue_[1], colorValue_[2], colorValue_[3]);
    value_.set(valueNumber_);
    if (depthFunc_ != 0) {
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(depthFunc_);
    }
    if (blend_ != 0) {
      glEnable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      if (blend_ == 1)
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      else
        glBlendFunc(GL_ONE, GL_ONE);
    }
  }

  uint32_t changedState() const override {
    return (blend_ != 0 ? kGlStateBlend : 0u) | (depthFunc_ != 0 ? kGlStateDepth : 0u);
  }

  ProgramUniform resolution_{this, "u_resolution"}, color_{this, "u_color"}, value_{this, "u_value"};
  GLenum depthFunc_ = GL_ALWAYS;  // 0: no depth test
  int blend_ = 0;
  float colorValue_[4] = {1, 1, 1, 1}, valueNumber_ = 0, resolutionValue_[2] = {0, 0};
};

PassTypeDesc makeFullscreenPass() {
  PassTypeDesc d = decl::passType("fullscreen", "Runs a fragment shader over the whole image (fullscreen triangle)");
  for (size_t i = 0; i < kInputs.size(); ++i)
    d.slots.push_back(decl::slot(kInputs[i], Access::sampled, false, SlotDecl::Load::never,
                               "texture bound to `uniform sampler2D " + std::string(kInputs[i]) + "` on unit " +
                                   std::to_string(i)));
  d.slots.push_back(decl::slot("color", Access::color_attachment, true, SlotDecl::Load::optional,
                             "colour output at location 0 (bind an input too to blend into it)"));
  for (int i = 1; i <= 3; ++i)
    d.slots.push_back(decl::slot("color" + std::to_string(i), Access::color_attachment, false,
                               SlotDecl::Load::optional, "extra colour output at location " + std::to_string(i)));
  d.slots.push_back(decl::slot("depth", Access::depth_attachment, false, SlotDecl::Load::optional,
                             "optional depth attachment, tested with depth_func (write gl_FragDepth)"));
  d.params = {
      decl::param("shader", ParamType::shader, std::string(),
                "fragment shader file under shaders/ (uniforms: input0..3, u_resolution, u_color, u_value)"),
      decl::param("color", ParamType::vec4, std::vector<double>{1.0, 1.0, 1.0, 1.0}, "value of `uniform vec4 u_color`"),
      decl::param("value", ParamType::number, 0.0, "value of `uniform float u_value`"),
      decl::param("depth_func", ParamType::enumeration, std::string("always"),
                "depth test when a depth slot is bound ('off' disables test and writes)",
                {"always", "less", "lequal", "greater", "gequal", "equal", "never", "off"}),
      decl::param("blend", ParamType::enumeration, std::string("none"), "blending into the colour output(s)",
                {"none", "alpha", "additive"}),
  };
  d.programs = [](const ParamSet& p) {
    ShaderProgramSpec s = gl::fullscreenProgram(p.getString("shader"));
    if (s.frag.empty()) throw RuntimeError("parameter 'shader' is empty: name a fragment shader");
    for (size_t i = 0; i < kInputs.size(); ++i) s.samplers.push_back({kInputs[i], kInputs[i], static_cast<int>(i)});
    s.blendsSourceAlpha = p.getString("blend") == "alpha";
    return std::vector<ShaderProgramSpec>{std::move(s)};
  };
  d.create = [] { return std::make_unique<FullscreenShaderPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeFullscreenPass);
}  // namespace
