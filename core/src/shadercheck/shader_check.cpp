// The glslang shader checker (see rgraph/shader_check.h). No GL here: stages
// are compiled and linked by glslang as GLSL 4.50 for OpenGL, and the linked
// program is reflected to compare its fragment outputs and samplers with
// what the config binds.
#include "rgraph/shader_check.h"

#include <glslang/Include/Types.h>
#include <glslang/MachineIndependent/localintermediate.h>
#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <set>

#include "rgraph/config.h"
#include "sampler_shape.h"
#include "rgraph/registry.h"
#include "rgraph/scene_program.h"
#include "uniform_blocks.h"

namespace rgraph {
namespace {

void initGlslang() {
  static std::once_flag once;
  std::call_once(once, [] {
    glslang::InitializeProcess();
    // Cached results hold no glslang objects, so its tables can go at exit
    // (keeps leak checkers quiet).
    std::atexit([] { glslang::FinalizeProcess(); });
  });
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

const char* stageName(EShLanguage s) {
  switch (s) {
    case EShLangVertex: return "vertex";
    case EShLangFragment: return "fragment";
    case EShLangCompute: return "compute";
    case EShLangGeometry: return "geometry";
    case EShLangTessControl: return "tessellation control";
    case EShLangTessEvaluation: return "tessellation evaluation";
    default: return "shader";
  }
}

// One stage to compile: its file name as the pass gave it, and the loaded source.
struct Stage {
  EShLanguage lang;
  std::string file;
  ShaderSource src;
  bool loaded = false;
  std::unique_ptr<glslang::TShader> shader;
};

// Compiles one stage as an OpenGL driver would: desktop GLSL, core profile,
// default version 450. The input dialect is left at "none" on purpose:
// EShClientOpenGL as *input* dialect switches glslang to ARB_gl_spirv rules
// (every in/out and loose uniform must have a location), which GLSL compiled
// by a GL driver does not require; the client is still OpenGL 4.5 (not
// Vulkan), no SPIR-V target.
bool compileStage(Stage& st, std::vector<ShaderMessage>& messages) {
  st.shader = std::make_unique<glslang::TShader>(st.lang);
  const char* text = st.src.text.c_str();
  const int length = static_cast<int>(st.src.text.size());
  st.shader->setStringsWithLengths(&text, &length, 1);
  st.shader->setEnvInput(glslang::EShSourceGlsl, st.lang, glslang::EShClientNone, 0);
  st.shader->setEnvClient(glslang::EShClientOpenGL, glslang::EShTargetOpenGL_450);
  st.shader->setEnvTarget(glslang::EShTargetNone, glslang::EShTargetSpv_1_0);
  const bool ok = st.shader->parse(GetDefaultResources(), 450, ECoreProfile, false, false, EShMsgDefault);
  std::vector<ShaderMessage> parsed = parseShaderLog(st.shader->getInfoLog(), st.src);
  if (!ok && std::none_of(parsed.begin(), parsed.end(), [](const ShaderMessage& m) { return m.severity == Severity::error; })) {
    ShaderMessage m;
    m.file = st.src.files.empty() ? st.file : st.src.files[0];
    m.text = std::string(stageName(st.lang)) + " shader failed to compile";
    parsed.push_back(std::move(m));
  }
  for (auto& m : parsed) messages.push_back(std::move(m));
  return ok;
}

// Loads a stage's source; a missing file or include becomes an error message.
bool loadStage(Stage& st, const ShaderProgramSpec& spec, const std::vector<std::string>& dirs,
               std::vector<ShaderMessage>& messages) {
  ShaderMessage m;
  try {
    st.src = loadShaderSource(st.file, spec.defines, dirs);
    st.loaded = true;
    return true;
  } catch (const ShaderSourceError& e) {
    m.file = e.file();
    m.line = e.line();
    m.text = e.message();
  } catch (const std::exception& e) {
    m.text = e.what();  // the file itself is missing: no file to point at (reported at the pass)
  }
  messages.push_back(std::move(m));
  return false;
}

FragmentOutput::Kind outputKind(glslang::TBasicType t) {
  switch (t) {
    case glslang::EbtInt:
    case glslang::EbtInt8:
    case glslang::EbtInt16:
    case glslang::EbtInt64: return FragmentOutput::Kind::signed_int;
    case glslang::EbtUint:
    case glslang::EbtUint8:
    case glslang::EbtUint16:
    case glslang::EbtUint64: return FragmentOutput::Kind::unsigned_int;
    default: return FragmentOutput::Kind::floating;
  }
}

std::string baseName(const std::string& reflected) {
  size_t b = reflected.find('[');
  return b == std::string::npos ? reflected : reflected.substr(0, b);
}

// Every sampler a stage declares (used or not), from its linker objects,
// located in the original file through the stage's line table.
void collectDeclaredSamplers(const glslang::TIntermediate* interm, const ShaderSource& src,
                             std::vector<SamplerUniform>& out) {
  if (!interm || !interm->getTreeRoot()) return;
  glslang::TIntermAggregate* root = interm->getTreeRoot()->getAsAggregate();
  if (!root) return;
  for (TIntermNode* node : root->getSequence()) {
    glslang::TIntermAggregate* agg = node ? node->getAsAggregate() : nullptr;
    if (!agg || agg->getOp() != glslang::EOpLinkerObjects) continue;
    for (TIntermNode* obj : agg->getSequence()) {
      glslang::TIntermSymbol* sym = obj ? obj->getAsSymbolNode() : nullptr;
      if (!sym) continue;
      const glslang::TType& type = sym->getType();
      if (type.getQualifier().storage != glslang::EvqUniform || type.getBasicType() != glslang::EbtSampler) continue;
      const glslang::TSampler& s = type.getSampler();
      if (!s.isTexture()) continue;  // images and pure samplers are not sampled slots
      std::string name(sym->getName().c_str());
      if (name.empty() || name.rfind("gl_", 0) == 0) continue;
      if (std::any_of(out.begin(), out.end(), [&](const SamplerUniform& u) { return u.name == name; })) continue;
      SamplerUniform u;
      u.name = name;
      u.binding = type.getQualifier().hasBinding() ? static_cast<int>(type.getQualifier().layoutBinding) : -1;
      u.multisample = s.isMultiSample();
      u.shadow = s.isShadow();
      u.integer = s.getBasicType() == glslang::EbtInt || s.getBasicType() == glslang::EbtUint;
      u.dim = s.dim == glslang::Esd2D ? SamplerUniform::Dim::d2
              : s.dim == glslang::EsdCube ? SamplerUniform::Dim::cube
                                          : SamplerUniform::Dim::other;
      u.arrayed = s.isArrayed();
      u.type = s.getString().c_str();
      int line = sym->getLoc().line;  // of the expanded text: no #line directives
      // Linker objects often carry no location: the first expanded line that
      // declares a sampler of this name.
      for (size_t pos = 0, n = 1; line <= 0 && pos < src.text.size(); ++n) {
        const size_t end = std::min(src.text.find('\n', pos), src.text.size());
        const std::string_view l(src.text.data() + pos, end - pos);
        const size_t at = l.find(name);
        const bool declares =
            l.find("uniform") != std::string_view::npos && l.find("sampler") != std::string_view::npos;
        if (declares && at != std::string_view::npos &&
            (at + name.size() == l.size() || !std::isalnum(static_cast<unsigned char>(l[at + name.size()]))))
          line = static_cast<int>(n);
        pos = end + 1;
      }
      if (line > 0 && static_cast<size_t>(line) <= src.lines.size()) {
        const auto [file, fileLine] = src.lines[static_cast<size_t>(line) - 1];
        if (file >= 0 && static_cast<size_t>(file) < src.files.size()) {
          u.file = src.files[static_cast<size_t>(file)];
          u.line = fileLine;
        }
      }
      out.push_back(std::move(u));
    }
  }
}

std::string cacheKey(const ShaderProgramSpec& spec) {
  std::string key = spec.vert + '\x1f' + spec.frag + '\x1f' + spec.comp + '\x1e';
  for (const auto& d : spec.defines) key += d + '\x1f';
  return key;
}

std::string componentLetters(uint32_t from, uint32_t to) {  // 0-based [from, to)
  static const char* names[] = {"r", "g", "b", "a"};
  std::vector<std::string> v;
  for (uint32_t i = from; i < to && i < 4; ++i) v.push_back(names[i]);
  return join(v, ", ");
}

std::string glslTypeName(const FragmentOutput& o) {
  const char* prefix = o.kind == FragmentOutput::Kind::signed_int ? "i" : o.kind == FragmentOutput::Kind::unsigned_int ? "u" : "";
  if (o.components == 1) return o.kind == FragmentOutput::Kind::signed_int ? "int"
                              : o.kind == FragmentOutput::Kind::unsigned_int ? "uint" : "float";
  return std::string(prefix) + "vec" + std::to_string(o.components);
}

}  // namespace

const SamplerUniform* ProgramCheck::findSampler(const std::string& name) const {
  for (const auto& s : samplers)
    if (s.name == name) return &s;
  return nullptr;
}

const UniformBlock* ProgramCheck::findUniformBlock(const std::string& name) const {
  for (const auto& b : uniformBlocks)
    if (b.name == name) return &b;
  return nullptr;
}

const UniformBlockMember* UniformBlock::findMember(const std::string& member) const {
  for (const auto& m : members)
    if (m.name == member) return &m;
  return nullptr;
}

ShaderChecker::ShaderChecker(std::vector<std::string> searchDirectories) : dirs_(std::move(searchDirectories)) {}
ShaderChecker::~ShaderChecker() = default;

const ProgramCheck& ShaderChecker::program(const ShaderProgramSpec& spec) {
  const std::string key = cacheKey(spec);
  if (auto it = cache_.find(key); it != cache_.end()) {
    ++stats_.cacheHits;
    return *it->second;
  }
  const auto start = std::chrono::steady_clock::now();
  initGlslang();
  auto result = std::make_unique<ProgramCheck>();
  ProgramCheck& pc = *result;
  pc.spec = spec;

  // Stages are declared before the program: a TProgram must be destroyed
  // before the shaders linked into it.
  std::vector<Stage> stages;
  if (!spec.comp.empty()) stages.push_back(Stage{EShLangCompute, spec.comp, {}, false, nullptr});
  if (!spec.vert.empty()) stages.push_back(Stage{EShLangVertex, spec.vert, {}, false, nullptr});
  if (!spec.frag.empty()) stages.push_back(Stage{EShLangFragment, spec.frag, {}, false, nullptr});
  if (stages.empty()) {
    pc.messages.push_back(ShaderMessage{Severity::error, "", 0, "the program names no shader file"});
  }
  bool ok = !stages.empty();
  for (auto& st : stages) {
    if (!loadStage(st, spec, dirs_, pc.messages)) {
      ok = false;
      pc.files.push_back(st.file);
      continue;
    }
    pc.files.push_back(st.src.files[0]);
    if (!compileStage(st, pc.messages)) ok = false;
  }
  if (ok) {
    glslang::TProgram program;
    for (auto& st : stages) program.addShader(st.shader.get());
    if (!program.link(EShMsgDefault)) {
      ok = false;
      const Stage& last = stages.back();
      std::vector<ShaderMessage> linkMessages = parseShaderLog(program.getInfoLog(), last.src);
      if (linkMessages.empty()) linkMessages.push_back(ShaderMessage{Severity::error, last.src.files[0], 0, "program failed to link"});
      for (auto& m : linkMessages) {
        m.text = "link: " + m.text;
        pc.messages.push_back(std::move(m));
      }
    } else if (program.buildReflection(EShReflectionAllIOVariables | EShReflectionAllBlockVariables)) {
      if (!spec.frag.empty()) {
        for (int i = 0; i < program.getNumPipeOutputs(); ++i) {
          const glslang::TObjectReflection& r = program.getPipeOutput(i);
          const glslang::TType* t = r.getType();
          if (!t || r.name.rfind("gl_", 0) == 0) continue;
          if (t->getQualifier().builtIn != glslang::EbvNone) continue;
          FragmentOutput o;
          o.name = baseName(r.name);
          o.location = t->getQualifier().hasLocation() ? static_cast<int>(t->getQualifier().layoutLocation) : -1;
          o.arraySize = t->isArray() ? std::max(1, t->getOuterArraySize()) : 0;
          o.components = std::clamp(t->getVectorSize(), 1, 4);
          o.kind = outputKind(t->getBasicType());
          pc.outputs.push_back(std::move(o));
        }
        std::sort(pc.outputs.begin(), pc.outputs.end(),
                  [](const FragmentOutput& a, const FragmentOutput& b) { return a.location < b.location; });
      }
      for (auto& st : stages) collectDeclaredSamplers(program.getIntermediate(st.lang), st.src, pc.samplers);
      for (int i = 0; i < program.getNumUniformVariables(); ++i) {
        const std::string name = baseName(program.getUniform(i).name);
        for (auto& s : pc.samplers)
          if (s.name == name) s.active = true;
      }
      pc.uniformBlocks = shadercheck_detail::reflectUniformBlocks(program);
    }
  }
  pc.ok = ok;
  ++stats_.programsCompiled;
  stats_.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return *cache_.emplace(key, std::move(result)).first->second;
}

namespace {

// What checkPass finds in one pass instance, in the order found. Variants of
// one pass often repeat the same finding: it is kept once.
class PassFindings {
 public:
  PassFindings(const std::string& passName, const PassTypeDesc& type, const SourceLocation& passWhere)
      : who("pass '" + passName + "' (" + type.name + ")"), passWhere(passWhere), passName_(passName) {}

  void add(Severity sev, std::string message, SourceLocation where, std::string slot = {}, std::string resource = {}) {
    Diagnostic d;
    d.code = DiagCode::shader_error;
    d.severity = sev;
    d.message = std::move(message);
    d.pass = passName_;
    d.slot = std::move(slot);
    d.resource = std::move(resource);
    d.where = std::move(where);
    std::string key = formatDiagnostic(d);
    if (seen_.insert(key).second) out_.push_back(std::move(d));
  }

  // The compiler's messages about a program, at their shader lines.
  void reportMessages(const ProgramCheck& pc) {
    std::string context;
    if (pc.files.size() > 1 || !pc.spec.defines.empty()) {
      context = " [" + join(pc.files, " + ");
      if (!pc.spec.defines.empty()) context += " with " + join(pc.spec.defines, " ");
      context += "]";
    }
    for (const auto& m : pc.messages) {
      if (m.file.empty()) {  // nothing in a shader to point at: the pass in the config
        add(m.severity, who + ": " + m.text + context, passWhere);
        continue;
      }
      SourceLocation where;
      where.file = m.file;
      where.line = m.line;
      add(m.severity, m.text + context, where);
    }
  }

  Diagnostics take() { return std::move(out_); }

  const std::string who;  // "pass 'NAME' (TYPE)": how messages name the pass
  const SourceLocation& passWhere;

 private:
  std::string passName_;
  Diagnostics out_;
  std::set<std::string> seen_;
};

// The pass's bindings as the executor uses them: colour attachments in
// slot-declaration order at locations 0..N-1 (as the executor builds the
// pass's framebuffer); sampled inputs by slot.
struct PassBindings {
  std::vector<const BoundSlot*> attachments;
  std::map<std::string, const BoundSlot*> sampled;
};

PassBindings passBindings(const PassTypeDesc& type, const std::vector<BoundSlot>& bound) {
  auto slotIndex = [&](const std::string& slot) {
    for (size_t i = 0; i < type.slots.size(); ++i)
      if (type.slots[i].name == slot) return i;
    return type.slots.size();
  };
  PassBindings out;
  for (const auto& b : bound) {
    if (b.access == Access::color_attachment) out.attachments.push_back(&b);
    if (b.access == Access::sampled) out.sampled.emplace(b.slot, &b);
  }
  std::stable_sort(out.attachments.begin(), out.attachments.end(),
                   [&](const BoundSlot* a, const BoundSlot* b) { return slotIndex(a->slot) < slotIndex(b->slot); });
  return out;
}

// A program's fragment outputs, one per location (arrays unrolled), and
// whether their locations are known.
struct LocatedOutputs {
  std::vector<FragmentOutput> outs;
  bool locationsKnown = true;
};

LocatedOutputs locateOutputs(const ProgramCheck& pc, const std::string& shader, PassFindings& f) {
  LocatedOutputs located;
  std::vector<FragmentOutput>& outs = located.outs;
  size_t unlocated = 0;
  for (const auto& o : pc.outputs) unlocated += o.location < 0 ? 1 : 0;
  if (unlocated > 0 && pc.outputs.size() == 1 && pc.outputs[0].arraySize == 0) {
    outs.push_back(pc.outputs[0]);
    outs.back().location = 0;  // a single output without a location goes to location 0
  } else if (unlocated > 0) {
    located.locationsKnown = false;
    f.add(Severity::warning,
          f.who + ": " + shader + " declares " + std::to_string(pc.outputs.size()) +
              " colour outputs, some without layout(location): their locations are the linker's choice; give "
              "each output a location matching the pass's colour attachments",
          f.passWhere);
  } else {
    for (const auto& o : pc.outputs) {
      const int n = o.arraySize > 0 ? o.arraySize : 1;
      for (int i = 0; i < n; ++i) {
        FragmentOutput e = o;
        e.location = o.location + i;
        e.arraySize = 0;
        if (o.arraySize > 0) e.name = o.name + "[" + std::to_string(i) + "]";
        outs.push_back(std::move(e));
      }
    }
  }
  return located;
}

// Fragment outputs vs colour attachments: every output lands in an
// attachment and every attachment is written.
void checkOutputsMatchAttachments(const ProgramCheck& pc, const LocatedOutputs& located,
                                  const std::vector<const BoundSlot*>& attachments, const std::string& shader,
                                  PassFindings& f) {
  const std::vector<FragmentOutput>& outs = located.outs;
  auto outputList = [&] {
    std::vector<std::string> v;
    for (const auto& o : outs) v.push_back("'" + o.name + "' at " + std::to_string(o.location));
    return v.empty() ? std::string("none") : join(v, ", ");
  };
  auto attachmentList = [&] {
    std::vector<std::string> v;
    for (size_t i = 0; i < attachments.size(); ++i)
      v.push_back("'" + attachments[i]->slot + "' (" + attachments[i]->resource + ") at " + std::to_string(i));
    return v.empty() ? std::string("none") : join(v, ", ");
  };
  const size_t outputCount = located.locationsKnown ? outs.size() : pc.outputs.size();
  if (located.locationsKnown) {
    std::vector<std::string> problems;
    for (const auto& o : outs)
      if (o.location < 0 || static_cast<size_t>(o.location) >= attachments.size())
        problems.push_back("output '" + o.name + "' (location " + std::to_string(o.location) +
                           ") has no colour attachment: its values are discarded");
    for (size_t i = 0; i < attachments.size(); ++i)
      if (std::none_of(outs.begin(), outs.end(),
                       [&](const FragmentOutput& o) { return o.location == static_cast<int>(i); }))
        problems.push_back("colour attachment '" + attachments[i]->slot + "' (location " + std::to_string(i) +
                           ") is written by no output: its contents would be undefined");
    if (!problems.empty())
      f.add(Severity::error,
            f.who + ": fragment shader " + shader + " writes " + std::to_string(outputCount) + " colour output" +
                (outputCount == 1 ? "" : "s") + " (" + outputList() + ") but the pass binds " +
                std::to_string(attachments.size()) + " colour attachment" + (attachments.size() == 1 ? "" : "s") +
                " (" + attachmentList() + "): " + join(problems, "; "),
            f.passWhere);
  } else if (outputCount != attachments.size()) {
    f.add(Severity::error,
          f.who + ": fragment shader " + shader + " writes " + std::to_string(outputCount) +
              " colour outputs but the pass binds " + std::to_string(attachments.size()) + " colour attachments (" +
              attachmentList() + ")",
          f.passWhere);
  }
}

// Per attachment: the output's type and components against the format
// (blending with a source alpha the shader leaves undefined is an error).
void checkOutputFormats(const ShaderProgramSpec& spec, const std::vector<FragmentOutput>& outs,
                        const std::vector<const BoundSlot*>& attachments, const std::string& shader, PassFindings& f) {
  for (size_t i = 0; i < attachments.size(); ++i) {
    const BoundSlot& a = *attachments[i];
    auto it = std::find_if(outs.begin(), outs.end(),
                           [&](const FragmentOutput& o) { return o.location == static_cast<int>(i); });
    if (it == outs.end() || !a.format) continue;
    const FormatInfo& fi = formatInfo(*a.format);
    if (fi.isDepth) continue;  // the graph reports a depth format bound as a colour attachment
    const std::string target = "colour attachment '" + a.slot + "' (" + a.resource + ", " + std::string(fi.name) +
                               ", " + std::to_string(fi.components) + " component" + (fi.components == 1 ? "" : "s") +
                               ")";
    const SourceLocation& where = a.where.known() ? a.where : f.passWhere;
    // Integer formats (rg32ui) take unsigned outputs, float and normalized ones float outputs: GL
    // leaves any other pairing undefined.
    const bool unsignedOut = it->kind == FragmentOutput::Kind::unsigned_int;
    if (fi.isInteger ? !unsignedOut : it->kind != FragmentOutput::Kind::floating) {
      f.add(Severity::error,
            f.who + ": fragment shader " + shader + " writes " + glslTypeName(*it) + " '" + it->name + "' into " +
                target +
                (fi.isInteger ? ": only unsigned integer outputs (uint, uvec2...) are defined in an unsigned integer "
                                "format"
                              : ": integer outputs into a float or normalized format are undefined"),
            where, a.slot, a.resource);
      continue;
    }
    const uint32_t comps = static_cast<uint32_t>(it->components);
    if (comps > fi.components) {
      f.add(Severity::warning,
            f.who + ": fragment shader " + shader + " writes " + glslTypeName(*it) + " '" + it->name + "' into " +
                target + ": components " + componentLetters(fi.components, comps) +
                " are dropped (is the format right?)",
            where, a.slot, a.resource);
    } else if (comps < fi.components) {
      const bool alphaMissing = fi.components == 4 && comps < 4;
      const bool error = spec.blendsSourceAlpha && alphaMissing;
      f.add(error ? Severity::error : Severity::warning,
            f.who + ": fragment shader " + shader + " writes " + glslTypeName(*it) + " '" + it->name + "' into " +
                target + ": components " + componentLetters(comps, fi.components) + " are left undefined" +
                (error ? ", and the pass blends with source alpha" : ""),
            where, a.slot, a.resource);
    }
  }
}

// Samplers the spec maps to sampled slots: given a unit, bound when read, on
// the unit the spec names, and of a kind the bound texture can be sampled with.
void checkMappedSamplers(const ProgramCheck& pc, const ShaderProgramSpec& spec,
                         const std::map<std::string, const BoundSlot*>& sampled, const std::string& shader,
                         PassFindings& f) {
  for (const auto& m : spec.samplers) {
    if (m.unit < 0) {
      f.add(Severity::error,
            f.who + ": sampler '" + m.uniform + "' (input '" + m.slot + "') names no texture unit: give every " +
                "sampler of a ShaderProgramSpec its unit (SamplerSlot::unit)",
            f.passWhere, m.slot);
      continue;
    }
    const SamplerUniform* s = pc.findSampler(m.uniform);
    auto bit = sampled.find(m.slot);
    const BoundSlot* b = bit == sampled.end() ? nullptr : bit->second;
    if (!s) {
      if (b)
        f.add(Severity::warning,
              f.who + ": input '" + m.slot + "' is bound (" + b->resource + ") but " + join(pc.files, " + ") +
                  " declares no sampler '" + m.uniform + "' to read it: the binding is unused",
              b->where.known() ? b->where : f.passWhere, m.slot, b->resource);
      continue;
    }
    if (!s->active) continue;  // declared, not read with these defines: binding it or not makes no difference
    if (!b) {
      if (m.optional) continue;  // the pass tells the shader the slot is unbound
      f.add(Severity::error,
            f.who + ": " + shader + " samples '" + m.uniform + "' (input '" + m.slot + "') but the config binds no " +
                "resource to '" + m.slot + "': it would read texture 0 (bind the input)",
            f.passWhere, m.slot);
      continue;
    }
    const SourceLocation& where = b->where.known() ? b->where : f.passWhere;
    // Without layout(binding) the shader reads the unit the executor sets
    // the sampler uniform to; an explicit binding must agree with it.
    if (s->binding >= 0 && s->binding != m.unit)
      f.add(Severity::error,
            f.who + ": sampler '" + m.uniform + "' in " + shader + " reads texture unit " + std::to_string(s->binding) +
                " (layout(binding = " + std::to_string(s->binding) + ")) but the pass binds input '" + m.slot +
                "' to unit " + std::to_string(m.unit),
            where, m.slot, b->resource);
    if (s->integer)
      f.add(Severity::error,
            f.who + ": sampler '" + m.uniform + "' in " + shader + " is an integer sampler but input '" + m.slot +
                "' (" + b->resource + (b->format ? ", " + std::string(formatName(*b->format)) : std::string()) +
                ") is a float or normalized texture: the results are undefined",
            where, m.slot, b->resource);
    if (s->multisample != (b->samples > 1))
      f.add(Severity::error,
            f.who + ": sampler '" + m.uniform + "' in " + shader + " is " +
                (s->multisample ? "a multisample sampler" : "not a multisample sampler") + " but input '" + m.slot +
                "' (" + b->resource + ") has " + std::to_string(b->samples) + " sample" + (b->samples == 1 ? "" : "s"),
            where, m.slot, b->resource);
    if (s->shadow && b->format && !isDepthFormat(*b->format))
      f.add(Severity::error,
            f.who + ": sampler '" + m.uniform + "' in " + shader + " is a shadow sampler but input '" + m.slot + "' (" +
                b->resource + ", " + std::string(formatName(*b->format)) + ") has no depth",
            where, m.slot, b->resource);
    for (std::string& problem : samplerShapeProblems(*s, m, *b, shader))
      f.add(Severity::error, f.who + ": " + problem, where, m.slot, b->resource);
  }
}

// Active samplers no slot maps and the pass does not bind itself: they read
// whatever texture is on their unit.
void checkUnmappedSamplers(const ProgramCheck& pc, const ShaderProgramSpec& spec, const std::string& shader,
                           PassFindings& f) {
  std::set<std::string> mapped;
  for (const auto& m : spec.samplers) mapped.insert(m.uniform);
  for (const auto& s : pc.samplers) {
    if (!s.active || mapped.count(s.name)) continue;
    if (std::find(spec.ownSamplers.begin(), spec.ownSamplers.end(), s.name) != spec.ownSamplers.end()) continue;
    std::vector<std::string> known;
    for (const auto& m : spec.samplers) known.push_back(m.uniform + " <- " + m.slot);
    f.add(Severity::warning,
          f.who + ": sampler '" + s.name + "' in " + shader + " is bound to no input of the pass (it reads whatever " +
              "texture is on unit " + std::to_string(s.binding < 0 ? 0 : s.binding) + ")" +
              (known.empty() ? std::string() : "; the pass binds " + join(known, ", ")),
          f.passWhere);
  }
}

}  // namespace

// One function per check above; this one only walks the pass's programs.
Diagnostics ShaderChecker::checkPass(const std::string& passName, const PassTypeDesc& type, const ParamSet& params,
                                     const std::vector<BoundSlot>& bound, const SourceLocation& passWhere) {
  PassFindings f(passName, type, passWhere);
  if (!type.programs) return f.take();  // a pass type without programs uses no shaders

  std::vector<ShaderProgramSpec> specs;
  try {
    specs = type.programs(params);
  } catch (const std::exception& e) {
    f.add(Severity::error, f.who + ": " + e.what(), passWhere);
    return f.take();
  }

  const PassBindings bindings = passBindings(type, bound);
  for (const auto& spec : specs) {
    const ProgramCheck& pc = program(spec);
    checked_.push_back({passName, spec});
    f.reportMessages(pc);
    if (!pc.ok) continue;
    if (drawsScene(spec)) {
      // The variant a deforming scene runs (rgraph/scene_program.h): the
      // same fragment shader, so only the compiler's messages can differ.
      ShaderProgramSpec animated = spec;
      animated.defines.push_back(kSceneAnimationDefine);
      f.reportMessages(program(animated));
      checked_.push_back({passName, std::move(animated)});
    }
    const std::string shader = pc.files.empty() ? spec.frag : pc.files.back();
    if (!spec.frag.empty() && spec.drawsToAttachments) {
      const LocatedOutputs located = locateOutputs(pc, shader, f);
      checkOutputsMatchAttachments(pc, located, bindings.attachments, shader, f);
      if (located.locationsKnown) checkOutputFormats(spec, located.outs, bindings.attachments, shader, f);
    }
    if (spec.checkSamplers) {
      checkMappedSamplers(pc, spec, bindings.sampled, shader, f);
      checkUnmappedSamplers(pc, spec, shader, f);
    }
  }
  return f.take();
}

Diagnostics ShaderChecker::checkPipeline(const PipelineConfig& pipeline, const Plan& plan,
                                         const PassRegistry& registry) {
  Diagnostics out;
  const GraphDesc& g = pipeline.graph;
  for (size_t p = 0; p < g.passes.size(); ++p) {
    const PassDecl& pd = g.passes[p];
    if (!pd.enabled) continue;
    const PassTypeDesc* type = registry.find(pd.type);
    if (!type) continue;
    ParamSet params = defaultParams(type->params);
    if (p < pipeline.params.size())
      for (const auto& [k, v] : pipeline.params[p].values()) params.set(k, v);

    const std::vector<BoundUse>* uses = p < plan.bindings.size() ? &plan.bindings[p] : nullptr;
    std::vector<BoundSlot> bound;
    for (size_t u = 0; u < pd.uses.size(); ++u) {
      const ResourceUse& ru = pd.uses[u];
      BoundSlot b;
      b.slot = ru.slot;
      b.access = ru.access;
      const bool write = isWriteAccess(ru.access);
      b.resource = write ? ru.output : ru.input;
      b.where = write ? ru.outputWhere : ru.inputWhere;
      const BoundUse* bu = nullptr;
      if (uses && u < uses->size() && (*uses)[u].slot == ru.slot) bu = &(*uses)[u];
      if (uses && !bu)
        for (const auto& x : *uses)
          if (x.slot == ru.slot) bu = &x;
      if (bu && bu->resource.valid()) {
        const ResourceDecl& rd = g.resources[bu->resource.value()];
        if (rd.kind == ResourceKind::texture) {
          b.format = rd.texture.format;
          b.samples = std::max<uint32_t>(1, rd.texture.samples);
          b.layers = rd.texture.layers;
          b.cube = rd.texture.cube;
          b.sub = ru.sub;
        }
      }
      if (const SlotDecl* sd = type->findSlot(ru.slot); sd && ru.access == Access::sampled)
        b.sampler = slotSamplerState(pipeline, p, *sd, &b.samplerWhere);
      bound.push_back(std::move(b));
    }
    Diagnostics d = checkPass(pd.name, *type, params, bound, pd.where);
    out.insert(out.end(), std::make_move_iterator(d.begin()), std::make_move_iterator(d.end()));
  }
  return out;
}

}  // namespace rgraph
