// Appending to a shared list in the items' order, not in the order the
// invocations happen to run: a list whose order follows atomicAdd's changes
// with the scheduling (on a GPU, from frame to frame), and so does every sum
// over it in floating point and, when the list is cut at its length, which
// items it keeps. Here the group takes its items in rounds, item `slot` of a
// round being the invocation with localIndex() `slot`; each invocation says
// whether it keeps its item, and gets the number of kept items before it in
// the round: the list's order is the items' whichever invocation had which.
// One barrier a round; three bit sets in turn, so that clearing the one two
// rounds ahead needs no barrier of its own.
// Needs include/invocation.glsl first. Every invocation of the group calls
// orderedAppendInit() before the group's first barrier, then orderedAppend()
// the same number of times, in dynamically uniform control flow.
const uint kAppendWords = (kGroupInvocations + 31u) / 32u;
shared uint s_appendBits[3][kAppendWords];
uint g_appendRound = 0u;

void orderedAppendInit(uint slot) {
  if (slot < kAppendWords) {
    s_appendBits[0][slot] = 0u;
    s_appendBits[1][slot] = 0u;
  }
}

// The number of kept items before item `slot` of this round (its place in
// the list from the round's first); `total`: the items the round keeps.
uint orderedAppend(bool keep, uint slot, out uint total) {
  const uint b = g_appendRound % 3u;
  ++g_appendRound;
  const uint word = slot / 32u, bit = 1u << (slot % 32u);
#if RGRAPH_PERMUTE_INVOCATIONS == 5
  // Broken on purpose (include/invocation.glsl): the place atomicAdd gives.
  uint before = 0u;
  if (keep) before = atomicAdd(s_appendBits[b][0], 1u);
  groupBarrier();
  total = s_appendBits[b][0];
#else
  if (keep) atomicOr(s_appendBits[b][word], bit);
  groupBarrier();
  uint before = uint(bitCount(s_appendBits[b][word] & (bit - 1u)));
  total = 0u;
  for (uint w = 0u; w < kAppendWords; ++w) {
    const uint n = uint(bitCount(s_appendBits[b][w]));
    total += n;
    if (w < word) before += n;
  }
#endif
  // Last read in the previous round (before this round's barrier), next set
  // in the round after the next (after the next round's barrier).
  if (slot < kAppendWords) s_appendBits[(b + 2u) % 3u][slot] = 0u;
  return before;
}
