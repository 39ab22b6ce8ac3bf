// The programs of one pass, built by the executor from its type's
// PassTypeDesc::programs(params) (the same specs `rgraph validate` checks),
// and the sampled slots those programs read, with their texture units.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "rgraph/gl/executor.h"
#include "rgraph/gl/shader_library.h"
#include "rgraph/pass.h"
#include "sampler_cache.h"

namespace rgraph {

struct PipelineConfig;

class PassPrograms {
 public:
  // Builds every program of the specs through `shaders` (which caches them)
  // and sets each sampler uniform to its unit, once. Throws RuntimeError
  // naming the pass: programs() threw, a sampler names no unit or no sampled
  // slot of the type, two slots share a unit, a shader fails to compile.
  // `sceneDefines` go to every program whose vertex shader is scene.vert
  // (the scene's own variant: SCENE_ANIMATION where it deforms).
  void build(const std::string& passName, const PassTypeDesc& type, const ParamSet& params, ShaderLibrary& shaders,
             const std::vector<std::string>& sceneDefines = {});

  uint32_t program(size_t index, const std::string& passName) const;
  size_t count() const { return ids_.size(); }

  // Takes the textures of the sampled slots the specs name, once per build
  // (texture 0 for an unbound slot), so that a frame looks up no slot names.
  void resolveSlots(const PassContext& ctx);
  // The sampler objects of the slots with a sampler state (declared by the
  // type or overridden by pass `pass` of the pipeline), from `cache`, once
  // per build. Slots without one keep sampler 0 (the texture's parameters).
  void resolveSamplers(const PipelineConfig& pipeline, size_t pass, const PassTypeDesc& type,
                       gl::SamplerCache& cache);
  // Binds them to their units: those a program reads (a sampler the
  // compiler dropped is not bound), with their sampler objects. Nothing
  // unbinds the textures after the pass: the next pass binds its own units,
  // the executor clears every slot unit at the end of the frame (units()).
  void bindSlots() const;
  // Puts sampler 0 back on the units bindSlots() gave a sampler object, after
  // the pass: between passes every unit samples with its texture's own
  // parameters, so that a pass binding textures itself needs no sampler call
  // and slots without a state need none either.
  void unbindSamplers() const;
  std::vector<uint32_t> units() const;

 private:
  std::vector<uint32_t> ids_;
  struct Unit {
    uint32_t unit = 0;
    std::string slot;
    bool read = false;     // an active sampler uniform in one of the programs
    uint32_t texture = 0;  // resolveSlots
    uint32_t sampler = 0;  // resolveSamplers; 0: the texture's own parameters
  };
  std::vector<Unit> units_;  // each unit once
};

// Records the programs a pass asks the ShaderLibrary for while it is set up
// or executed (each once per pass) into `built` (Executor::builtPrograms),
// for as long as it lives.
class RequestRecorder {
 public:
  RequestRecorder(ShaderLibrary& shaders, std::vector<Executor::BuiltProgram>& built, const std::string& pass);
  ~RequestRecorder();
  RequestRecorder(const RequestRecorder&) = delete;
  RequestRecorder& operator=(const RequestRecorder&) = delete;

 private:
  ShaderLibrary& shaders_;
  std::vector<Executor::BuiltProgram>& built_;
  const std::string& pass_;
  std::vector<ProgramRequest> log_;
};

}  // namespace rgraph
