#include "pass_programs.h"

#include <GL/glcorearb.h>

#include <algorithm>
#include <exception>

#include "rgraph/config.h"
#include "rgraph/error.h"
#include "rgraph/scene_program.h"

namespace rgraph {

namespace {
std::string files(const ShaderProgramSpec& s) { return s.comp.empty() ? s.vert + " + " + s.frag : s.comp; }
}  // namespace

void PassPrograms::build(const std::string& passName, const PassTypeDesc& type, const ParamSet& params,
                         ShaderLibrary& shaders, const std::vector<std::string>& sceneDefines) {
  ids_.clear();
  units_.clear();
  if (!type.programs) return;
  const std::string who = "pass '" + passName + "' (type '" + type.name + "')";
  std::vector<ShaderProgramSpec> specs;
  try {
    specs = type.programs(params);
  } catch (const std::exception& e) {
    throw RuntimeError(who + ": " + e.what());
  }
  GLint maxUnits = 16;
  glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &maxUnits);
  for (size_t i = 0; i < specs.size(); ++i) {
    const ShaderProgramSpec& s = specs[i];
    const std::string what = who + ", program " + std::to_string(i) + " (" + files(s) + ")";
    if (s.comp.empty() == (s.vert.empty() || s.frag.empty()))
      throw RuntimeError(what + ": a program is a vertex + fragment pair or a compute shader");
    for (const SamplerSlot& m : s.samplers) {
      const SlotDecl* slot = type.findSlot(m.slot);
      if (!slot || slot->access != Access::sampled)
        throw RuntimeError(what + ": sampler '" + m.uniform + "' reads '" + m.slot +
                           "', which is not a sampled slot of the type");
      if (m.unit < 0 || m.unit >= maxUnits)
        throw RuntimeError(what + ": sampler '" + m.uniform + "' of input '" + m.slot + "' names texture unit " +
                           std::to_string(m.unit) + "; name one of 0.." + std::to_string(maxUnits - 1) +
                           " (SamplerSlot::unit)");
      const auto unit = static_cast<uint32_t>(m.unit);
      bool known = false;
      for (const Unit& u : units_) {
        if (u.unit != unit) continue;
        if (u.slot != m.slot)
          throw RuntimeError(what + ": inputs '" + u.slot + "' and '" + m.slot + "' both name texture unit " +
                             std::to_string(unit));
        known = true;
      }
      if (!known) units_.push_back({unit, m.slot});
    }
    std::vector<std::string> defines = s.defines;
    if (drawsScene(s)) defines.insert(defines.end(), sceneDefines.begin(), sceneDefines.end());
    const uint32_t id =
        s.comp.empty() ? shaders.program(s.vert, s.frag, defines) : shaders.computeProgram(s.comp, s.defines);
    // Once here, so that a shader without layout(binding) reads the unit too.
    for (const SamplerSlot& m : s.samplers) {
      const GLint loc = glGetUniformLocation(id, m.uniform.c_str());
      if (loc < 0) continue;
      glProgramUniform1i(id, loc, m.unit);
      for (Unit& u : units_) u.read = u.read || u.unit == static_cast<uint32_t>(m.unit);
    }
    ids_.push_back(id);
  }
}

uint32_t PassPrograms::program(size_t index, const std::string& passName) const {
  if (index >= ids_.size())
    throw RuntimeError("pass '" + passName + "': asks for program " + std::to_string(index) + " but its type's " +
                       "programs() names " + std::to_string(ids_.size()));
  return ids_[index];
}

void PassPrograms::resolveSlots(const PassContext& ctx) {
  for (Unit& u : units_) u.texture = ctx.texture(u.slot);
}

void PassPrograms::resolveSamplers(const PipelineConfig& pipeline, size_t pass, const PassTypeDesc& type,
                                   gl::SamplerCache& cache) {
  for (Unit& u : units_) {
    if (!u.read) continue;  // bindSlots skips it: no sampler object for it either
    const SlotDecl* slot = type.findSlot(u.slot);
    const std::optional<SamplerState> state = slot ? slotSamplerState(pipeline, pass, *slot) : std::nullopt;
    u.sampler = state ? cache.get(*state) : 0;
  }
}

void PassPrograms::bindSlots() const {
  for (const Unit& u : units_) {
    if (!u.read) continue;
    glBindTextureUnit(u.unit, u.texture);
    if (u.sampler) glBindSampler(u.unit, u.sampler);
  }
}

void PassPrograms::unbindSamplers() const {
  for (const Unit& u : units_)
    if (u.read && u.sampler) glBindSampler(u.unit, 0);
}

std::vector<uint32_t> PassPrograms::units() const {
  std::vector<uint32_t> out;
  for (const Unit& u : units_)
    if (u.read) out.push_back(u.unit);
  return out;
}

RequestRecorder::RequestRecorder(ShaderLibrary& shaders, std::vector<Executor::BuiltProgram>& built,
                                 const std::string& pass)
    : shaders_(shaders), built_(built), pass_(pass) {
  shaders_.recordRequests(&log_);
}

RequestRecorder::~RequestRecorder() {
  shaders_.recordRequests(nullptr);
  for (auto& r : log_) {
    Executor::BuiltProgram b{pass_, std::move(r)};
    if (std::find(built_.begin(), built_.end(), b) == built_.end()) built_.push_back(std::move(b));
  }
}

}  // namespace rgraph
