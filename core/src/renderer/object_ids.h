// Picking (Renderer::requestPick, RendererOptions::picking): asking a
// pipeline for object ids, finding them in a plan, and reading one pixel of
// them back a frame late. The ids are written by a pass type that declares a
// colour slot "object_id" and a boolean parameter of the same name (the
// geometry pass: passes/common gbuffer_layout.h, objectIdTarget); core knows
// that convention, no pass type by name.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rgraph/config.h"
#include "rgraph/gl/objects.h"
#include "rgraph/graph.h"
#include "rgraph/renderer.h"

typedef struct __GLsync* GLsync;

namespace rgraph {

class Executor;
class PassRegistry;

inline constexpr const char* kObjectIdSlot = "object_id";

// RendererOptions::picking: every enabled pass whose type can write object
// ids and leaves its slot unbound gets its parameter on and the slot bound to
// a resource "object_id" (a new name when the pipeline has one), declared at
// the output's size in the slot's format. Returns the passes changed.
std::vector<std::string> addObjectIds(PipelineConfig& pipeline, const PassRegistry& registry);

// The resource the last pass that runs writes through an "object_id" slot,
// and the step after which it is complete; nullopt: no pass writes ids.
struct ObjectIdSource {
  std::string resource;
  size_t step = 0;
};
std::optional<ObjectIdSource> findObjectIds(const Plan& plan);

// One pick at a time: a request, the copy of its pixel in flight (a pixel
// buffer mapped once, persistently, and a fence), and the last answer.
class PickReader {
 public:
  PickReader() = default;
  ~PickReader();
  PickReader(const PickReader&) = delete;
  PickReader& operator=(const PickReader&) = delete;

  void setSource(std::optional<ObjectIdSource> source) { source_ = std::move(source); }
  // A new question (top-left origin, output pixels of an output of `output`
  // size): replaces one not yet read; the last answer is forgotten.
  void request(uint32_t x, uint32_t y, Extent output);
  // After each pass of frame `frame`: at the source's step, queues the copy
  // of the requested pixel and remembers which object each Objects entry was
  // (`objects()`: the scene's objects in scene().primitives order, asked
  // only then). A copy still in flight is polled first, and the request
  // waits for a later frame while it is.
  void afterPass(size_t step, const Executor& executor, uint64_t frame,
                 const std::function<std::vector<InstanceId>()>& objects);
  // Forgets the request, the copy in flight and the answer (a new scene).
  void cancel();
  // At the end of a frame: a request the frame could not read (no ids in the
  // pipeline) is answered with the problem.
  void endFrame(uint64_t frame);
  // Takes the copy in flight once its fence has signalled (wait: waits for it).
  // `alive` says whether an object still exists (RenderScene::contains).
  // The answer of a request replaced since is dropped.
  void poll(bool wait, const std::function<bool(InstanceId)>& alive) {
    if (!ready(wait)) return;
    PickResult r = resolve();
    if (requested_) return;
    if (r.instance && !alive(r.instance)) r.instance = {}, r.triangle = 0;
    answer_ = std::move(r);
  }
  const std::optional<PickResult>& answer() const { return answer_; }
  // A request waits for a frame: the frame must run the after-pass hook.
  bool wantsFrame() const { return requested_.has_value(); }

 private:
  struct Request {
    uint32_t x = 0, y = 0;
    Extent output;
  };
  bool ready(bool wait);
  PickResult resolve();

  std::optional<ObjectIdSource> source_;
  std::optional<Request> requested_;  // asked, not yet copied
  std::optional<Request> inFlight_;   // copied, fence pending
  uint64_t inFlightFrame_ = 0;
  std::vector<InstanceId> inFlightObjects_;
  GLsync fence_ = nullptr;
  gl::Buffer pixels_;                  // 8 bytes: one rg32ui texel
  const uint32_t* mapped_ = nullptr;   // persistently mapped, coherent
  std::optional<PickResult> answer_;
};

}  // namespace rgraph
