#include "scene_depth.h"

#include <GL/glcorearb.h>

#include "rgraph/error.h"
#include "rgraph/gl/executor.h"
#include "rgraph/registry.h"

namespace rgraph {

std::optional<SceneDepthSource> findSceneDepth(const Plan& plan, const PassRegistry& registry,
                                               const std::string& wanted) {
  std::optional<SceneDepthSource> found;
  for (size_t step = 0; step < plan.order.size(); ++step) {
    const PassIndex p = plan.order[step];
    const PassTypeDesc* type = registry.find(plan.pass(p).type);
    if (!type) continue;
    for (const BoundUse& use : plan.bindings[p.value()]) {
      if (use.access != Access::depth_attachment && use.access != Access::depth_attachment_read) continue;
      if (!use.resource.valid()) continue;
      const PlannedResource& r = plan.resource(use.resource);
      if (!wanted.empty()) {
        if (r.name == wanted) found = SceneDepthSource{r.name, step};
        continue;
      }
      // The camera's depth: drawn by a scene pass at the output's size (a
      // shadow map is another size, or layered, or both).
      bool flat = use.sub.layerCount <= 1;
      if (r.physical.valid()) {
        const PhysicalTexture& t = plan.physical[r.physical.value()];
        flat = flat && t.layers == 1 && !t.cube;
      }
      if (type->needsScene && r.extent == plan.output && flat) found = SceneDepthSource{r.name, step};
    }
  }
  return found;
}

void SceneDepthCopy::setSource(std::optional<SceneDepthSource> source) {
  source_ = std::move(source);
  if (!source_) {
    texture_.reset();
    extent_ = {};
    internalFormat_ = 0;
  }
}

void SceneDepthCopy::afterPass(size_t step, const Executor& executor) {
  if (!source_ || step != source_->step) return;
  const GLuint from = executor.textureOf(source_->resource);
  if (!from) return;
  GLint w = 0, h = 0, format = 0;
  glGetTextureLevelParameteriv(from, 0, GL_TEXTURE_WIDTH, &w);
  glGetTextureLevelParameteriv(from, 0, GL_TEXTURE_HEIGHT, &h);
  glGetTextureLevelParameteriv(from, 0, GL_TEXTURE_INTERNAL_FORMAT, &format);
  const Extent size{static_cast<uint32_t>(w), static_cast<uint32_t>(h)};
  // Made again only when the depth's size or format changes (a resize, a reload).
  if (!texture_ || size != extent_ || static_cast<unsigned>(format) != internalFormat_) {
    texture_ = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture_.id(), 1, static_cast<GLenum>(format), w, h);
    glTextureParameteri(texture_.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture_.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    extent_ = size;
    internalFormat_ = static_cast<unsigned>(format);
    if (!draw_) draw_ = gl::createFramebuffer();
    const bool stencil = format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8;
    glNamedFramebufferTexture(draw_.id(), stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, texture_.id(), 0);
  }
  if (!read_) read_ = gl::createFramebuffer();
  const bool stencil = format == GL_DEPTH24_STENCIL8 || format == GL_DEPTH32F_STENCIL8;
  glNamedFramebufferTexture(read_.id(), stencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT, from, 0);
  // A blit obeys the scissor test alone (no depth mask, no depth test); the
  // executor's state between passes has it off, a pass may have left it on.
  glDisable(GL_SCISSOR_TEST);
  glBlitNamedFramebuffer(read_.id(), draw_.id(), 0, 0, w, h, 0, 0, w, h, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
}

}  // namespace rgraph
