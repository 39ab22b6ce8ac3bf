#include "imported_texture.h"

#include <GL/glcorearb.h>

#include <cstdio>

#include <algorithm>

#include "rgraph/diagnostics.h"
#include "rgraph/gl/format.h"

namespace rgraph::gl {
namespace {

std::string describe(const std::string& format, Extent e, uint32_t samples, uint32_t levels, bool showLevels) {
  std::string s = format + " " + std::to_string(e.width) + "x" + std::to_string(e.height) + ", " +
                  std::to_string(samples) + (samples == 1 ? " sample" : " samples");
  if (showLevels) s += ", " + std::to_string(levels) + (levels == 1 ? " mip level" : " mip levels");
  return s;
}

std::string formatOfInternal(GLint internal) {
  for (Format f : allFormats())
    if (static_cast<GLint>(glFormat(f).internalFormat) == internal) return std::string(formatName(f));
  char buf[48];
  std::snprintf(buf, sizeof buf, "GL internal format 0x%04x", static_cast<unsigned>(internal));
  return buf;
}

std::string targetName(GLenum target) {
  switch (target) {
    case GL_TEXTURE_2D: return "GL_TEXTURE_2D";
    case GL_TEXTURE_2D_ARRAY: return "GL_TEXTURE_2D_ARRAY";
    case GL_TEXTURE_CUBE_MAP: return "GL_TEXTURE_CUBE_MAP";
    case GL_TEXTURE_CUBE_MAP_ARRAY: return "GL_TEXTURE_CUBE_MAP_ARRAY";
    case GL_TEXTURE_2D_MULTISAMPLE: return "GL_TEXTURE_2D_MULTISAMPLE";
    case GL_TEXTURE_2D_MULTISAMPLE_ARRAY: return "GL_TEXTURE_2D_MULTISAMPLE_ARRAY";
    default: return "target " + std::to_string(target);
  }
}

}  // namespace

TextureShape declaredShape(const ResourceDecl& decl, Extent planned) {
  TextureShape shape;
  shape.format = decl.texture.format;
  shape.extent = planned;
  shape.samples = std::max<uint32_t>(1, decl.texture.samples);
  shape.mips = decl.texture.mips;
  shape.layers = std::max<uint32_t>(1, decl.texture.layers);
  shape.cube = decl.texture.cube;
  return shape;
}

std::string checkImportName(const GraphDesc& graph, const std::string& resource) {
  const auto& decls = graph.resources;
  auto decl = std::find_if(decls.begin(), decls.end(), [&](const ResourceDecl& d) { return d.name == resource; });
  const std::string head = "cannot import a texture for ";
  if (decl == decls.end()) {
    std::vector<std::string> names;
    for (const auto& d : decls) names.push_back(d.name);
    const std::string near = closestMatch(resource, names);
    return head + "'" + resource + "': the pipeline declares no such resource" +
           (near.empty() ? std::string() : " (did you mean '" + near + "'?)");
  }
  if (decl->kind != ResourceKind::texture) return head + "resource '" + resource + "': it is a buffer";
  if (!decl->imported)
    return head + "resource '" + resource +
           "': it is not declared \"imported\": true (the graph owns it and may alias it)";
  return {};
}

std::string checkImportedTexture(const std::string& resource, const TextureShape& declared, uint32_t texture) {
  const std::string head = "imported texture " + std::to_string(texture) + " for resource '" + resource + "' ";
  if (texture == 0 || !glIsTexture(texture))
    return head + "is not a texture name in the current GL context (create it with glCreateTextures)";
  const uint32_t samples = declared.samples > 1 ? declared.samples : 1;
  const GLenum wantTarget = textureTarget(samples, declared.layers, declared.cube);
  GLint target = 0;
  glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &target);
  if (static_cast<GLenum>(target) != wantTarget)
    return head + "has the wrong target: the resource needs " + targetName(wantTarget) + " (" +
           describe(std::string(formatName(declared.format)), declared.extent, samples, 1, false) + ")";

  GLint internal = 0, width = 0, height = 0, texSamples = 0, immutable = 0, levels = 1;
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &internal);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, &width);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_HEIGHT, &height);
  glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_SAMPLES, &texSamples);
  GLint depth = 1;  // array layers (6 per cube of a cube array); the target said the rest
  if (declared.layers > 1) glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_DEPTH, &depth);
  const uint32_t wantDepth = declared.layers > 1 ? declared.layers * (declared.cube ? 6 : 1) : 1;
  glGetTextureParameteriv(texture, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
  if (immutable) glGetTextureParameteriv(texture, GL_TEXTURE_IMMUTABLE_LEVELS, &levels);
  const uint32_t gotSamples = texSamples > 1 ? static_cast<uint32_t>(texSamples) : 1;
  // A name from glCreateTextures alone reports GL's default internal format
  // (GL_RGBA) at 0x0: say what is missing rather than describe that.
  if (width == 0 || height == 0)
    return head + "has no storage (glTexStorage* never called); the resource is " +
           describe(std::string(formatName(declared.format)), declared.extent, samples, 1, false);
  const uint32_t wantLevels = declared.mips == 0 ? fullMipCount(declared.extent) : declared.mips;
  // Mip levels count only where the resource declares more than one and the
  // texture's storage is immutable (a mutable texture's levels are not fixed).
  const bool checkLevels = wantLevels > 1 && samples == 1 && immutable;
  const bool same = internal == static_cast<GLint>(glFormat(declared.format).internalFormat) &&
                    static_cast<uint32_t>(width) == declared.extent.width &&
                    static_cast<uint32_t>(height) == declared.extent.height && gotSamples == samples &&
                    static_cast<uint32_t>(depth) == wantDepth &&
                    (!checkLevels || static_cast<uint32_t>(levels) == wantLevels);
  if (same) return {};
  const auto layerText = [&](uint32_t n) {
    return declared.layers > 1 ? ", " + std::to_string(n) + (n == 1 ? " layer" : " layers") : std::string();
  };
  return head + "does not match its declaration: the resource is " +
         describe(std::string(formatName(declared.format)), declared.extent, samples, wantLevels, checkLevels) +
         layerText(wantDepth) + "; the texture is " +
         describe(formatOfInternal(internal), Extent{static_cast<uint32_t>(width), static_cast<uint32_t>(height)},
                  gotSamples, static_cast<uint32_t>(levels), checkLevels) +
         layerText(static_cast<uint32_t>(depth));
}

}  // namespace rgraph::gl
