#include <GL/glcorearb.h>

#include <algorithm>

#include "rgraph/error.h"
#include "rgraph/gl/format.h"

namespace rgraph::gl {

GlFormat glFormat(Format f) {
  switch (f) {
    case Format::rgba8: return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case Format::srgb8_alpha8: return {GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case Format::rgba16f: return {GL_RGBA16F, GL_RGBA, GL_FLOAT};
    case Format::rgba32f: return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
    case Format::rg16f: return {GL_RG16F, GL_RG, GL_FLOAT};
    case Format::rg8: return {GL_RG8, GL_RG, GL_UNSIGNED_BYTE};
    case Format::r8: return {GL_R8, GL_RED, GL_UNSIGNED_BYTE};
    case Format::r16f: return {GL_R16F, GL_RED, GL_FLOAT};
    case Format::r32f: return {GL_R32F, GL_RED, GL_FLOAT};
    case Format::r11g11b10f: return {GL_R11F_G11F_B10F, GL_RGB, GL_FLOAT};
    case Format::rgb16f: return {GL_RGB16F, GL_RGB, GL_FLOAT};
    case Format::rgb32f: return {GL_RGB32F, GL_RGB, GL_FLOAT};
    case Format::depth24: return {GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_FLOAT};
    case Format::depth32f: return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
    case Format::depth24_stencil8: return {GL_DEPTH24_STENCIL8, GL_DEPTH_STENCIL, GL_UNSIGNED_INT_24_8};
    case Format::depth32f_stencil8:
      return {GL_DEPTH32F_STENCIL8, GL_DEPTH_STENCIL, GL_FLOAT_32_UNSIGNED_INT_24_8_REV};
    case Format::rg32ui: return {GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT};
  }
  return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
}

unsigned attachmentPoint(Format f) {
  const FormatInfo& i = formatInfo(f);
  if (i.isDepth) return i.hasStencil ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT;
  return GL_COLOR_ATTACHMENT0;
}

bool isDepth(Format f) { return formatInfo(f).isDepth; }
bool hasStencil(Format f) { return formatInfo(f).hasStencil; }
bool isSrgb(Format f) { return f == Format::srgb8_alpha8; }

uint32_t fullMipCount(Extent e) {
  uint32_t m = std::max(e.width, e.height), n = 1;
  while (m > 1) {
    m >>= 1;
    ++n;
  }
  return n;
}

Texture createTexture2D(Format f, Extent e, uint32_t mips, uint32_t samples) {
  return createTexture(f, e, mips, samples, 1, false);
}

unsigned textureTarget(uint32_t samples, uint32_t layers, bool cube) {
  if (samples > 1) return layers > 1 ? GL_TEXTURE_2D_MULTISAMPLE_ARRAY : GL_TEXTURE_2D_MULTISAMPLE;
  if (cube) return layers > 1 ? GL_TEXTURE_CUBE_MAP_ARRAY : GL_TEXTURE_CUBE_MAP;
  return layers > 1 ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D;
}

Texture createTexture(Format f, Extent e, uint32_t mips, uint32_t samples, uint32_t layers, bool cube) {
  if (e.width == 0 || e.height == 0)
    throw RuntimeError("cannot create a " + std::string(formatName(f)) + " texture of size 0");
  if (cube && samples > 1) throw RuntimeError("cannot create a multisampled cube map");
  if (cube && e.width != e.height)
    throw RuntimeError("cannot create a cube map of " + std::to_string(e.width) + "x" + std::to_string(e.height) +
                       " texels: its faces are square");
  layers = std::max<uint32_t>(1, layers);
  const GlFormat g = glFormat(f);
  const unsigned target = textureTarget(samples, layers, cube);
  const auto w = static_cast<GLsizei>(e.width), h = static_cast<GLsizei>(e.height);
  const auto depth = static_cast<GLsizei>(cube ? 6 * layers : layers);
  Texture t = createTexture(target);
  if (samples > 1) {
    if (layers > 1)
      glTextureStorage3DMultisample(t.id(), static_cast<GLsizei>(samples), g.internalFormat, w, h, depth, GL_TRUE);
    else
      glTextureStorage2DMultisample(t.id(), static_cast<GLsizei>(samples), g.internalFormat, w, h, GL_TRUE);
    return t;
  }
  uint32_t levels = mips == 0 ? fullMipCount(e) : std::min(mips, fullMipCount(e));
  if (target == GL_TEXTURE_2D || target == GL_TEXTURE_CUBE_MAP)
    glTextureStorage2D(t.id(), static_cast<GLsizei>(levels), g.internalFormat, w, h);
  else
    glTextureStorage3D(t.id(), static_cast<GLsizei>(levels), g.internalFormat, w, h, depth);
  glTextureParameteri(t.id(), GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(t.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  if (cube) glTextureParameteri(t.id(), GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
  return t;
}

}  // namespace rgraph::gl
