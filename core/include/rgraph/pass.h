// What a pass type is (its declaration) and what a pass instance does at run
// time. No GL include: GL object names travel as uint32_t.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "rgraph/format.h"
#include "rgraph/graph.h"
#include "rgraph/params.h"

namespace rgraph {

struct Scene;          // defined by the scene module
class ShaderLibrary;   // defined by the GL backend
class GpuScene;        // the scene uploaded to the GPU (rgraph/gl/gpu_scene.h)

// How a slot may be bound in a config.
struct SlotDecl {
  std::string name;
  Access access = Access::sampled;
  bool required = true;
  // For writing slots: whether the config may (or must) also bind the slot in
  // "inputs" to load that version and produce its successor (blend into it).
  enum class Load { never, optional, required };
  Load load = Load::never;
  std::vector<Format> formats;  // accepted formats; empty accepts any
  bool acceptsMultisample = false;
  std::string description;
};

class PassContext;

// One pass in a running pipeline. Created per pass per realized plan.
class PassInstance {
 public:
  virtual ~PassInstance() = default;
  // After the plan's textures and framebuffers exist (again after a resize).
  // Throw rgraph::RuntimeError with a clear message on failure.
  virtual void setup(PassContext& /*ctx*/) {}
  // Record the pass's GL work. The executor has already bound nothing: use
  // ctx.framebuffer() and ctx.texture(slot).
  virtual void execute(PassContext& ctx) = 0;
};

struct PassTypeDesc {
  std::string name;          // the config's "type"
  std::string description;   // one line
  std::vector<SlotDecl> slots;
  std::vector<ParamDecl> params;
  bool sideEffect = false;
  // Shader files this pass type uses (relative to the shader directory), so
  // `rgraph validate` can check them without a GL context.
  std::vector<std::string> shaders;
  std::function<std::unique_ptr<PassInstance>()> create;
  std::string origin = "built-in";  // or the plugin file it came from

  const SlotDecl* findSlot(std::string_view slot) const;
  const ParamDecl* findParam(std::string_view param) const;
};

// Per-frame data the executor gives to passes.
class PassContext {
 public:
  virtual ~PassContext() = default;
  virtual const std::string& passName() const = 0;
  virtual const ParamSet& params() const = 0;
  virtual Extent outputExtent() const = 0;

  // Slots: bound or not, GL texture name (0 for unbound or buffers), format, size.
  virtual bool bound(std::string_view slot) const = 0;
  virtual uint32_t texture(std::string_view slot) const = 0;
  virtual uint32_t buffer(std::string_view slot) const = 0;
  virtual Format format(std::string_view slot) const = 0;
  virtual Extent extent(std::string_view slot) const = 0;
  virtual uint32_t samples(std::string_view slot) const = 0;
  // True when a writing slot loads its previous version (do not clear it).
  virtual bool loads(std::string_view slot) const = 0;

  // The pass's framebuffer: colour attachments in slot-declaration order at
  // GL_COLOR_ATTACHMENT0.., plus the depth/stencil slot; draw buffers set.
  // 0 when the pass has no attachments. Its size is framebufferExtent().
  virtual uint32_t framebuffer() const = 0;
  virtual Extent framebufferExtent() const = 0;

  virtual ShaderLibrary& shaders() = 0;
  virtual const Scene* scene() const = 0;  // nullptr when the pipeline runs without a scene
  // The scene on the GPU, created once per executor; its Frame block is
  // updated for the output extent before the first pass of every frame.
  // nullptr without a scene.
  virtual GpuScene* gpuScene() { return nullptr; }
};

}  // namespace rgraph
