// Shader sources and shader checks without a GL context.
//
// 1. Shader sources: finding a shader file in the shader search directories,
//    expanding its #include lines and inserting defines, with a line table
//    that maps every expanded line back to its file and line. ShaderLibrary
//    (the GL backend) loads every shader through these functions, so what is
//    checked here is byte for byte what the driver compiles.
//
// 2. ShaderChecker: what `rgraph validate` runs after the graph compiles.
//    For every enabled pass it asks the pass type which programs it would
//    build for its params (PassTypeDesc::programs), compiles each stage with
//    glslang (GLSL 4.50 as an OpenGL driver sees it), links the program, and
//    reflects it against the config's bindings. Results are cached per
//    (files, defines) for the checker's lifetime.
//
//    Errors (Severity::error, DiagCode::shader_error):
//      - a shader file or an included file is missing; a nested #include;
//      - a compile or link error: located at the shader's FILE:LINE (the
//        included file's, for an error inside an include), with the pass;
//      - fragment outputs vs colour attachments: the pass's colour
//        attachments are its bound colour-attachment slots in slot
//        declaration order at locations 0..N-1 (as the executor builds the
//        framebuffer). An output at a location with no attachment (its values
//        are discarded) or an attachment no output writes (its contents are
//        undefined) is an error naming the pass, the shader and both lists;
//      - an int/uint output into a float or normalized format (undefined);
//      - an output with fewer components than its attachment's format when
//        the program blends with source alpha and alpha is among the missing
//        components (the blend itself is undefined, ShaderProgramSpec::
//        blendsSourceAlpha);
//      - a sampler the shader reads (active for the pass's defines) whose
//        slot the config leaves unbound: it would sample texture 0 (unless
//        the mapping is SamplerSlot::optional: the pass tells the shader);
//      - a sampler mapping without a texture unit (SamplerSlot::unit < 0);
//      - a sampler whose layout(binding) differs from the texture unit the
//        spec binds its slot to (without layout(binding), the executor sets
//        the sampler uniform to that unit); an integer sampler (isampler/usampler) on a
//        float/normalized texture; a multisample sampler on a single-sample
//        texture or the reverse; a shadow sampler on a colour texture;
//      - a sampler whose GLSL type does not fit the shape of what the slot
//        binds: sampler2D* reads a 2D texture or one layer or face of an
//        array or cube (a subresource with one layer), sampler2DArray* more
//        layers, samplerCube* a whole cube (6 faces), samplerCubeArray* a
//        cube array; 1D, 3D, rect and buffer samplers read no graph texture;
//      - a shadow sampler (sampler2DShadow, samplerCubeShadow, ...) on a slot
//        whose sampler state has no compare mode (SlotDecl::sampler, the
//        config's "samplers"), or a compare mode on a slot a non-shadow
//        sampler reads (GL leaves both undefined).
//      These name the sampler's declaration (shader FILE:LINE) in the message
//      and point at the slot's binding in the config.
//    Warnings:
//      - an output with more components than its attachment's format (the
//        extra components are dropped: legal, but usually a wrong format);
//      - an output with fewer components than the format (the missing
//        components are undefined; legal while nothing reads them, and which
//        later pass reads which channel is not known here), unless it is
//        the blending error above;
//      - a sampled slot bound in the config whose sampler the program never
//        declares (the binding does nothing);
//      - an active sampler that is neither mapped to a slot nor one the pass
//        binds itself (ShaderProgramSpec::ownSamplers): nothing binds it;
//      - several fragment outputs without layout(location) (their locations
//        are the linker's choice and cannot be checked);
//      - glslang's own warnings.
//    Pass types without `programs` use no shaders: nothing to check.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rgraph/diagnostics.h"
#include "rgraph/error.h"
#include "rgraph/format.h"
#include "rgraph/graph.h"
#include "rgraph/pass.h"

namespace rgraph {

struct PipelineConfig;
class PassRegistry;

// ------------------------------------------------------------ shader sources

// The default shader search directories, in order: $RGRAPH_SHADER_DIR
// (':'-separated), then rgraph's built-in shaders: <prefix>/share/rgraph/shaders
// found from librgraph's own location in an install, the source tree's
// shaders/ in a build tree (rgraph/own_files.h). (ShaderLibrary puts the
// directories added with addSearchDirectory in front of these.)
std::vector<std::string> defaultShaderSearchDirectories();
// Folders added for the whole process (thread-safe), seen by every later
// defaultShaderSearchDirectories(): `--shader-path` folders come before the
// defaults; a loaded plugin's own shader folder comes after them.
void addShaderSearchDirectory(const std::string& dir);
void addPluginShaderDirectory(const std::string& dir);

// Full path of a shader file: absolute paths as they are (they come from
// code: a plugin's or an application's pass type; a config cannot name one),
// relative ones in the first directory that has them. A relative name counts
// only inside one of `dirs` (symbolic links resolved: `..` and links that
// lead out of every folder are not found). "" when not found. A file named
// by its absolute path may include files beside it.
std::string findShaderFile(const std::string& file, const std::vector<std::string>& dirs);
// Like findShaderFile but throws RuntimeError listing the directories searched,
// or saying where a name that leads outside them resolves to.
std::string resolveShaderFile(const std::string& file, const std::vector<std::string>& dirs);

// A path as shown in messages: relative to the working directory when inside it.
std::string shaderDisplayPath(const std::string& path);

// Where a shader file came from, for messages. rgraph_add_plugin copies a
// plugin's shaders into <build>/share/rgraph/plugins/<name>/ and writes
// kShaderSourcesManifest there, one `COPY<TAB>SOURCE` line per shader (the
// copy's file name, the absolute path it was copied from). Messages about a
// copy name the source the author edits instead:
//   - the source exists with the copy's contents: `display` is the source
//     (shaderDisplayPath of it), `note` is empty;
//   - the source exists but differs (edited since the last build): `display`
//     is the copy and `note` says which source it is a copy of and to rebuild;
//   - no manifest, no line for the file, or the source is gone (a package
//     built elsewhere): `display` is the file itself.
// `text` is the file's contents (already read by the caller).
inline constexpr const char* kShaderSourcesManifest = "rgraph-shader-sources.txt";
struct ShaderOrigin {
  std::string display;
  std::string note;
};
ShaderOrigin shaderOrigin(const std::string& path, const std::string& text);

// A load failure with a location: a missing include or a nested #include.
// what() is `FILE:LINE: error: message`.
class ShaderSourceError : public RuntimeError {
 public:
  ShaderSourceError(std::string file, int line, std::string message);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_;
  int line_;
  std::string message_;
};

struct ShaderSource {
  std::string path;                        // the resolved file
  std::string text;                        // after #include expansion and defines
  std::vector<std::string> files;          // display paths (shaderOrigin): 0 the shader, then included files
  std::vector<std::string> resolvedFiles;  // the same files as found on disk (for watching them)
  // Where the shader would be found first if a file were there: its name in each folder searched before the one
  // it came from (missing now; an override created there, or restored after being deleted, would win). Watched too.
  std::vector<std::string> shadowPaths;
  std::vector<std::pair<int, int>> lines;  // expanded line - 1 -> (file index, line in that file)
  std::vector<std::string> notes;          // per file: ShaderOrigin::note ("" for most); last, for older plugins
};

// Loads a shader: `#include "file"` (or <file>) expanded one level deep
// (relative to the including file first, then the search directories),
// defines ("NAME" or "NAME=VALUE") inserted after the #version line
// (`#version 450 core` is added when there is none). No #line directives:
// compiler messages are mapped back through ShaderSource::lines.
// Throws RuntimeError (missing file) or ShaderSourceError (missing include,
// nested include).
ShaderSource loadShaderSource(const std::string& file, const std::vector<std::string>& defines,
                              const std::vector<std::string>& dirs);

// A compiler message mapped back to its file and line.
struct ShaderMessage {
  Severity severity = Severity::error;
  std::string file;  // display path; the shader itself when the compiler gave no line
  int line = 0;      // 0: no line
  std::string text;  // the compiler's message without its location prefix
};

// Parses a compiler log (glslang `ERROR: 0:12: ...`, Mesa `0:12(5): error: ...`,
// NVIDIA `0(12) : error C0000: ...`) into messages located in the original
// files. Lines that name no location are kept with line 0; glslang's
// "N compilation errors" summary is dropped. A message in a file with a note
// (a stale copy, see shaderOrigin) ends with that note in parentheses.
std::vector<ShaderMessage> parseShaderLog(const std::string& log, const ShaderSource& src);
// What `rgraph render` shows of a driver's compile log, the way `validate`
// shows glslang's: one `FILE:LINE: error: text` line per source line with an
// error (its first message: Mesa follows "no matching function ...;
// candidates are:" with one line per overload, which this drops along with
// the "; candidates are:" tail), at most `maxLines` lines. Warnings are left out.
std::string shaderErrorSummary(const std::vector<ShaderMessage>& messages, size_t maxLines = 8);
// The same log with locations rewritten to `FILE:LINE: ...` (what
// ShaderLibrary throws on a compile error).
std::string mapShaderLog(const std::string& log, const ShaderSource& src);

// ------------------------------------------------------------ reflection

struct FragmentOutput {
  std::string name;
  int location = -1;   // -1: no layout(location)
  int arraySize = 0;   // 0: not an array; an array takes locations location..location+arraySize-1
  int components = 4;  // 1..4
  enum class Kind { floating, signed_int, unsigned_int } kind = Kind::floating;
};

struct SamplerUniform {
  std::string name;
  int binding = -1;  // layout(binding), -1 when none (the unit is then 0 unless the pass sets it)
  bool active = false;  // read by the program (declared-only samplers are inactive)
  bool multisample = false;
  bool shadow = false;
  bool integer = false;  // isampler / usampler
  // The texture shape it reads: 2D (also 2D multisample), cube, or another
  // (1D, 3D, rect, buffer), and whether it is an array sampler.
  enum class Dim { d2, cube, other } dim = Dim::d2;
  bool arrayed = false;
  std::string type;  // the GLSL type, e.g. "sampler2DArrayShadow"
  std::string file;  // where it is declared (display path), "" when unknown
  int line = 0;
};

// A member of a uniform block as glslang lays it out (std140 for the blocks
// rgraph's shaders declare).
struct UniformBlockMember {
  std::string name;  // as declared ("u_view"; "Block.member" for a block with an instance name)
  int offset = -1;   // bytes from the start of the block
  std::string type;  // GLSL spelling: "mat4", "vec4", "ivec4", "float", "vec4[8]"...
};

// A uniform block the program uses, with every member (read or not).
struct UniformBlock {
  std::string name;  // the block name ("Frame")
  int binding = -1;  // layout(binding), -1 when none
  int size = 0;      // bytes
  std::vector<UniformBlockMember> members;  // in offset order
  const UniformBlockMember* findMember(const std::string& member) const;
};

// One program, compiled, linked and reflected.
struct ProgramCheck {
  ShaderProgramSpec spec;
  std::vector<std::string> files;  // display paths of its stages (vert, frag or comp)
  bool ok = false;                 // every stage compiled and the program linked
  std::vector<ShaderMessage> messages;  // errors and warnings, located
  std::vector<FragmentOutput> outputs;  // user fragment outputs (built-ins left out)
  std::vector<SamplerUniform> samplers; // every declared sampler, active or not
  std::vector<UniformBlock> uniformBlocks;  // the blocks the program uses (a block it never reads is left out)
  const SamplerUniform* findSampler(const std::string& name) const;
  const UniformBlock* findUniformBlock(const std::string& name) const;
};

// A slot of a pass instance as the config binds it.
struct BoundSlot {
  std::string slot;
  Access access = Access::sampled;
  std::string resource;           // the resource (or version) name, for messages
  std::optional<Format> format;   // unknown when the graph could not resolve it
  uint32_t samples = 1;
  // The texture's shape (TextureDesc::layers, ::cube) and the part the slot
  // binds: known with the format.
  uint32_t layers = 1;
  bool cube = false;
  Subresource sub;
  // The state the slot samples with (rgraph::slotSamplerState); nullopt: the
  // texture's own parameters (no compare). `samplerWhere`: the config's
  // override, when there is one.
  std::optional<SamplerState> sampler;
  SourceLocation samplerWhere;
  SourceLocation where;           // the binding in the config
};

struct CheckedProgram {
  std::string pass;
  ShaderProgramSpec spec;
};

struct ShaderCheckStats {
  size_t programsCompiled = 0;  // distinct (files, defines) compiled with glslang
  size_t cacheHits = 0;
  double seconds = 0.0;         // time spent compiling and reflecting
};

class ShaderChecker {
 public:
  // Shader files are looked up in these directories, in order (usually a
  // ShaderLibrary's searchDirectories(), which includes the directories
  // plugins add).
  explicit ShaderChecker(std::vector<std::string> searchDirectories = defaultShaderSearchDirectories());
  ~ShaderChecker();
  ShaderChecker(const ShaderChecker&) = delete;
  ShaderChecker& operator=(const ShaderChecker&) = delete;

  const std::vector<std::string>& searchDirectories() const { return dirs_; }

  // Every enabled pass of a pipeline (culled ones included). `plan` is the
  // compiled graph (for the formats of bound resources); pass types come
  // from `registry`. Passes whose type is unknown are skipped (the config
  // loader reported them).
  Diagnostics checkPipeline(const PipelineConfig& pipeline, const Plan& plan, const PassRegistry& registry);

  // One pass instance: name, type, params and how the config binds its slots.
  // `passWhere` locates the pass in the config (diagnostics about bindings
  // point there or at the binding).
  Diagnostics checkPass(const std::string& passName, const PassTypeDesc& type, const ParamSet& params,
                        const std::vector<BoundSlot>& bound, const SourceLocation& passWhere = {});

  // Compiles, links and reflects one program (cached by files + defines).
  // Never throws: load failures become error messages.
  const ProgramCheck& program(const ShaderProgramSpec& spec);

  const ShaderCheckStats& stats() const { return stats_; }
  // Every program checkPass checked, per pass, in order (a program two passes
  // share is listed for each): what the executor builds for the same passes
  // (Executor::builtPrograms).
  const std::vector<CheckedProgram>& checkedPrograms() const { return checked_; }

 private:
  std::vector<std::string> dirs_;
  std::vector<CheckedProgram> checked_;
  std::map<std::string, std::unique_ptr<ProgramCheck>> cache_;
  ShaderCheckStats stats_;
};

}  // namespace rgraph
