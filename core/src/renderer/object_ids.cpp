#include "object_ids.h"

#include <GL/glcorearb.h>

#include <algorithm>

#include "rgraph/gl/executor.h"
#include "rgraph/registry.h"

namespace rgraph {

namespace {
const SlotDecl* objectIdSlot(const PassTypeDesc& type) {
  for (const auto& s : type.slots)
    if (s.name == kObjectIdSlot && s.access == Access::color_attachment) return &s;
  return nullptr;
}
bool hasObjectIdParam(const PassTypeDesc& type) {
  return std::any_of(type.params.begin(), type.params.end(),
                     [](const ParamDecl& p) { return p.name == kObjectIdSlot && p.type == ParamType::boolean; });
}
bool declared(const GraphDesc& graph, const std::string& name) {
  return std::any_of(graph.resources.begin(), graph.resources.end(),
                     [&](const ResourceDecl& r) { return r.name == name; });
}
}  // namespace

std::vector<std::string> addObjectIds(PipelineConfig& pipeline, const PassRegistry& registry) {
  std::vector<std::string> changed;
  GraphDesc& graph = pipeline.graph;
  for (size_t i = 0; i < graph.passes.size(); ++i) {
    PassDecl& pass = graph.passes[i];
    const PassTypeDesc* type = registry.find(pass.type);
    const SlotDecl* slot = type ? objectIdSlot(*type) : nullptr;
    if (!pass.enabled || !slot || !hasObjectIdParam(*type) || i >= pipeline.params.size()) continue;
    if (std::any_of(pass.uses.begin(), pass.uses.end(), [](const ResourceUse& u) { return u.slot == kObjectIdSlot; }))
      continue;  // the pipeline asks itself
    // One resource per pass (a second geometry pass writes its own); the
    // first is "object_id" unless the pipeline has a resource of that name.
    std::string name = kObjectIdSlot;
    for (int n = 2; declared(graph, name); ++n) name = std::string(kObjectIdSlot) + "_" + std::to_string(n);
    ResourceDecl r;
    r.name = name;
    r.texture.format = slot->formats.empty() ? Format::rg32ui : slot->formats.front();
    r.texture.size.kind = SizeSpec::Kind::output;
    graph.resources.push_back(r);
    ResourceUse use;
    use.slot = kObjectIdSlot;
    use.access = Access::color_attachment;
    use.output = name;
    pass.uses.push_back(use);
    pipeline.params[i].set(kObjectIdSlot, true);
    changed.push_back(pass.name);
  }
  return changed;
}

std::optional<ObjectIdSource> findObjectIds(const Plan& plan) {
  std::optional<ObjectIdSource> found;
  for (size_t step = 0; step < plan.order.size(); ++step) {
    const PassIndex p = plan.order[step];
    for (const BoundUse& use : plan.bindings[p.value()])
      if (use.slot == kObjectIdSlot && use.access == Access::color_attachment && use.resource.valid())
        found = ObjectIdSource{plan.resource(use.resource).name, step};
  }
  return found;
}

PickReader::~PickReader() {
  if (fence_) glDeleteSync(fence_);
}

void PickReader::request(uint32_t x, uint32_t y, Extent output) {
  requested_ = Request{x, y, output};
  answer_.reset();
}

void PickReader::afterPass(size_t step, const Executor& executor, uint64_t frame,
                           const std::function<std::vector<InstanceId>()>& objects) {
  if (!requested_ || !source_ || step != source_->step) return;
  if (inFlight_) {
    if (!ready(false)) return;  // still copying: this request waits for a later frame
    resolve();                  // the answer to a request this one replaced
  }
  const GLuint texture = executor.textureOf(source_->resource);
  if (!texture) return;
  // Its size from the plan, not a glGet (a round trip on drivers that run GL on a thread of their own).
  GLint w = 0, h = 0;
  for (const PlannedResource& res : executor.plan().resources)
    if (res.name == source_->resource) w = GLint(res.extent.width), h = GLint(res.extent.height);
  if (w <= 0 || h <= 0) return;
  const Request& r = *requested_;
  // The ids may be at another size than the output (a scaled resource):
  // the same place in them. GL's rows count from the bottom.
  const auto tx = static_cast<GLint>(uint64_t(r.x) * uint64_t(w) / std::max(r.output.width, 1u));
  const auto ty = static_cast<GLint>(uint64_t(r.y) * uint64_t(h) / std::max(r.output.height, 1u));
  if (!pixels_) {
    // Made once: read through a persistent, coherent mapping, so that taking
    // an answer is a memory read, not a GL call that could wait.
    pixels_ = gl::createBuffer();
    const GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    glNamedBufferStorage(pixels_.id(), 2 * sizeof(uint32_t), nullptr, flags);
    mapped_ = static_cast<const uint32_t*>(glMapNamedBufferRange(pixels_.id(), 0, 2 * sizeof(uint32_t), flags));
  }
  glBindBuffer(GL_PIXEL_PACK_BUFFER, pixels_.id());
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureSubImage(texture, 0, tx, h - 1 - ty, 0, 1, 1, 1, GL_RG_INTEGER, GL_UNSIGNED_INT,
                       2 * sizeof(uint32_t), nullptr);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  fence_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  glFlush();  // so that the fence signals without anyone waiting on it
  inFlight_ = requested_;
  inFlightFrame_ = frame;
  inFlightObjects_ = objects();
  requested_.reset();
}

void PickReader::cancel() {
  if (fence_) glDeleteSync(fence_);
  fence_ = nullptr;
  requested_.reset();
  inFlight_.reset();
  inFlightObjects_.clear();
  answer_.reset();
}

void PickReader::endFrame(uint64_t frame) {
  if (!requested_ || source_) return;
  PickResult none;
  none.x = requested_->x;
  none.y = requested_->y;
  none.problem = "the pipeline writes no object ids (frame " + std::to_string(frame) +
                 "): set RendererOptions::picking, or give its geometry pass \"object_id\": true and an "
                 "'object_id' output (docs/embedding.md, Picking)";
  answer_ = std::move(none);
  requested_.reset();
}

bool PickReader::ready(bool wait) {
  if (!inFlight_ || !fence_) return false;
  GLint status = GL_UNSIGNALED;
  if (wait) {
    const GLenum r = glClientWaitSync(fence_, GL_SYNC_FLUSH_COMMANDS_BIT, uint64_t(10) * 1000 * 1000 * 1000);
    status = r == GL_ALREADY_SIGNALED || r == GL_CONDITION_SATISFIED ? GL_SIGNALED : GL_UNSIGNALED;
  } else {
    glGetSynciv(fence_, GL_SYNC_STATUS, 1, nullptr, &status);
  }
  if (status != GL_SIGNALED) return false;
  glDeleteSync(fence_);
  fence_ = nullptr;
  return true;
}

PickResult PickReader::resolve() {
  PickResult out;
  out.x = inFlight_->x;
  out.y = inFlight_->y;
  out.frame = inFlightFrame_;
  const uint32_t entry = mapped_ ? mapped_[0] : 0;  // Objects entry + 1; 0: nothing drawn
  if (entry > 0 && entry - 1 < inFlightObjects_.size()) {
    out.instance = inFlightObjects_[entry - 1];
    out.triangle = mapped_[1];
  }
  inFlight_.reset();
  inFlightObjects_.clear();
  return out;
}

}  // namespace rgraph
