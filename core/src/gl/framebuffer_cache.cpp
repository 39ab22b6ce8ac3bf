#include "rgraph/gl/framebuffer_cache.h"

#include <GL/glcorearb.h>

#include <cstdio>

#include "rgraph/error.h"

namespace rgraph::gl {

std::string framebufferStatusName(unsigned status) {
  switch (status) {
    case GL_FRAMEBUFFER_COMPLETE: return "GL_FRAMEBUFFER_COMPLETE";
    case GL_FRAMEBUFFER_UNDEFINED: return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT: return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
    case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER: return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE: return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS: return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
    case 0: return "no status (glCheckNamedFramebufferStatus failed: a GL error)";
    default: {
      char buf[40];
      std::snprintf(buf, sizeof buf, "unknown status 0x%04x", status);
      return buf;
    }
  }
}

std::string framebufferStatusMessage(unsigned status, std::span<const FramebufferAttachment> attachments) {
  std::string atts;
  for (const FramebufferAttachment& a : attachments) {
    atts += (atts.empty() ? "" : ", ") + (a.slot.empty() ? std::string("texture ") + std::to_string(a.texture) : a.slot) +
            "=" + std::string(formatName(a.format)) + " " + std::to_string(a.extent.width) + "x" +
            std::to_string(a.extent.height) + (a.samples > 1 ? " x" + std::to_string(a.samples) : "");
    if (a.level != 0) atts += " level " + std::to_string(a.level);
    if (a.layer != FramebufferAttachment::kAllLayers) atts += " layer " + std::to_string(a.layer);
  }
  return "framebuffer incomplete: " + framebufferStatusName(status) + " (attachments: " +
         (atts.empty() ? std::string("none") : atts) + ")";
}

uint32_t FramebufferCache::get(std::span<const FramebufferAttachment> attachments,
                               std::span<const unsigned> drawBuffers, std::string_view who) {
  std::vector<uint32_t> key;
  key.reserve(attachments.size() * 4 + drawBuffers.size() + 1);
  for (const FramebufferAttachment& a : attachments) key.insert(key.end(), {a.point, a.texture, a.level, a.layer});
  key.push_back(0);  // separates the draw buffers from the attachments
  key.insert(key.end(), drawBuffers.begin(), drawBuffers.end());
  if (auto it = fbos_.find(key); it != fbos_.end()) return it->second.id();

  Framebuffer fbo = createFramebuffer();
  unsigned readBuffer = GL_NONE;
  for (const FramebufferAttachment& a : attachments) {
    if (a.layer == FramebufferAttachment::kAllLayers)
      glNamedFramebufferTexture(fbo.id(), a.point, a.texture, static_cast<GLint>(a.level));
    else
      glNamedFramebufferTextureLayer(fbo.id(), a.point, a.texture, static_cast<GLint>(a.level),
                                     static_cast<GLint>(a.layer));
    if (readBuffer == GL_NONE && a.point >= GL_COLOR_ATTACHMENT0 && a.point < GL_COLOR_ATTACHMENT0 + 32)
      readBuffer = a.point;
  }
  if (drawBuffers.empty())
    glNamedFramebufferDrawBuffer(fbo.id(), GL_NONE);
  else
    glNamedFramebufferDrawBuffers(fbo.id(), static_cast<GLsizei>(drawBuffers.size()), drawBuffers.data());
  glNamedFramebufferReadBuffer(fbo.id(), readBuffer);
  const GLenum status = glCheckNamedFramebufferStatus(fbo.id(), GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw RuntimeError(std::string(who) + ": " + framebufferStatusMessage(status, attachments));
  return fbos_.emplace(std::move(key), std::move(fbo)).first->second.id();
}

uint32_t FramebufferCache::view(uint32_t texture, unsigned target, unsigned internalFormat, const Subresource& sub) {
  const std::vector<uint32_t> key{texture, target, sub.mipBegin, sub.mipCount, sub.layerBegin, sub.layerCount};
  if (auto it = views_.find(key); it != views_.end()) return it->second.id();
  // glGenTextures: a view's name must not have a target yet (glCreateTextures gives it one).
  GLuint id = 0;
  glGenTextures(1, &id);
  Texture view(id);
  glTextureView(view.id(), target, texture, internalFormat, sub.mipBegin, sub.mipCount, sub.layerBegin,
                sub.layerCount);
  // A view starts with default sampling state: take the texture's, so that
  // a view samples like the texture it shows.
  for (GLenum p : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER, GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) {
    GLint v = 0;
    glGetTextureParameteriv(texture, p, &v);
    glTextureParameteri(view.id(), p, v);
  }
  return views_.emplace(key, std::move(view)).first->second.id();
}

void FramebufferCache::clear() {
  fbos_.clear();
  views_.clear();
}

}  // namespace rgraph::gl
