// fullscreen: runs a fragment shader over a fullscreen triangle into its
// colour attachment(s), with up to four sampled inputs.
#include <GL/glcorearb.h>

#include <array>

#include "rgraph/error.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/shader_library.h"
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

class FullscreenPass final : public PassInstance {
 public:
  void setup(PassContext& ctx) override {
    std::string shader = ctx.params().getString("shader");
    if (shader.empty()) throw RuntimeError("fullscreen pass '" + ctx.passName() + "': parameter 'shader' is empty");
    program_ = ctx.shaders().program("fullscreen.vert", shader);
    triangle_ = std::make_unique<gl::FullscreenTriangle>();
    locResolution_ = glGetUniformLocation(program_, "u_resolution");
    locColor_ = glGetUniformLocation(program_, "u_color");
    locValue_ = glGetUniformLocation(program_, "u_value");
    for (size_t i = 0; i < kInputs.size(); ++i) {
      locInputs_[i] = glGetUniformLocation(program_, kInputs[i]);
      if (locInputs_[i] >= 0) glProgramUniform1i(program_, locInputs_[i], static_cast<GLint>(i));
    }
    std::string df = ctx.params().getString("depth_func", "always");
    depthFunc_ = GL_ALWAYS;
    for (const auto& f : kDepthFuncs)
      if (df == f.name) depthFunc_ = f.func;
    std::string blend = ctx.params().getString("blend", "none");
    blend_ = blend == "alpha" ? 1 : blend == "additive" ? 2 : 0;
  }

  void execute(PassContext& ctx) override {
    gl::bindPassFramebuffer(ctx);
    glUseProgram(program_);
    Extent e = ctx.framebufferExtent();
    if (locResolution_ >= 0)
      glProgramUniform2f(program_, locResolution_, static_cast<float>(e.width), static_cast<float>(e.height));
    if (locColor_ >= 0) {
      std::vector<double> c = ctx.params().getVector("color", {1, 1, 1, 1});
      c.resize(4, 1.0);
      glProgramUniform4f(program_, locColor_, static_cast<float>(c[0]), static_cast<float>(c[1]),
                         static_cast<float>(c[2]), static_cast<float>(c[3]));
    }
    if (locValue_ >= 0) glProgramUniform1f(program_, locValue_, static_cast<float>(ctx.params().getNumber("value")));
    for (size_t i = 0; i < kInputs.size(); ++i)
      if (locInputs_[i] >= 0) glBindTextureUnit(static_cast<GLuint>(i), ctx.texture(kInputs[i]));

    if (ctx.bound("depth") && depthFunc_ != 0) {
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(depthFunc_);
    } else {
      glDisable(GL_DEPTH_TEST);
    }
    if (blend_ != 0) {
      glEnable(GL_BLEND);
      glBlendEquation(GL_FUNC_ADD);
      if (blend_ == 1)
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
      else
        glBlendFunc(GL_ONE, GL_ONE);
    }
    triangle_->draw();
    for (size_t i = 0; i < kInputs.size(); ++i)
      if (locInputs_[i] >= 0) glBindTextureUnit(static_cast<GLuint>(i), 0);
  }

 private:
  uint32_t program_ = 0;
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
  GLint locResolution_ = -1, locColor_ = -1, locValue_ = -1;
  std::array<GLint, 4> locInputs_{-1, -1, -1, -1};
  GLenum depthFunc_ = GL_ALWAYS;
  int blend_ = 0;
};

PassTypeDesc makeFullscreenPass() {
  PassTypeDesc d;
  d.name = "fullscreen";
  d.description = "Runs a fragment shader over the whole image (fullscreen triangle)";
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
    ShaderProgramSpec s;
    s.vert = "fullscreen.vert";
    s.frag = p.getString("shader");
    if (s.frag.empty()) throw RuntimeError("parameter 'shader' is empty: name a fragment shader");
    for (size_t i = 0; i < kInputs.size(); ++i) s.samplers.push_back({kInputs[i], kInputs[i], -1});  // set by setup()
    s.blendsSourceAlpha = p.getString("blend", "none") == "alpha";
    return std::vector<ShaderProgramSpec>{std::move(s)};
  };
  d.shaders = {"fullscreen.vert"};
  d.create = [] { return std::make_unique<FullscreenPass>(); };
  return d;
}

RGRAPH_REGISTER_PASS(makeFullscreenPass);
}  // namespace
