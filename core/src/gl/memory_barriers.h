// Memory barriers from declared access (internal to the GL backend).
//
// Image stores and storage-buffer writes are incoherent in OpenGL: a later
// command sees them only after a glMemoryBarrier whose bits name the way it
// reads (GL 4.5 core, 7.12.2). Passes declare how they touch each resource
// (Access), so the executor can issue those barriers itself: once per plan
// (Executor::resize) this derives, for every executed pass, the bits it needs
// before it runs, and the bits needed after the frame for whoever reads the
// results outside the graph (readbacks, a window blit, the next frame). No
// pass calls glMemoryBarrier.
#pragma once

#include <cstdint>
#include <vector>

#include "rgraph/graph.h"

namespace rgraph {

struct MemoryBarrierPlan {
  std::vector<uint32_t> beforePass;  // per Plan::order entry: glMemoryBarrier bits, 0 for none
  uint32_t afterFrame = 0;           // after the last pass; 0 when nothing was written incoherently
};

// The barrier bit that makes earlier image/storage writes visible to a pass
// touching a resource of `kind` through `access`.
uint32_t memoryBarrierBit(Access access, ResourceKind kind);

// Walks the plan's execution order. A resource's memory (its physical texture
// when aliased: aliases share memory) written through storage_write is
// "pending" until a barrier covers each way it is touched afterwards: a later
// pass touching it (reading, loading, or overwriting an alias) gets the bit
// for its access (and the texture-update bit when it first clears a texture
// it does not attach) unless an earlier barrier since that write had it.
// A barrier covers every write issued before it, so each bit is issued once
// per write. After the frame, every way an outside reader may touch what was
// written through storage and is not yet covered. The plan must be ok.
MemoryBarrierPlan deriveMemoryBarriers(const Plan& plan);

}  // namespace rgraph
