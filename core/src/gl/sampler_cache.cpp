#include "sampler_cache.h"

#include <GL/glcorearb.h>

#include <algorithm>
#include <cstring>

#include "rgraph/gl/context.h"

namespace rgraph::gl {
namespace {

GLenum minFilter(const SamplerState& s) {
  const bool linear = s.filter == SamplerState::Filter::linear;
  switch (s.mip) {
    case SamplerState::MipFilter::none: return linear ? GL_LINEAR : GL_NEAREST;
    case SamplerState::MipFilter::nearest: return linear ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
    case SamplerState::MipFilter::linear: return linear ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR;
  }
  return GL_LINEAR;
}

GLenum wrap(SamplerState::Wrap w) {
  switch (w) {
    case SamplerState::Wrap::clamp: return GL_CLAMP_TO_EDGE;
    case SamplerState::Wrap::repeat: return GL_REPEAT;
    case SamplerState::Wrap::mirror: return GL_MIRRORED_REPEAT;
    case SamplerState::Wrap::border: return GL_CLAMP_TO_BORDER;
  }
  return GL_CLAMP_TO_EDGE;
}

GLenum compareFunc(SamplerState::Compare c) {
  switch (c) {
    case SamplerState::Compare::none:
    case SamplerState::Compare::never: return GL_NEVER;
    case SamplerState::Compare::less: return GL_LESS;
    case SamplerState::Compare::less_equal: return GL_LEQUAL;
    case SamplerState::Compare::equal: return GL_EQUAL;
    case SamplerState::Compare::not_equal: return GL_NOTEQUAL;
    case SamplerState::Compare::greater_equal: return GL_GEQUAL;
    case SamplerState::Compare::greater: return GL_GREATER;
    case SamplerState::Compare::always: return GL_ALWAYS;
  }
  return GL_NEVER;
}


}  // namespace

float SamplerCache::maxAnisotropy() {
  if (maxAnisotropy_ > 0.0f) return maxAnisotropy_;
  maxAnisotropy_ = 1.0f;
  // Core in 4.6 only: a 4.5 context has it through either extension (same enum).
  if (hasExtension("GL_ARB_texture_filter_anisotropic") || hasExtension("GL_EXT_texture_filter_anisotropic")) {
    GLfloat m = 1.0f;
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &m);
    maxAnisotropy_ = std::max(1.0f, m);
  }
  return maxAnisotropy_;
}

uint32_t SamplerCache::get(const SamplerState& s) {
  if (auto it = samplers_.find(s); it != samplers_.end()) return it->second.id();
  Sampler sampler = createSampler();
  const GLuint id = sampler.id();
  glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(minFilter(s)));
  glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, s.filter == SamplerState::Filter::linear ? GL_LINEAR : GL_NEAREST);
  glSamplerParameteri(id, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap(s.wrap[0])));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap(s.wrap[1])));
  glSamplerParameteri(id, GL_TEXTURE_WRAP_R, static_cast<GLint>(wrap(s.wrap[2])));
  glSamplerParameterfv(id, GL_TEXTURE_BORDER_COLOR, s.border.data());
  if (s.compare == SamplerState::Compare::none) {
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_NONE);
  } else {
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glSamplerParameteri(id, GL_TEXTURE_COMPARE_FUNC, static_cast<GLint>(compareFunc(s.compare)));
  }
  const float anisotropy = s.anisotropy > 1.0f ? std::min(s.anisotropy, maxAnisotropy()) : 1.0f;
  if (anisotropy > 1.0f) glSamplerParameterf(id, GL_TEXTURE_MAX_ANISOTROPY, anisotropy);
  return samplers_.emplace(s, std::move(sampler)).first->second.id();
}

}  // namespace rgraph::gl
