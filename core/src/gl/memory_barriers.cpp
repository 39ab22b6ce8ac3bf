// Memory barriers from declared access: see memory_barriers.h.
#include "memory_barriers.h"

#include <GL/glcorearb.h>

namespace rgraph {
namespace {

// What a reader outside the graph may do with a texture or buffer after the
// frame: read it back (glGetTextureImage, glReadPixels into a pixel buffer),
// blit or sample it (a window), or the next frame's passes in any way.
constexpr uint32_t kTextureAfterFrame = GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                                        GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                                        GL_PIXEL_BUFFER_BARRIER_BIT;
constexpr uint32_t kBufferAfterFrame = GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT |
                                       GL_UNIFORM_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
                                       GL_ELEMENT_ARRAY_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
                                       GL_PIXEL_BUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT;

struct MemoryState {
  bool storageWritten = false;  // written through storage_write this frame
  ResourceKind kind = ResourceKind::texture;
  uint32_t covered = 0;  // bits issued since its last storage write
};

}  // namespace

uint32_t memoryBarrierBit(Access access, ResourceKind kind) {
  switch (access) {
    case Access::sampled:
      return GL_TEXTURE_FETCH_BARRIER_BIT;
    case Access::storage_read:
    case Access::storage_write:
      return kind == ResourceKind::buffer ? GL_SHADER_STORAGE_BARRIER_BIT : GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    // Attachments are read and written through the framebuffer, and so are
    // blits (glBlitNamedFramebuffer).
    case Access::color_attachment:
    case Access::depth_attachment:
    case Access::depth_attachment_read:
    case Access::blit_src:
    case Access::blit_dst:
      return GL_FRAMEBUFFER_BARRIER_BIT;
  }
  return 0;
}

MemoryBarrierPlan deriveMemoryBarriers(const Plan& plan) {
  MemoryBarrierPlan out;
  // One entry per physical texture, then one per resource: the plan is ok,
  // so a resource a pass uses has a physical or is imported (its own memory).
  const size_t physicalCount = plan.physical.size();
  std::vector<MemoryState> memory(physicalCount + plan.resources.size());
  auto memoryOf = [&](ResourceIndex resource) -> MemoryState& {
    const PlannedResource& r = plan.resource(resource);
    return memory[r.physical.valid() ? r.physical.value() : physicalCount + resource.value()];
  };

  for (PassIndex pass : plan.order) {
    const std::vector<BoundUse>& uses = plan.uses(pass);
    uint32_t bits = 0;
    for (const BoundUse& u : uses) {
      const MemoryState& m = memoryOf(u.resource);
      if (!m.storageWritten) continue;
      const ResourceKind kind = plan.resource(u.resource).kind;
      uint32_t need = memoryBarrierBit(u.access, kind);
      // A first write applies the resource's clear, to a texture that is not
      // attached with glClearTexImage: a texture update.
      if (u.firstWrite && kind == ResourceKind::texture && !isAttachmentAccess(u.access))
        need |= GL_TEXTURE_UPDATE_BARRIER_BIT;
      bits |= need & ~m.covered;
    }
    // The barrier orders every incoherent write issued so far.
    for (MemoryState& m : memory)
      if (m.storageWritten) m.covered |= bits;
    for (const BoundUse& u : uses) {
      if (u.access != Access::storage_write) continue;
      MemoryState& m = memoryOf(u.resource);
      m.storageWritten = true;
      m.kind = plan.resource(u.resource).kind;
      m.covered = 0;
    }
    out.beforePass.push_back(bits);
  }
  for (const MemoryState& m : memory)
    if (m.storageWritten)
      out.afterFrame |= (m.kind == ResourceKind::buffer ? kBufferAfterFrame : kTextureAfterFrame) & ~m.covered;
  return out;
}

}  // namespace rgraph
