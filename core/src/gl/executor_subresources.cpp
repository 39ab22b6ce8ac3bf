// Executor: the parts of textures a pass draws into and samples. Every
// framebuffer and texture view comes from the executor's one cache
// (rgraph/gl/framebuffer_cache.h): a pass's own framebuffer (its attachment
// slots at the levels and layers they bind), the ones a pass asks for
// (PassContext::framebuffer), and the views of subresources it samples.
#include <GL/glcorearb.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>

#include "executor_internal.h"
#include "rgraph/error.h"
#include "rgraph/gl/format.h"

namespace rgraph {
namespace exec_detail {

SubresourceSampling subresourceSamplingFromEnvironment() {
  const char* v = std::getenv("RGRAPH_SUBRESOURCE_SAMPLING");
  if (!v || !*v || std::string_view(v) == "views") return SubresourceSampling::views;
  if (std::string_view(v) == "levels") return SubresourceSampling::levels;
  spdlog::warn("RGRAPH_SUBRESOURCE_SAMPLING={}: not 'views' or 'levels'; using views", v);
  return SubresourceSampling::views;
}

namespace {

bool wholeTexture(const SlotBinding& s, const Subresource& abs) {
  return abs.mipBegin == 0 && abs.mipCount == s.mips && abs.layerBegin == 0 && abs.layerCount == s.arrayLayers;
}

// `rel` (relative to the part the slot binds; kAll: to its end) as levels and
// layers of the texture. Throws naming the pass and slot when it leaves that part.
Subresource within(const SlotBinding& s, const Subresource& rel, const std::string& who) {
  auto range = [&](uint32_t boundBegin, uint32_t boundCount, uint32_t begin, uint32_t count, const char* what) {
    const uint32_t n = count == Subresource::kAll ? (begin < boundCount ? boundCount - begin : 0) : count;
    if (begin >= boundCount || n == 0 || n > boundCount - begin)
      throw RuntimeError(who + ": slot '" + s.slot + "' binds " + std::to_string(boundCount) + " " + what +
                         (boundCount == 1 ? "" : "s") + "; asked for " + what + " " + std::to_string(begin) +
                         (n > 1 ? ".." + std::to_string(begin + n - 1) : std::string()));
    return std::pair{boundBegin + begin, n};
  };
  Subresource abs;
  std::tie(abs.mipBegin, abs.mipCount) = range(s.sub.mipBegin, s.sub.mipCount, rel.mipBegin, rel.mipCount, "level");
  std::tie(abs.layerBegin, abs.layerCount) =
      range(s.sub.layerBegin, s.sub.layerCount, rel.layerBegin, rel.layerCount, "layer");
  return abs;
}

// The target a view of `abs` samples as: a cube where it is whole cubes of a
// cube texture, an array where it has several layers, else a 2D texture.
GLenum viewTarget(const SlotBinding& s, const Subresource& abs) {
  if (s.samples > 1) return abs.layerCount > 1 ? GL_TEXTURE_2D_MULTISAMPLE_ARRAY : GL_TEXTURE_2D_MULTISAMPLE;
  if (s.cube && abs.layerBegin % 6 == 0 && abs.layerCount % 6 == 0)
    return abs.layerCount == 6 ? GL_TEXTURE_CUBE_MAP : GL_TEXTURE_CUBE_MAP_ARRAY;
  if (s.arrayLayers > 1) return abs.layerCount == 1 ? GL_TEXTURE_2D : GL_TEXTURE_2D_ARRAY;
  return GL_TEXTURE_2D;
}

Extent levelExtent(Extent e, uint32_t level) {
  return {std::max(1u, e.width >> level), std::max(1u, e.height >> level)};
}

}  // namespace

void PassRun::setLevels(uint32_t tex, uint32_t base, uint32_t max) {
  if (std::none_of(levelRestores.begin(), levelRestores.end(), [&](const LevelRestore& r) { return r.texture == tex; })) {
    LevelRestore r{tex};
    glGetTextureParameteriv(tex, GL_TEXTURE_BASE_LEVEL, &r.base);
    glGetTextureParameteriv(tex, GL_TEXTURE_MAX_LEVEL, &r.max);
    levelRestores.push_back(r);
  }
  glTextureParameteri(tex, GL_TEXTURE_BASE_LEVEL, static_cast<GLint>(base));
  glTextureParameteri(tex, GL_TEXTURE_MAX_LEVEL, static_cast<GLint>(max));
}

void PassRun::applyLevelRanges() {
  for (const SlotBinding& s : slots)
    if (s.levelRange) setLevels(s.texture, s.sub.mipBegin, s.sub.mipBegin + s.sub.mipCount - 1);
}

void PassRun::restoreLevels() {
  for (const LevelRestore& r : levelRestores) {
    glTextureParameteri(r.texture, GL_TEXTURE_BASE_LEVEL, r.base);
    glTextureParameteri(r.texture, GL_TEXTURE_MAX_LEVEL, r.max);
  }
  levelRestores.clear();
}

uint32_t PassRun::texture(std::string_view slot, const Subresource& rel) {
  const SlotBinding* s = find(slot);
  if (!s || !s->texture) return 0;
  const Subresource abs = within(*s, rel, who());
  const bool allLayers = abs.layerBegin == 0 && abs.layerCount == s->arrayLayers;
  // Levels: the texture itself, its levels narrowed (or put back: an earlier
  // call of this pass may have narrowed them). Also for a texture whose
  // storage is not immutable (a caller's), which cannot have views.
  if (allLayers && s->samples == 1 && (sampling == SubresourceSampling::levels || !s->immutable)) {
    const bool changed = std::any_of(levelRestores.begin(), levelRestores.end(),
                                     [&](const LevelRestore& r) { return r.texture == s->texture; });
    if (!wholeTexture(*s, abs) || changed) setLevels(s->texture, abs.mipBegin, abs.mipBegin + abs.mipCount - 1);
    return s->texture;
  }
  if (wholeTexture(*s, abs)) return s->texture;
  if (!s->immutable)
    throw RuntimeError(who() + ": slot '" + s->slot + "': sampling some of a texture's layers needs a view, and its " +
                       "texture (a caller's) has no immutable storage (glTextureStorage*)");
  return cache->view(s->texture, viewTarget(*s, abs), gl::glFormat(s->format).internalFormat, abs);
}

PassFramebuffer PassRun::framebuffer(std::span<const AttachmentRef> refs) {
  std::vector<gl::FramebufferAttachment> atts;
  std::vector<unsigned> drawBuffers;
  Extent extent;
  bool depth = false;
  for (const AttachmentRef& ref : refs) {
    const SlotBinding* s = find(ref.slot);
    if (!s || !s->texture)
      throw RuntimeError(who() + ": framebuffer(): slot '" + std::string(ref.slot) + "' is not bound to a texture");
    const Subresource abs =
        within(*s, Subresource{ref.mip, 1, ref.layer == AttachmentRef::kAllLayers ? 0 : ref.layer,
                               ref.layer == AttachmentRef::kAllLayers ? Subresource::kAll : 1},
               who());
    gl::FramebufferAttachment a;
    a.slot = s->slot;
    a.format = s->format;
    a.samples = s->samples;
    a.extent = levelExtent(s->textureExtent, abs.mipBegin);
    a.texture = s->texture;
    a.level = abs.mipBegin;
    if (s->arrayLayers > 1 && abs.layerCount == 1) {
      a.layer = abs.layerBegin;
    } else if (abs.layerCount != s->arrayLayers) {
      // Some layers, layered: attach a view that has only those.
      a.texture = cache->view(s->texture, s->samples > 1 ? GL_TEXTURE_2D_MULTISAMPLE_ARRAY : GL_TEXTURE_2D_ARRAY,
                              gl::glFormat(s->format).internalFormat, Subresource{abs.mipBegin, 1, abs.layerBegin,
                                                                                   abs.layerCount});
      a.level = 0;
    }
    if (gl::isDepth(s->format)) {
      if (depth) throw RuntimeError(who() + ": framebuffer(): more than one depth attachment");
      depth = true;
      a.point = gl::attachmentPoint(s->format);
    } else {
      a.point = GL_COLOR_ATTACHMENT0 + static_cast<unsigned>(drawBuffers.size());
      drawBuffers.push_back(a.point);
    }
    extent = atts.empty() ? a.extent
                          : Extent{std::min(extent.width, a.extent.width), std::min(extent.height, a.extent.height)};
    atts.push_back(std::move(a));
  }
  if (atts.empty()) return {};
  return {cache->get(atts, drawBuffers, who()), extent};
}

}  // namespace exec_detail

void Executor::Impl::resolveSubresource(exec_detail::PassRun& run, exec_detail::SlotBinding& b,
                                        const Subresource& sub) const {
  b.sub = Subresource{0, b.mips, 0, b.arrayLayers};
  b.sub = exec_detail::within(b, sub, run.who());
  b.extent = exec_detail::levelExtent(b.textureExtent, b.sub.mipBegin);
  GLint immutable = 0;
  glGetTextureParameteriv(b.texture, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
  b.immutable = immutable != 0;
}

void Executor::Impl::bindSampledSubresources(exec_detail::PassRun& run) {
  using exec_detail::SlotBinding;
  for (SlotBinding& s : run.slots) {
    if (s.access != Access::sampled || !s.texture || exec_detail::wholeTexture(s, s.sub)) continue;
    const bool allLayers = s.sub.layerBegin == 0 && s.sub.layerCount == s.arrayLayers;
    bool levels = allLayers && s.samples == 1 && (sampling == exec_detail::SubresourceSampling::levels || !s.immutable);
    // Two level ranges of one texture in one pass cannot both be its base and max level.
    for (const SlotBinding& o : run.slots)
      if (&o != &s && o.levelRange && o.texture == s.texture && !(o.sub == s.sub)) levels = false;
    if (levels) {
      s.levelRange = true;
      continue;
    }
    if (!s.immutable)
      throw RuntimeError(run.who() + ": slot '" + s.slot + "' samples part of a caller's texture that has no " +
                         "immutable storage (glTextureStorage*), so no view of it can be made");
    s.sampled = cache.view(s.texture, exec_detail::viewTarget(s, s.sub), gl::glFormat(s.format).internalFormat, s.sub);
  }
}

// Colour attachments in slot-declaration order, then depth, each at the
// first level and the layers its slot binds.
void Executor::Impl::attachPassFramebuffer(exec_detail::PassRun& run) {
  std::vector<AttachmentRef> refs;
  exec_detail::SlotBinding* depth = nullptr;
  size_t colors = 0;
  for (auto& s : run.slots) {
    if (s.access == Access::color_attachment) {
      s.colorIndex = static_cast<int>(colors++);
    } else if (s.access == Access::depth_attachment || s.access == Access::depth_attachment_read) {
      if (depth)
        throw RuntimeError("pass '" + run.name + "': more than one depth attachment ('" + depth->slot + "' and '" +
                           s.slot + "')");
      depth = &s;
      s.depthAttachment = true;
      run.readOnlyDepth = s.access == Access::depth_attachment_read;
    } else {
      continue;
    }
    refs.push_back(AttachmentRef{s.slot, 0, s.sub.layerCount == 1 ? 0 : AttachmentRef::kAllLayers});
  }
  if (refs.empty()) return;
  GLint maxDraw = 8;
  glGetIntegerv(GL_MAX_DRAW_BUFFERS, &maxDraw);
  if (static_cast<GLint>(colors) > maxDraw)
    throw RuntimeError("pass '" + run.name + "': " + std::to_string(colors) + " colour attachments, the GL allows " +
                       std::to_string(maxDraw));
  // A depth slot declared before a colour one still goes last: colour
  // attachments number from 0 in slot order.
  std::stable_partition(refs.begin(), refs.end(), [&](const AttachmentRef& r) { return !run.find(r.slot)->depthAttachment; });
  const PassFramebuffer fb = run.framebuffer(std::span<const AttachmentRef>(refs));
  run.fbo = fb.id;
  run.fbExtent = fb.extent;
}

}  // namespace rgraph
