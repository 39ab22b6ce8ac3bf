// Loads GLSL files from the shader directories, compiles and links programs
// once (cached by files + defines). Compile and link errors throw
// rgraph::RuntimeError naming the file and line: `shaders/NAME.frag:LINE: message`.
//
// Search order for a relative name: directories added with addSearchDirectory
// (latest first), then defaultShaderSearchDirectories() (rgraph/shader_check.h:
// $RGRAPH_SHADER_DIR, rgraph's built-in shaders). Absolute paths are used as is.
//
// Sources may `#include "file"` (one level: included files may not include),
// resolved like any shader name (relative to the including file's directory first).
// Defines ("NAME" or "NAME=VALUE") are inserted after the #version line.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "rgraph/gl/objects.h"

namespace rgraph {

// One program()/computeProgram() call: the files and defines asked for.
struct ProgramRequest {
  std::string vert, frag;  // a vertex + fragment program
  std::string comp;        // or a compute program
  std::vector<std::string> defines;
  bool operator==(const ProgramRequest&) const = default;
};

class ShaderLibrary {
 public:
  ShaderLibrary();
  ~ShaderLibrary();
  ShaderLibrary(const ShaderLibrary&) = delete;
  ShaderLibrary& operator=(const ShaderLibrary&) = delete;

  // Vertex + fragment program. Needs a current GL context. Returns the GL program name.
  uint32_t program(const std::string& vert, const std::string& frag, const std::vector<std::string>& defines = {});
  // Compute program.
  uint32_t computeProgram(const std::string& comp, const std::vector<std::string>& defines = {});

  // Full path of a shader file; throws RuntimeError listing the directories searched.
  std::string resolve(const std::string& file) const;
  // Like resolve() but returns "" when not found.
  std::string find(const std::string& file) const;
  // Source after #include expansion and define insertion (what the driver
  // compiles; no #line directives: errors are mapped back through a line
  // table). Throws RuntimeError when a file is missing.
  std::string preprocess(const std::string& file, const std::vector<std::string>& defines = {}) const;

  void addSearchDirectory(const std::string& dir);  // searched before the defaults
  std::vector<std::string> searchDirectories() const;

  // While set, every program() and computeProgram() call (cached or not) is
  // appended to *log; nullptr stops. The executor reports with it what each
  // pass built (Executor::builtPrograms).
  void recordRequests(std::vector<ProgramRequest>* log) { log_ = log; }

  // Drops every cached program (e.g. to reload edited shaders). Needs the context current.
  void clear();
  // Reloading edited shaders, keeping what did not change: retireChanged()
  // takes the cached programs whose files (the shaders and what they include)
  // changed on disk since they were compiled, or are gone, or whose shader
  // now has an override in an earlier folder, out of the cache
  // (the next program() call compiles them again) but keeps them alive, since
  // passes still draw with them; releaseRetired() deletes them once nothing
  // uses them, restoreRetired() puts them back (the reload failed). Returns
  // how many were retired.
  size_t retireChanged();
  void releaseRetired();
  void restoreRetired();
  // Every file the cached programs were compiled from (resolved paths, once each), and where an
  // override of each shader would be (ShaderSource::shadowPaths; retireChanged() takes a program whose
  // override appeared there).
  std::vector<std::string> files() const;
  size_t cachedPrograms() const { return programs_.size(); }

 private:
  struct Source {
    std::string text;
    std::vector<std::string> files;  // 0: the shader itself, then included files (display paths)
    std::vector<std::pair<int, int>> lines;  // expanded line - 1 -> (file index, line in that file)
  };
  struct WatchedFile {
    std::string path;
    std::filesystem::file_time_type written;
    bool present = true;  // false: a shadow path (ShaderSource::shadowPaths), missing when compiled
    static WatchedFile now(const std::string& path);
    bool changed() const;  // appeared, disappeared or rewritten since
  };
  struct Cached {
    gl::Program program;
    std::vector<WatchedFile> files;  // what it was compiled from, as it was then
  };
  Source load(const std::string& file, const std::vector<std::string>& defines) const;
  gl::Shader compileStage(unsigned stage, const std::string& file, const std::vector<std::string>& defines,
                          std::vector<WatchedFile>& read) const;
  uint32_t link(const std::string& key, std::vector<gl::Shader> stages, std::vector<WatchedFile> read,
                const std::string& what);

  std::vector<std::string> extraDirs_;
  std::map<std::string, Cached> programs_;
  std::vector<std::pair<std::string, Cached>> retired_;
  std::vector<ProgramRequest>* log_ = nullptr;
};

}  // namespace rgraph
