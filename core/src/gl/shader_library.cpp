#include "rgraph/gl/shader_library.h"

#include <GL/glcorearb.h>
#include <spdlog/spdlog.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include "rgraph/error.h"

#ifndef RGRAPH_SHADER_SOURCE_DIR
#define RGRAPH_SHADER_SOURCE_DIR ""
#endif
#ifndef RGRAPH_SHADER_INSTALL_DIR
#define RGRAPH_SHADER_INSTALL_DIR ""
#endif

namespace fs = std::filesystem;

namespace rgraph {
namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RuntimeError("cannot read shader file " + path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Shown in messages: relative to the working directory when inside it.
std::string displayPath(const std::string& path) {
  std::error_code ec;
  fs::path rel = fs::relative(path, fs::current_path(ec), ec);
  if (!ec && !rel.empty() && *rel.begin() != "..") return rel.generic_string();
  return fs::path(path).lexically_normal().generic_string();
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream ss(text);
  while (std::getline(ss, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

std::string trimLeft(const std::string& s) {
  size_t i = s.find_first_not_of(" \t");
  return i == std::string::npos ? std::string() : s.substr(i);
}

// A tiny cursor for the line parsers below (no std::regex: slow to build and
// noisy under the sanitizers).
struct Cursor {
  const std::string& s;
  size_t i = 0;
  void spaces() {
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  }
  bool lit(std::string_view t) {
    if (s.compare(i, t.size(), t) != 0) return false;
    i += t.size();
    return true;
  }
  bool number(std::string& out) {
    size_t b = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
    out = s.substr(b, i - b);
    return i > b && i - b < 9;
  }
  std::string rest() const { return i < s.size() ? s.substr(i) : std::string(); }
};

// `#include "file"` (or <file>) -> file.
bool parseInclude(const std::string& line, std::string& file) {
  Cursor c{line};
  c.spaces();
  if (!c.lit("#")) return false;
  c.spaces();
  if (!c.lit("include")) return false;
  c.spaces();
  if (c.i >= line.size() || (line[c.i] != '"' && line[c.i] != '<')) return false;
  char close = line[c.i] == '"' ? '"' : '>';
  size_t end = line.find(close, c.i + 1);
  if (end == std::string::npos || end == c.i + 1) return false;
  file = line.substr(c.i + 1, end - c.i - 1);
  c.i = end + 1;
  c.spaces();
  return c.i >= line.size() || c.lit("//");
}

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

// Rewrites driver log lines (`0:12(5): error: ...` Mesa, `0(12) : error ...`
// NVIDIA, `ERROR: 0:12: ...`) to `FILE:12: error: ...`.
std::string mapLog(const std::string& log, const std::vector<std::string>& files,
                   const std::vector<std::pair<int, int>>& lineMap) {
  // Source string 0, expanded line L -> "FILE:LINE" of the original text.
  auto where = [&](const std::string& srcNo, const std::string& lineNo) {
    size_t l = std::stoul(lineNo);
    std::string main = files.empty() ? std::string("<shader>") : files[0];
    if (std::stoul(srcNo) != 0 || l == 0 || l > lineMap.size()) return main + ":" + lineNo;
    const auto& [f, orig] = lineMap[l - 1];
    return (static_cast<size_t>(f) < files.size() ? files[f] : main) + ":" + std::to_string(orig);
  };
  std::string out;
  for (const auto& line : splitLines(log)) {
    if (trimLeft(line).empty()) continue;
    std::string mapped = line, src, ln, col;
    Cursor c{line};
    c.spaces();
    size_t start = c.i;
    if (c.number(src) && c.lit(":") && c.number(ln) && c.lit("(") && c.number(col) && c.lit("):")) {
      c.spaces();  // Mesa: 0:12(5): error: ...
      mapped = where(src, ln) + ": " + c.rest();
    } else if ((c.i = start, c.number(src) && c.lit("(") && c.number(ln) && c.lit(")"))) {
      c.spaces();  // NVIDIA: 0(12) : error C0000: ...
      if (c.lit(":")) {
        c.spaces();
        mapped = where(src, ln) + ": " + c.rest();
      }
    } else {
      c.i = start;  // ERROR: 0:12: ... (and WARNING:)
      std::string sev = c.lit("ERROR:") ? "error" : c.lit("WARNING:") ? "warning" : "";
      c.spaces();
      if (!sev.empty() && c.number(src) && c.lit(":") && c.number(ln) && c.lit(":")) {
        c.spaces();
        mapped = where(src, ln) + ": " + sev + ": " + c.rest();
      }
    }
    if (!out.empty()) out += "\n";
    out += mapped;
  }
  return out;
}

}  // namespace

ShaderLibrary::ShaderLibrary() = default;
ShaderLibrary::~ShaderLibrary() = default;

void ShaderLibrary::addSearchDirectory(const std::string& dir) { extraDirs_.insert(extraDirs_.begin(), dir); }

std::vector<std::string> ShaderLibrary::searchDirectories() const {
  std::vector<std::string> dirs = extraDirs_;
  if (const char* env = std::getenv("RGRAPH_SHADER_DIR")) {
    std::string s = env;
    size_t start = 0;
    while (start <= s.size()) {
      size_t end = s.find(':', start);
      if (end == std::string::npos) end = s.size();
      if (end > start) dirs.push_back(s.substr(start, end - start));
      start = end + 1;
    }
  }
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) dirs.push_back((exe.parent_path() / ".." / "share" / "rgraph" / "shaders").lexically_normal().string());
  if (std::string(RGRAPH_SHADER_INSTALL_DIR).size()) dirs.push_back(RGRAPH_SHADER_INSTALL_DIR);
  if (std::string(RGRAPH_SHADER_SOURCE_DIR).size()) dirs.push_back(RGRAPH_SHADER_SOURCE_DIR);
  return dirs;
}

std::string ShaderLibrary::find(const std::string& file) const {
  std::error_code ec;
  fs::path p(file);
  if (p.is_absolute()) return fs::is_regular_file(p, ec) ? p.string() : std::string();
  for (const auto& dir : searchDirectories()) {
    fs::path candidate = fs::path(dir) / p;
    if (fs::is_regular_file(candidate, ec)) return candidate.lexically_normal().string();
  }
  return {};
}

std::string ShaderLibrary::resolve(const std::string& file) const {
  std::string path = find(file);
  if (!path.empty()) return path;
  std::string dirs;
  for (const auto& d : searchDirectories()) dirs += (dirs.empty() ? "" : ", ") + d;
  throw RuntimeError("shader file '" + file + "' not found (searched: " + dirs + ")");
}

ShaderLibrary::Source ShaderLibrary::load(const std::string& file, const std::vector<std::string>& defines) const {
  // Expanded into one source string without #line directives (drivers disagree
  // on source-string numbers, Mesa even within one log); every expanded line
  // remembers its file and line instead.
  Source src;
  std::string path = resolve(file);
  src.files.push_back(displayPath(path));
  std::vector<std::string> lines = splitLines(readFile(path));

  std::string out;
  auto emit = [&](const std::string& line, int fileIndex, int lineNo) {
    out += line;
    out += '\n';
    src.lines.emplace_back(fileIndex, lineNo);
  };
  auto emitDefines = [&](int lineNo) {
    for (const auto& d : defines) {
      size_t eq = d.find('=');
      emit(eq == std::string::npos ? "#define " + d : "#define " + d.substr(0, eq) + " " + d.substr(eq + 1), 0,
           lineNo);
    }
  };

  bool hasVersion = false;
  for (const auto& line : lines)
    if (trimLeft(line).rfind("#version", 0) == 0) hasVersion = true;
  if (!hasVersion) {
    emit("#version 450 core", 0, 1);
    emitDefines(1);
  }
  bool versionSeen = false;
  for (size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    int lineNo = static_cast<int>(i) + 1;
    if (!versionSeen && trimLeft(line).rfind("#version", 0) == 0) {
      versionSeen = true;
      emit(line, 0, lineNo);
      emitDefines(lineNo);
      continue;
    }
    std::string inc;
    if (parseInclude(line, inc)) {
      fs::path local = fs::path(path).parent_path() / inc;
      std::error_code ec;
      std::string incPath = fs::is_regular_file(local, ec) ? local.lexically_normal().string() : find(inc);
      if (incPath.empty())
        throw RuntimeError(src.files[0] + ":" + std::to_string(lineNo) + ": error: included file '" + inc +
                           "' not found");
      int id = static_cast<int>(src.files.size());
      src.files.push_back(displayPath(incPath));
      std::vector<std::string> incLines = splitLines(readFile(incPath));
      for (size_t j = 0; j < incLines.size(); ++j) {
        std::string nested;
        if (parseInclude(incLines[j], nested))
          throw RuntimeError(src.files[id] + ":" + std::to_string(j + 1) +
                             ": error: nested #include is not supported (include '" + nested + "' from " +
                             src.files[0] + " instead)");
        emit(incLines[j], id, static_cast<int>(j) + 1);
      }
      continue;
    }
    emit(line, 0, lineNo);
  }
  src.text = std::move(out);
  return src;
}

std::string ShaderLibrary::preprocess(const std::string& file, const std::vector<std::string>& defines) const {
  return load(file, defines).text;
}

gl::Shader ShaderLibrary::compileStage(unsigned stage, const std::string& file,
                                       const std::vector<std::string>& defines) const {
  Source src = load(file, defines);
  gl::Shader shader = gl::createShader(stage);
  const char* text = src.text.c_str();
  glShaderSource(shader.id(), 1, &text, nullptr);
  glCompileShader(shader.id());
  GLint ok = 0;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  std::string log = shaderLog(shader.id());
  if (!ok) {
    std::string mapped = mapLog(log, src.files, src.lines);
    if (mapped.empty()) mapped = src.files[0] + ": error: " + stageName(stage) + " shader failed to compile";
    throw RuntimeError(mapped);
  }
  if (!log.empty()) spdlog::debug("{} ({} shader): {}", src.files[0], stageName(stage), mapLog(log, src.files, src.lines));
  return shader;
}

uint32_t ShaderLibrary::link(const std::string& key, std::vector<gl::Shader> stages, const std::string& what) {
  gl::Program program = gl::createProgram();
  for (const auto& s : stages) glAttachShader(program.id(), s.id());
  glLinkProgram(program.id());
  for (const auto& s : stages) glDetachShader(program.id(), s.id());
  GLint ok = 0;
  glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (!ok) throw RuntimeError(what + ": error: program failed to link: " + programLog(program.id()));
  uint32_t id = program.id();
  programs_[key] = std::move(program);
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
  std::string key = cacheKey({vert, frag}, defines);
  if (auto it = programs_.find(key); it != programs_.end()) return it->second.id();
  std::vector<gl::Shader> stages;
  stages.push_back(compileStage(GL_VERTEX_SHADER, vert, defines));
  stages.push_back(compileStage(GL_FRAGMENT_SHADER, frag, defines));
  return link(key, std::move(stages), displayPath(resolve(vert)) + " + " + displayPath(resolve(frag)));
}

uint32_t ShaderLibrary::computeProgram(const std::string& comp, const std::vector<std::string>& defines) {
  std::string key = cacheKey({comp}, defines);
  if (auto it = programs_.find(key); it != programs_.end()) return it->second.id();
  std::vector<gl::Shader> stages;
  stages.push_back(compileStage(GL_COMPUTE_SHADER, comp, defines));
  return link(key, std::move(stages), displayPath(resolve(comp)));
}

void ShaderLibrary::clear() { programs_.clear(); }

}  // namespace rgraph
