#include "rgraph/gl/shader_library.h"

#include <GL/glcorearb.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "rgraph/error.h"
#include "rgraph/shader_check.h"

namespace rgraph {
namespace {

const char* stageName(unsigned stage) {
  switch (stage) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_COMPUTE_SHADER: return "compute";
    case GL_GEOMETRY_SHADER: return "geometry";
    default: return "shader";
  }
}

std::string programLog(GLuint program) {
  GLint len = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &len);
  std::string log(static_cast<size_t>(std::max(len, 1)), '\0');
  glGetProgramInfoLog(program, len, nullptr, log.data());
  log.resize(std::strlen(log.c_str()));
  while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
  return log;
}

std::string shaderLog(GLuint shader) {
  GLint len = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &len);
  std::string log(static_cast<size_t>(std::max(len, 1)), '\0');
  glGetShaderInfoLog(shader, len, nullptr, log.data());
  log.resize(std::strlen(log.c_str()));
  return log;
}

}  // namespace

ShaderLibrary::ShaderLibrary() = default;
ShaderLibrary::~ShaderLibrary() = default;

void ShaderLibrary::addSearchDirectory(const std::string& dir) { extraDirs_.insert(extraDirs_.begin(), dir); }

std::vector<std::string> ShaderLibrary::searchDirectories() const {
  std::vector<std::string> dirs = extraDirs_;
  for (auto& d : defaultShaderSearchDirectories()) dirs.push_back(std::move(d));
  return dirs;
}

std::string ShaderLibrary::find(const std::string& file) const { return findShaderFile(file, searchDirectories()); }

std::string ShaderLibrary::resolve(const std::string& file) const {
  return resolveShaderFile(file, searchDirectories());
}

ShaderLibrary::Source ShaderLibrary::load(const std::string& file, const std::vector<std::string>& defines) const {
  // The expansion itself is GL-free and shared with the glslang checker
  // (rgraph/shader_check.h), so validate checks what the driver compiles.
  ShaderSource loaded = loadShaderSource(file, defines, searchDirectories());
  Source src;
  src.text = std::move(loaded.text);
  src.files = std::move(loaded.files);
  src.lines = std::move(loaded.lines);
  return src;
}

std::string ShaderLibrary::preprocess(const std::string& file, const std::vector<std::string>& defines) const {
  return load(file, defines).text;
}

gl::Shader ShaderLibrary::compileStage(unsigned stage, const std::string& file, const std::vector<std::string>& defines,
                                       std::vector<WatchedFile>& read) const {
  ShaderSource src;
  try {
    src = loadShaderSource(file, defines, searchDirectories());
  } catch (const ShaderSourceError& e) {
    throw LocatedError(e.what());  // already FILE:LINE: error: ...
  }
  for (const auto& path : src.resolvedFiles) read.push_back(WatchedFile::now(path));
  for (const auto& path : src.shadowPaths) read.push_back(WatchedFile::now(path));
  gl::Shader shader = gl::createShader(stage);
  const char* text = src.text.c_str();
  glShaderSource(shader.id(), 1, &text, nullptr);
  glCompileShader(shader.id());
  GLint ok = 0;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  std::string log = shaderLog(shader.id());
  if (!ok) {
    // The clean form `validate` prints (one line per line with an error);
    // the driver's own log, which can run to dozens of lines (Mesa lists
    // every overload of a builtin), only at debug level.
    spdlog::debug("{} ({} shader): the driver's compile log:\n{}", src.files[0], stageName(stage),
                  mapShaderLog(log, src));
    std::string summary = shaderErrorSummary(parseShaderLog(log, src));
    if (summary.empty()) summary = src.files[0] + ": error: " + stageName(stage) + " shader failed to compile";
    throw LocatedError(summary + "\n  (the driver refused this " + stageName(stage) +
                       " shader; its full log is logged at debug level: rgraph --log-level debug)");
  }
  if (!log.empty()) spdlog::debug("{} ({} shader): {}", src.files[0], stageName(stage), mapShaderLog(log, src));
  return shader;
}

uint32_t ShaderLibrary::link(const std::string& key, std::vector<gl::Shader> stages, std::vector<WatchedFile> read,
                             const std::string& what) {
  gl::Program program = gl::createProgram();
  for (const auto& s : stages) glAttachShader(program.id(), s.id());
  glLinkProgram(program.id());
  for (const auto& s : stages) glDetachShader(program.id(), s.id());
  GLint ok = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok) throw RuntimeError(what + ": error: program failed to link: " + programLog(program.id()));
  uint32_t id = program.id();
  programs_[key] = Cached{std::move(program), std::move(read)};
  return id;
}

namespace {
std::string cacheKey(const std::vector<std::string>& files, const std::vector<std::string>& defines) {
  std::string key;
  for (const auto& f : files) key += f + '\x1f';
  key += '\x1e';
  for (const auto& d : defines) key += d + '\x1f';
  return key;
}
}  // namespace

uint32_t ShaderLibrary::program(const std::string& vert, const std::string& frag,
                                const std::vector<std::string>& defines) {
  if (log_) log_->push_back({vert, frag, {}, defines});
  std::string key = cacheKey({vert, frag}, defines);
  if (auto it = programs_.find(key); it != programs_.end()) return it->second.program.id();
  std::vector<gl::Shader> stages;
  std::vector<WatchedFile> read;
  stages.push_back(compileStage(GL_VERTEX_SHADER, vert, defines, read));
  stages.push_back(compileStage(GL_FRAGMENT_SHADER, frag, defines, read));
  return link(key, std::move(stages), std::move(read),
              shaderDisplayPath(resolve(vert)) + " + " + shaderDisplayPath(resolve(frag)));
}

uint32_t ShaderLibrary::computeProgram(const std::string& comp, const std::vector<std::string>& defines) {
  if (log_) log_->push_back({{}, {}, comp, defines});
  std::string key = cacheKey({comp}, defines);
  if (auto it = programs_.find(key); it != programs_.end()) return it->second.program.id();
  std::vector<gl::Shader> stages;
  std::vector<WatchedFile> read;
  stages.push_back(compileStage(GL_COMPUTE_SHADER, comp, defines, read));
  return link(key, std::move(stages), std::move(read), shaderDisplayPath(resolve(comp)));
}

void ShaderLibrary::clear() { programs_.clear(); }

ShaderLibrary::WatchedFile ShaderLibrary::WatchedFile::now(const std::string& path) {
  std::error_code ec;
  const auto written = std::filesystem::last_write_time(path, ec);
  return {path, written, !ec};
}

bool ShaderLibrary::WatchedFile::changed() const {
  const WatchedFile current = now(path);
  return current.present != present || (present && current.written != written);
}

size_t ShaderLibrary::retireChanged() {
  size_t retired = 0;
  for (auto it = programs_.begin(); it != programs_.end();) {
    const bool changed =
        std::any_of(it->second.files.begin(), it->second.files.end(), [](const WatchedFile& f) { return f.changed(); });
    if (changed) {
      retired_.push_back(std::move(*it));
      it = programs_.erase(it);
      ++retired;
    } else {
      ++it;
    }
  }
  return retired;
}

void ShaderLibrary::releaseRetired() { retired_.clear(); }

void ShaderLibrary::restoreRetired() {
  // A program built since from the same key (the failed attempt's) gives way
  // to the one still in use.
  for (auto& [key, cached] : retired_) programs_[key] = std::move(cached);
  retired_.clear();
}

std::vector<std::string> ShaderLibrary::files() const {
  std::vector<std::string> all;
  for (const auto& [key, cached] : programs_)
    for (const auto& f : cached.files)
      if (std::find(all.begin(), all.end(), f.path) == all.end()) all.push_back(f.path);
  return all;
}

}  // namespace rgraph
