// Two pass types for the history-resource tests (GL and renderer suites):
// one writes a colour that changes every frame, the other shows what its
// history input holds and records what the executor tells it.
//
//   history_test_colour: writes "color" cleared to frameColour(frameIndex()).
//   history_test_probe: reads "prev" (sampled, multisample accepted), writes
//     "dst" = prev (a framebuffer blit, which resolves a multisampled prev),
//     and appends {frameIndex, historyValid("prev"), historyValid("dst")}.
#pragma once

#include <GL/glcorearb.h>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rgraph/format.h"
#include "rgraph/gl/objects.h"
#include "rgraph/pass.h"
#include "rgraph/registry.h"

namespace rgraph::test {

// What frame `frame` writes: a different red each frame (multiples of 16/255
// so that rgba8 stores them exactly), for 15 frames.
inline std::array<float, 4> frameColour(uint64_t frame) {
  return {static_cast<float>((frame % 15 + 1) * 16) / 255.0f, 64.0f / 255.0f, 128.0f / 255.0f, 1.0f};
}

struct HistoryProbeRecord {
  uint64_t frame = 0;
  bool prevValid = false;
  bool dstValid = false;
};

// One per process: the probe instances append to it (tests clear it first).
inline std::vector<HistoryProbeRecord>& historyProbeLog() {
  static std::vector<HistoryProbeRecord> log;
  return log;
}

namespace history_detail {

class ColourPass final : public PassInstance {
 public:
  void execute(PassContext& ctx) override {
    const std::array<float, 4> c = frameColour(ctx.frameIndex());
    glClearNamedFramebufferfv(ctx.framebuffer(), GL_COLOR, 0, c.data());
  }
};

class ProbePass final : public PassInstance {
 public:
  void execute(PassContext& ctx) override {
    historyProbeLog().push_back({ctx.frameIndex(), ctx.historyValid("prev"), ctx.historyValid("dst")});
    if (!read_) read_ = gl::createFramebuffer();
    glNamedFramebufferTexture(read_.id(), GL_COLOR_ATTACHMENT0, ctx.texture("prev"), 0);
    glNamedFramebufferReadBuffer(read_.id(), GL_COLOR_ATTACHMENT0);
    const Extent e = ctx.extent("prev");
    const auto w = static_cast<GLint>(e.width), h = static_cast<GLint>(e.height);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glBlitNamedFramebuffer(read_.id(), ctx.framebuffer(), 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }

 private:
  gl::Framebuffer read_;
};

inline SlotDecl slot(const std::string& name, Access access) {
  SlotDecl s;
  s.name = name;
  s.access = access;
  s.acceptsMultisample = true;
  return s;
}

}  // namespace history_detail

// Adds both types to `reg` (no-op when they are there already).
inline void addHistoryTestTypes(PassRegistry& reg) {
  if (reg.find("history_test_colour")) return;
  PassTypeDesc colour;
  colour.name = "history_test_colour";
  colour.description = "test: clears its colour slot to a colour of the frame index";
  colour.slots = {history_detail::slot("color", Access::color_attachment)};
  colour.create = [] { return std::make_unique<history_detail::ColourPass>(); };
  reg.add(std::move(colour));
  PassTypeDesc probe;
  probe.name = "history_test_probe";
  probe.description = "test: copies its history input out and records historyValid";
  probe.slots = {history_detail::slot("prev", Access::sampled), history_detail::slot("dst", Access::color_attachment)};
  probe.create = [] { return std::make_unique<history_detail::ProbePass>(); };
  reg.add(std::move(probe));
}

}  // namespace rgraph::test
