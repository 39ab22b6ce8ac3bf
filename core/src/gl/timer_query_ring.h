// Pass times from GL_TIME_ELAPSED queries without waiting for the GPU: a ring
// of frame slots, each one query per pass. A frame's queries are read only
// once GL_QUERY_RESULT_AVAILABLE says they are in (typically 1-3 frames
// later), and a slot is used again only after all its queries were read: a
// frame that finds every slot still in flight is not timed at all (rather
// than waiting, or timing some of its passes: its sum would then be short).
// Used by the executor (executor.cpp) when it times with queries. Not installed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "rgraph/gl/objects.h"

namespace rgraph::gl {

class TimerQueryRing {
 public:
  static constexpr size_t kDepth = 3;  // frames in flight: enough for a CPU 2 frames ahead of the GPU

  // One query per pass and slot (created here: a GL context must be current).
  explicit TimerQueryRing(size_t passes);

  // Reads the results of every frame in flight whose queries are all in,
  // oldest first, never waiting: the newest becomes result(). beginFrame()
  // does this first.
  void collect();
  // The start of frame `frame` (Executor::frameIndex): collect(), then takes
  // a free slot for it. false when none is free: this frame is not timed.
  bool beginFrame(uint64_t frame);
  // Around pass `pass` of the frame begun (no-ops when it is not timed).
  void beginPass(size_t pass);
  void endPass(size_t pass);
  // The frame's queries are all issued: its slot waits for them. A frame
  // begun but never ended (a pass threw) is dropped at the next beginFrame,
  // its slot freed once the queries it issued are in.
  void endFrame();

  // The newest frame whose every pass was read, and its times (ms, per pass).
  std::optional<uint64_t> resultFrame() const { return resultFrame_; }
  const std::vector<double>& resultMs() const { return resultMs_; }
  // Frames that found every slot in flight (not timed).
  uint64_t untimedFrames() const { return untimed_; }
  size_t queryCount() const { return slots_.size() * passes_; }

 private:
  enum class State : uint8_t { free, recording, inFlight, dropped };
  struct Slot {
    std::vector<Query> queries;  // one per pass
    State state = State::free;
    uint64_t frame = 0;
    size_t issued = 0;  // queries begun in this slot's frame, in pass order
  };
  // Whether every query `slot` issued is in (reads them when it is in flight).
  bool tryRead(Slot& slot);

  size_t passes_ = 0;
  std::vector<Slot> slots_;
  Slot* recording_ = nullptr;
  std::optional<uint64_t> resultFrame_;
  std::vector<double> resultMs_;
  uint64_t untimed_ = 0;
};

}  // namespace rgraph::gl
