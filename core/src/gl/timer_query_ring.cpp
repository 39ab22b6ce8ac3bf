#include "timer_query_ring.h"

#include <GL/glcorearb.h>

#include <algorithm>
#include <array>

namespace rgraph::gl {

TimerQueryRing::TimerQueryRing(size_t passes) : passes_(passes), slots_(kDepth), resultMs_(passes, 0.0) {
  for (Slot& s : slots_)
    for (size_t i = 0; i < passes; ++i) s.queries.push_back(createQuery(GL_TIME_ELAPSED));
}

bool TimerQueryRing::tryRead(Slot& slot) {
  if (slot.issued == 0) return true;
  // The last query first: while it is not in (the usual case for a frame in
  // flight) one call says so; once it is, the earlier ones normally are too.
  // Each is still asked before its result is read: GL promises no order.
  auto available = [](const Query& q) {
    GLuint in = GL_FALSE;
    glGetQueryObjectuiv(q.id(), GL_QUERY_RESULT_AVAILABLE, &in);
    return in == GL_TRUE;
  };
  if (!available(slot.queries[slot.issued - 1])) return false;
  for (size_t i = 0; i + 1 < slot.issued; ++i)
    if (!available(slot.queries[i])) return false;
  if (slot.state != State::inFlight) return true;  // dropped: nothing to read
  for (size_t i = 0; i < slot.issued; ++i) {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(slot.queries[i].id(), GL_QUERY_RESULT, &ns);  // in: no wait
    resultMs_[i] = static_cast<double>(ns) / 1.0e6;
  }
  resultFrame_ = slot.frame;
  return true;
}

void TimerQueryRing::collect() {
  // Oldest first, so that result() ends on the newest frame that is in (no
  // allocation: this runs every frame).
  std::array<Slot*, kDepth> waiting{};
  size_t n = 0;
  for (Slot& s : slots_)
    if (s.state == State::inFlight || s.state == State::dropped) waiting[n++] = &s;
  std::sort(waiting.begin(), waiting.begin() + static_cast<std::ptrdiff_t>(n),
            [](const Slot* a, const Slot* b) { return a->frame < b->frame; });
  for (size_t w = 0; w < n; ++w) {
    Slot* s = waiting[w];
    if (s->state == State::inFlight && resultFrame_ && s->frame < *resultFrame_) {
      s->state = State::dropped;  // older than a frame already reported: only freed
    }
    if (tryRead(*s)) {
      s->state = State::free;
      s->issued = 0;
    }
  }
}

bool TimerQueryRing::beginFrame(uint64_t frame) {
  if (recording_) {  // the last frame threw before endFrame
    recording_->state = State::dropped;
    recording_ = nullptr;
  }
  collect();
  auto freeSlot = std::find_if(slots_.begin(), slots_.end(), [](const Slot& s) { return s.state == State::free; });
  if (freeSlot == slots_.end()) {
    ++untimed_;
    return false;
  }
  recording_ = &*freeSlot;
  recording_->state = State::recording;
  recording_->frame = frame;
  recording_->issued = 0;
  return true;
}

void TimerQueryRing::beginPass(size_t pass) {
  if (!recording_ || pass != recording_->issued || pass >= passes_) return;
  glBeginQuery(GL_TIME_ELAPSED, recording_->queries[pass].id());
  ++recording_->issued;
}

void TimerQueryRing::endPass(size_t pass) {
  if (!recording_ || pass + 1 != recording_->issued) return;
  glEndQuery(GL_TIME_ELAPSED);
}

void TimerQueryRing::endFrame() {
  if (!recording_) return;
  // Every pass issued its query, or the frame is not reported.
  recording_->state = recording_->issued == passes_ ? State::inFlight : State::dropped;
  recording_ = nullptr;
}

}  // namespace rgraph::gl
