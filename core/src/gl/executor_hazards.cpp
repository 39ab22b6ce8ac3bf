// Hazard modes in the executor (rgraph/hazards.h): the plan options they
// change, the poison written into each transient when its lifetime begins,
// and the hostile GL state set before each pass. Nothing here runs in a plain
// frame: renderFrame tests one flag per pass.
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "executor_internal.h"
#include "fixed_state.h"
#include "rgraph/gl/format.h"

namespace rgraph {

using exec_detail::PassRun;

namespace {
// Integer formats (ids) take integer clears and uploads: asked of the texture,
// whatever formats rgraph/format.h lists.
// Larger than any uniform block or storage buffer a shipped pass declares
// (the Frame block is under 1 KiB): a block bound to a buffer smaller than
// itself reads undefined values.
constexpr GLsizeiptr kHostileBufferBytes = 64 * 1024;

bool integerTexture(uint32_t texture) {
  GLint type = 0;
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_RED_TYPE, &type);
  return type == GL_INT || type == GL_UNSIGNED_INT;
}
}  // namespace

void Executor::Impl::hazardCompileOptions(CompileOptions& options) const { applyHazardModes(hazards, options); }

// Transients whose lifetime begins at each step: textures the graph owns,
// whose content is meant to start undefined each frame (not persistent ones,
// which keep theirs, and not histories, which the executor fills itself).
void Executor::Impl::planPoison() {
  for (auto& run : runs) run->poisonAtStart.clear();
  if (!hazards.has(HazardMode::poison)) return;
  for (uint32_t r = 0; r < plan.resources.size(); ++r) {
    const PlannedResource& pr = plan.resources[r];
    if (pr.kind != ResourceKind::texture || pr.imported || pr.persistent || !pr.physical.valid() ||
        pr.historyOf.valid() || !pr.firstPass.valid() || !resources[r].texture)
      continue;
    if (pr.firstPass.value() < runs.size()) runs[pr.firstPass.value()]->poisonAtStart.push_back(ResourceIndex(r));
  }
}

// NaN in float formats; a checkerboard of 0 and 1 per channel (magenta and
// green) in the others; depth 0 (the near plane: every GL_LESS test fails)
// with stencil 0x5A. The pass's own clears, applied after this, overwrite it.
void Executor::Impl::poison(const PassRun& run) {
  for (ResourceIndex r : run.poisonAtStart) {
    const exec_detail::ResourceObject& obj = resources[r.value()];
    const uint32_t layers = obj.layers * (obj.cube ? 6u : 1u);
    for (uint32_t level = 0; level < obj.mips; ++level) {
      const GLint l = static_cast<GLint>(level);
      if (gl::isDepth(obj.format)) {
        if (gl::hasStencil(obj.format)) {
          const struct {
            float depth;
            uint32_t stencil;
          } ds{0.0f, 0x5Au};
          glClearTexImage(obj.texture, l, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV, &ds);
        } else {
          const float d = 0.0f;
          glClearTexImage(obj.texture, l, GL_DEPTH_COMPONENT, GL_FLOAT, &d);
        }
      } else if (integerTexture(obj.texture)) {
        const GLuint v[4] = {0xA5A5A5A5u, 0x5A5A5A5Au, 0xA5A5A5A5u, 0x5A5A5A5Au};
        glClearTexImage(obj.texture, l, GL_RGBA_INTEGER, GL_UNSIGNED_INT, v);
      } else if (formatInfo(obj.format).isFloat || obj.samples > 1) {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        const float magenta[4] = {1.0f, 0.0f, 1.0f, 0.0f};
        const float v[4] = {nan, nan, nan, nan};
        glClearTexImage(obj.texture, l, GL_RGBA, GL_FLOAT, formatInfo(obj.format).isFloat ? v : magenta);
      } else {
        const uint32_t w = std::max(1u, obj.extent.width >> level), h = std::max(1u, obj.extent.height >> level);
        std::vector<uint8_t> texels(size_t{w} * h * layers * 4);
        for (uint32_t z = 0; z < layers; ++z)
          for (uint32_t y = 0; y < h; ++y)
            for (uint32_t x = 0; x < w; ++x) {
              uint8_t* t = &texels[((size_t{z} * h + y) * w + x) * 4];
              const bool odd = ((x ^ y) & 1u) != 0;
              t[0] = odd ? 0 : 255, t[1] = odd ? 255 : 0, t[2] = odd ? 0 : 255, t[3] = odd ? 255 : 0;
            }
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        if (layers > 1 || obj.cube)
          glTextureSubImage3D(obj.texture, l, 0, 0, 0, static_cast<GLsizei>(w), static_cast<GLsizei>(h),
                              static_cast<GLsizei>(layers), GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
        else
          glTextureSubImage2D(obj.texture, l, 0, 0, static_cast<GLsizei>(w), static_cast<GLsizei>(h), GL_RGBA,
                              GL_UNSIGNED_BYTE, texels.data());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
      }
    }
  }
}

// Every item of the GL state guard a pass may find (rgraph/renderer.h's
// contract) set to a hostile value; resetState() then puts back what the
// executor promises (rgraph/pass.h's GlStateGroup), so that what is left
// hostile is exactly what a pass must set itself: blend functions and
// equations, stencil functions and operations, cull face mode and front face,
// scissor box, viewport, the draw framebuffer, program and vertex array, the
// textures on every unit (the pass's own slots are bound after this), colour
// masks of draw buffers 1-7 before the reset, and the uniform and storage
// buffer binding points (below). Polygon mode, multisample and the other
// enables the renderer resets once per frame are part of that promise and
// left alone; so are sampler objects: the executor promises sampler 0 on
// every unit (pass_programs.h), and checkState() names a pass that leaves one.
void Executor::Impl::scrambleState() {
  if (!hostileTexture) {
    hostileTexture = std::make_unique<gl::Texture>(gl::createTexture(Format::rgba8, Extent{1, 1}, 1, 1, 1, false));
    const uint8_t magenta[4] = {255, 0, 255, 7};
    glTextureSubImage2D(hostileTexture->id(), 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, magenta);
    hostileFramebuffer = gl::createFramebuffer();
    glNamedFramebufferTexture(hostileFramebuffer.id(), GL_COLOR_ATTACHMENT0, hostileTexture->id(), 0);
    hostileVao = gl::createVertexArray();
    hostileBuffer = gl::createBuffer();
    glNamedBufferStorage(hostileBuffer.id(), kHostileBufferBytes, nullptr, GL_DYNAMIC_STORAGE_BIT);
    GLint uniformPoints = 0, storagePoints = 0;
    glGetIntegerv(GL_MAX_UNIFORM_BUFFER_BINDINGS, &uniformPoints);
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &storagePoints);
    hostileBufferBindings = static_cast<uint32_t>(std::clamp(std::min(uniformPoints, storagePoints), 0, 16));
  }
  gl::applyFixedState(gl::hostileFixedState());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, hostileFramebuffer.id());
  glUseProgram(0);
  glBindVertexArray(hostileVao.id());
  for (GLuint unit = 0; unit < 16; ++unit) glBindTextureUnit(unit, hostileTexture->id());
  // Buffer binding points 0-15, uniform and storage: no pass may inherit one
  // from an earlier pass. What the executor binds for a pass (the Frame block
  // at uniform 0: resetState() forgets the scene's record, selectJitter()
  // binds it again) and what a pass binds itself (lights, clusters, shadow
  // information, the scene's instances, objects and skins) goes over this.
  // Refilled each time (a pass may write through what it inherited): words
  // of 255, a float near 0 and a small count, so that a shader looping over
  // an inherited count ends.
  const GLuint word = 0xFFu;
  glClearNamedBufferData(hostileBuffer.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &word);
  for (GLuint point = 0; point < hostileBufferBindings; ++point) {
    glBindBufferBase(GL_UNIFORM_BUFFER, point, hostileBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, point, hostileBuffer.id());
  }
  dirtyState = kGlStateAll;  // resetState: every group put back, the binding records forgotten
}

}  // namespace rgraph
