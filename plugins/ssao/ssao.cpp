// The SSAO plugin: screen-space ambient occlusion from the G-buffer
// (LearnOpenGL's SSAO chapter), for every G-buffer layout including compact.
//
//   ssao       G-buffer depth/position + normals -> ambient visibility (r8,
//              r16f or r32f; 1 open, 0 occluded), hemisphere kernel turned by
//              a 4x4 tile of random rotations
//   ssao_blur  box blur over the 4x4 tile, removing the rotation pattern
//
// The result goes to deferred_lighting's optional "ao" input, which scales
// the ambient term. Both outputs are slots the config binds to transient
// resources; the passes own only the 4x4 noise texture (constant data).
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "rgraph/error.h"
#include "rgraph/gl/fullscreen.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/gl/lighting_options.h"
#include "rgraph/gl/objects.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/pass_decl.h"
#include "rgraph/plugin.h"

namespace {
using namespace rgraph;

constexpr int kMaxKernel = 64;  // ssao.frag's u_kernel size
const std::vector<Format> kAoFormats = {Format::r8, Format::r16f, Format::r32f};

GLint loc(uint32_t program, const char* name) { return glGetUniformLocation(program, name); }

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

class SsaoPass final : public PassInstance {
 public:
  explicit SsaoPass(std::string frag) : frag_(std::move(frag)) {}

  void setup(PassContext& ctx) override {
    const std::string kind = "ssao pass '" + ctx.passName() + "'";
    if (!ctx.gpuScene()) throw RuntimeError(kind + " needs a scene (for the camera)");
    const std::string layout = ctx.params().getString("layout", "pbr");
    const char* needed = layout == "compact" ? "depth" : "position";
    if (!ctx.bound(needed))
      throw RuntimeError(kind + ": input '" + needed + "' is required by layout '" + layout + "' but not bound");
    program_ = ctx.shaders().program("fullscreen.vert", frag_, ssaoDefines(ctx.params()));
    triangle_ = std::make_unique<gl::FullscreenTriangle>();
    noise_ = noiseTexture();
    const int n = static_cast<int>(std::clamp<int64_t>(ctx.params().getInt("kernel_size", 32), 1, kMaxKernel));
    kernel_ = hemisphereKernel(n);
    gbufferSize_ = ctx.extent("normal");
  }

  void execute(PassContext& ctx) override {
    const ParamSet& p = ctx.params();
    gl::bindPassFramebuffer(ctx);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(program_);
    const int n = static_cast<int>(kernel_.size() / 3);
    glProgramUniform3fv(program_, loc(program_, "u_kernel"), n, kernel_.data());
    glProgramUniform1i(program_, loc(program_, "u_kernelSize"), n);
    glProgramUniform1f(program_, loc(program_, "u_radius"), static_cast<float>(p.getNumber("radius", 0.5)));
    glProgramUniform1f(program_, loc(program_, "u_bias"), static_cast<float>(p.getNumber("bias", 0.025)));
    glProgramUniform1f(program_, loc(program_, "u_power"), static_cast<float>(p.getNumber("power", 1.0)));
    glProgramUniform2f(program_, loc(program_, "u_gbufferSize"), static_cast<float>(gbufferSize_.width),
                       static_cast<float>(gbufferSize_.height));
    const Extent target = ctx.framebufferExtent();
    glProgramUniform2f(program_, loc(program_, "u_targetTexel"), 1.0f / static_cast<float>(target.width),
                       1.0f / static_cast<float>(target.height));
    ctx.gpuScene()->bindFrame();
    glBindTextureUnit(0, ctx.bound("position") ? ctx.texture("position") : 0);
    glBindTextureUnit(1, ctx.texture("normal"));
    glBindTextureUnit(4, ctx.bound("depth") ? ctx.texture("depth") : 0);
    glBindTextureUnit(5, noise_.id());
    triangle_->draw();
  }

 private:
  std::string frag_;
  uint32_t program_ = 0;
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
  gl::Texture noise_;
  std::vector<float> kernel_;
  Extent gbufferSize_;
};

// ------------------------------------------------------------ ssao_blur

class SsaoBlurPass final : public PassInstance {
 public:
  explicit SsaoBlurPass(std::string frag) : frag_(std::move(frag)) {}
  void setup(PassContext& ctx) override {
    if (ctx.extent("src") != ctx.framebufferExtent())
      throw RuntimeError("ssao_blur pass '" + ctx.passName() + "': 'src' and 'ao' must have the same size");
    program_ = ctx.shaders().program("fullscreen.vert", frag_);
    triangle_ = std::make_unique<gl::FullscreenTriangle>();
  }
  void execute(PassContext& ctx) override {
    gl::bindPassFramebuffer(ctx);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(program_);
    glProgramUniform1i(program_, loc(program_, "u_size"), static_cast<int>(ctx.params().getInt("size", 2)));
    glBindTextureUnit(0, ctx.texture("src"));
    triangle_->draw();
  }

 private:
  std::string frag_;
  uint32_t program_ = 0;
  std::unique_ptr<gl::FullscreenTriangle> triangle_;
};

// ------------------------------------------------------------ registration

void registerSsao(PluginHost& host) {
  using namespace rgraph::decl;
  {
    const std::string frag = host.shaderPath("ssao.frag");
    PassTypeDesc d;
    d.name = "ssao";
    d.description = "Screen-space ambient occlusion (hemisphere kernel) from G-buffer depth/position and normals";
    d.slots = {
        slot("position", Access::sampled, false, SlotDecl::Load::never,
             "G-buffer world position (every layout but compact)"),
        slot("normal", Access::sampled, true, SlotDecl::Load::never, "G-buffer normal"),
        slot("depth", Access::sampled, false, SlotDecl::Load::never, "G-buffer depth (compact: rebuilds position)",
             {Format::depth24, Format::depth32f, Format::depth24_stencil8, Format::depth32f_stencil8}),
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
    d.shaders = {"fullscreen.vert", frag};
    d.programs = [frag](const ParamSet& p) {
      ShaderProgramSpec s;
      s.vert = "fullscreen.vert";
      s.frag = frag;
      s.defines = ssaoDefines(p);
      s.samplers = {{"position", "g_position", 0}, {"normal", "g_normal", 1}, {"depth", "g_depth", 4}};
      s.ownSamplers = {"u_noise"};
      return std::vector<ShaderProgramSpec>{s};
    };
    d.create = [frag] { return std::make_unique<SsaoPass>(frag); };
    host.addPassType(std::move(d));
  }
  {
    const std::string frag = host.shaderPath("ssao_blur.frag");
    PassTypeDesc d;
    d.name = "ssao_blur";
    d.description = "SSAO 2/2: box blur over the 4x4 noise tile";
    d.slots = {
        slot("src", Access::sampled, true, SlotDecl::Load::never, "raw ssao output", kAoFormats),
        slot("ao", Access::color_attachment, true, SlotDecl::Load::never, "blurred ambient visibility (src's size)",
             kAoFormats),
    };
    d.params = {ranged("size", ParamType::integer, int64_t{2}, 0.0, 8.0,
                       "half width: averages 2*size x 2*size texels (2 matches the 4x4 noise tile; 0 copies)")};
    d.shaders = {"fullscreen.vert", frag};
    d.programs = [frag](const ParamSet&) {
      ShaderProgramSpec s;
      s.vert = "fullscreen.vert";
      s.frag = frag;
      s.samplers = {{"src", "u_src", 0}};
      return std::vector<ShaderProgramSpec>{s};
    };
    d.create = [frag] { return std::make_unique<SsaoBlurPass>(frag); };
    host.addPassType(std::move(d));
  }
}

}  // namespace

RGRAPH_PLUGIN("ssao", registerSsao)
