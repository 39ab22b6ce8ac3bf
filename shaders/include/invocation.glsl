// Which invocation does which work, for every compute shader: they read
// their IDs through localIndex(), localId(), groupId() and globalId(), never
// through gl_LocalInvocationIndex and the like, so that a test can hand each
// invocation another's work and check that the output bytes do not change
// (tests/tiled/invocation_order_test.cpp, docs/testing.md).
// What GL 4.5 guarantees a work group, and so all these shaders assume:
// barrier() in dynamically uniform control flow (groupBarrier below, with
// memoryBarrierShared so that shared writes before it are visible after it),
// shared memory, and atomics that are atomic. Not guaranteed, and so never
// assumed: a subgroup (warp) size, invocations running in lockstep or in
// rows, any order among a group's invocations or among the work groups, or
// the order in which atomics from different invocations happen. A result
// built in atomic order (a list appended with atomicAdd) must not reach the
// output: include/ordered_append.glsl appends in the items' order instead.
// RGRAPH_PERMUTE_INVOCATIONS (tests only: the passes' hidden
// permute_invocations parameter, rgraph/passes/invocation_order.h) maps the
// hardware's IDs through a bijection before any use:
//   0 (or undefined) identity; 1 local index reversed; 2 local index rotated
//   by a third of the group plus one; 3 transposed (an x-major group read
//   y-major; a 1-D group as 8 columns); 4 the work groups and the local index
//   reversed; 5 rotated, with include/ordered_append.glsl (and
//   tiled_deferred.comp's cullTile) appending in atomic order
//   (order-dependent on purpose: the tests assert it changes the output,
//   so that they can see an order dependence; reversed, the tiles' lists
//   would come out in order again, reversed once by the bins and once by
//   the tiles).
// Include after the layout(local_size_...) declaration (gl_WorkGroupSize).
#ifndef RGRAPH_PERMUTE_INVOCATIONS
#define RGRAPH_PERMUTE_INVOCATIONS 0
#endif

const uint kGroupInvocations = gl_WorkGroupSize.x * gl_WorkGroupSize.y * gl_WorkGroupSize.z;

uint localIndex() {
  const uint i = gl_LocalInvocationIndex, n = kGroupInvocations;
#if RGRAPH_PERMUTE_INVOCATIONS == 1 || RGRAPH_PERMUTE_INVOCATIONS == 4
  return n - 1u - i;
#elif RGRAPH_PERMUTE_INVOCATIONS == 2 || RGRAPH_PERMUTE_INVOCATIONS == 5
  return (i + n / 3u + 1u) % n;
#elif RGRAPH_PERMUTE_INVOCATIONS == 3
  // i = b r + a (a < r) -> a (n / r) + b: a bijection when r divides n.
  const uint r = gl_WorkGroupSize.y > 1u ? gl_WorkGroupSize.x : (n % 8u == 0u ? 8u : 1u);
  return (i % r) * (n / r) + i / r;
#else
  return i;
#endif
}

// localIndex() as x, y, z (x fastest, as gl_LocalInvocationIndex orders them).
uvec3 localId() {
  const uint i = localIndex();
  return uvec3(i % gl_WorkGroupSize.x, (i / gl_WorkGroupSize.x) % gl_WorkGroupSize.y,
               i / (gl_WorkGroupSize.x * gl_WorkGroupSize.y));
}

uvec3 groupId() {
#if RGRAPH_PERMUTE_INVOCATIONS == 4
  return gl_NumWorkGroups - 1u - gl_WorkGroupID;
#else
  return gl_WorkGroupID;
#endif
}

uvec3 globalId() { return groupId() * gl_WorkGroupSize + localId(); }

// Every invocation of the group waits here, and sees the shared writes that
// any made before it. Call only in dynamically uniform control flow.
void groupBarrier() {
  memoryBarrierShared();
  barrier();
}
