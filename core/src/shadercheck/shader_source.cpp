// Shader sources without a GL context: search directories, #include
// expansion, defines, the line table, and compiler-log mapping. Shared by
// ShaderLibrary (core/src/gl) and the glslang checker (shader_check.cpp).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <fstream>
#include <sstream>
#include <string_view>

#include "rgraph/own_files.h"
#include "rgraph/shader_check.h"


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

}  // namespace

ShaderSourceError::ShaderSourceError(std::string file, int line, std::string message)
    : RuntimeError(file + ":" + std::to_string(line) + ": error: " + message),
      file_(std::move(file)),
      line_(line),
      message_(std::move(message)) {}

namespace {
// Folders added for the whole process: --shader-path (searched first) and the
// shader folders of loaded plugins (searched last: they never shadow a
// built-in name; plugins name their own files by absolute path).
struct ProcessShaderDirs {
  std::mutex mutex;
  std::vector<std::string> first, last;
};
ProcessShaderDirs& processShaderDirs() {
  static ProcessShaderDirs dirs;
  return dirs;
}

void addUnique(std::vector<std::string>& dirs, const std::string& dir) {
  if (!dir.empty() && std::find(dirs.begin(), dirs.end(), dir) == dirs.end()) dirs.push_back(dir);
}

// Whether `path` (symbolic links resolved) lies inside one of `dirs` (theirs resolved too).
bool insideAny(const fs::path& path, const std::vector<std::string>& dirs) {
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(path, ec);
  if (ec) return false;
  for (const auto& dir : dirs) {
    const fs::path root = fs::weakly_canonical(dir, ec);
    if (ec || root.empty()) continue;
    const fs::path rel = real.lexically_relative(root);
    if (!rel.empty() && *rel.begin() != ".." && !rel.is_absolute()) return true;
  }
  return false;
}

std::string folderList(const std::vector<std::string>& dirs) {
  std::string list;
  for (const auto& d : dirs) list += (list.empty() ? "" : ", ") + d;
  return list;
}

// A file found where a relative name points, but outside every shader folder
// (a `..` or a symbolic link leading out): the reason, or "".
std::string escapeOf(const std::string& file, const std::vector<std::string>& dirs) {
  std::error_code ec;
  const fs::path p(file);
  if (p.is_absolute()) return {};  // used as is (findShaderFile)
  for (const auto& dir : dirs) {
    const fs::path c = fs::path(dir) / p;
    if (!fs::exists(c, ec) || insideAny(c, dirs)) continue;
    return "shader file '" + file + "' resolves to " + fs::weakly_canonical(c, ec).string() +
           ", outside the shader folders (" + folderList(dirs) +
           "); shaders are read only from inside them (add a folder with --shader-path)";
  }
  return {};
}
}  // namespace

void addShaderSearchDirectory(const std::string& dir) {
  ProcessShaderDirs& d = processShaderDirs();
  std::lock_guard<std::mutex> lock(d.mutex);
  addUnique(d.first, dir);
}

void addPluginShaderDirectory(const std::string& dir) {
  ProcessShaderDirs& d = processShaderDirs();
  std::lock_guard<std::mutex> lock(d.mutex);
  addUnique(d.last, dir);
}

std::vector<std::string> defaultShaderSearchDirectories() {
  std::vector<std::string> dirs;
  {
    ProcessShaderDirs& d = processShaderDirs();
    std::lock_guard<std::mutex> lock(d.mutex);
    dirs = d.first;
  }
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
  // rgraph's own shaders: one folder, found from where librgraph is (an
  // install's share/rgraph/shaders, or a build tree's source shaders/), never
  // a path baked in at build time (rgraph/own_files.h).
  if (const std::string& own = ownFiles().shaders; !own.empty()) dirs.push_back(own);
  ProcessShaderDirs& d = processShaderDirs();
  std::lock_guard<std::mutex> lock(d.mutex);
  for (const auto& dir : d.last) addUnique(dirs, dir);
  return dirs;
}

std::string findShaderFile(const std::string& file, const std::vector<std::string>& dirs) {
  std::error_code ec;
  fs::path p(file);
  if (file.find('\0') != std::string::npos) return {};
  // An absolute name comes from code, never from a config (the loader refuses
  // absolute shader parameters): a plugin's or an application's own file, used as is.
  if (p.is_absolute()) return fs::is_regular_file(p, ec) ? p.lexically_normal().string() : std::string();
  for (const auto& dir : dirs) {
    fs::path candidate = fs::path(dir) / p;
    if (fs::is_regular_file(candidate, ec) && insideAny(candidate, dirs)) return candidate.lexically_normal().string();
  }
  return {};
}

std::string resolveShaderFile(const std::string& file, const std::vector<std::string>& dirs) {
  std::string path = findShaderFile(file, dirs);
  if (!path.empty()) return path;
  if (fs::path(file).is_absolute())
    throw RuntimeError("shader file '" + file + "' not found (an absolute path: used as is, not searched for)");
  if (std::string why = escapeOf(file, dirs); !why.empty()) throw RuntimeError(why);
  throw RuntimeError("shader file '" + file + "' not found (searched: " + folderList(dirs) + ")");
}

std::string shaderDisplayPath(const std::string& path) {
  std::error_code ec;
  fs::path rel = fs::relative(path, fs::current_path(ec), ec);
  if (!ec && !rel.empty() && *rel.begin() != "..") return rel.generic_string();
  return fs::path(path).lexically_normal().generic_string();
}

namespace {
// The source a copy was made from, per the manifest beside it; "" when none.
std::string manifestSource(const fs::path& copy) {
  std::ifstream in(copy.parent_path() / kShaderSourcesManifest);
  if (!in) return {};
  const std::string name = copy.filename().string();
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t tab = line.find('\t');
    if (line.empty() || line[0] == '#' || tab == std::string::npos) continue;
    if (line.compare(0, tab, name) == 0 && tab == name.size()) return line.substr(tab + 1);
  }
  return {};
}
}  // namespace

ShaderOrigin shaderOrigin(const std::string& path, const std::string& text) {
  ShaderOrigin origin{shaderDisplayPath(path), {}};
  const std::string source = manifestSource(fs::path(path));
  std::error_code ec;
  if (source.empty() || !fs::is_regular_file(source, ec)) return origin;
  std::string sourceText;
  try {
    sourceText = readFile(source);
  } catch (const RuntimeError&) {
    return origin;
  }
  if (sourceText == text) {
    origin.display = shaderDisplayPath(source);
  } else {
    origin.note = origin.display + " is a copy of " + shaderDisplayPath(source) +
                  ", which has changed since it was copied: rebuild the plugin to copy it again";
  }
  return origin;
}

ShaderSource loadShaderSource(const std::string& file, const std::vector<std::string>& defines,
                              const std::vector<std::string>& dirs) {
  // Expanded into one source string without #line directives (drivers disagree
  // on source-string numbers, Mesa even within one log); every expanded line
  // remembers its file and line instead.
  ShaderSource src;
  src.path = resolveShaderFile(file, dirs);
  const std::string& path = src.path;
  const std::string mainText = readFile(path);
  {
    ShaderOrigin origin = shaderOrigin(path, mainText);
    src.files.push_back(std::move(origin.display));
    src.notes.push_back(std::move(origin.note));
  }
  src.resolvedFiles.push_back(path);
  if (!fs::path(file).is_absolute())
    for (const auto& dir : dirs) {
      std::string candidate = (fs::path(dir) / file).lexically_normal().string();
      if (candidate == path) break;
      src.shadowPaths.push_back(std::move(candidate));
    }
  std::vector<std::string> lines = splitLines(mainText);
  // A file named by its absolute path (a plugin's, an application's) includes
  // files beside it as a shader folder's would.
  std::vector<std::string> includeDirs = dirs;
  if (fs::path(file).is_absolute()) includeDirs.push_back(fs::path(path).parent_path().string());

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
      std::string incPath = fs::is_regular_file(local, ec) && insideAny(local, includeDirs)
                                ? local.lexically_normal().string()
                                : findShaderFile(inc, dirs);
      if (incPath.empty() && fs::exists(local, ec) && !insideAny(local, includeDirs))
        throw ShaderSourceError(src.files[0], lineNo,
                                "included file '" + inc + "' resolves to " + fs::weakly_canonical(local, ec).string() +
                                    ", outside the shader folders; shaders are read only from inside them");
      if (incPath.empty()) {
        std::string why = escapeOf(inc, dirs);
        throw ShaderSourceError(src.files[0], lineNo, why.empty() ? "included file '" + inc + "' not found" : why);
      }
      int id = static_cast<int>(src.files.size());
      const std::string incText = readFile(incPath);
      ShaderOrigin origin = shaderOrigin(incPath, incText);
      src.files.push_back(std::move(origin.display));
      src.notes.push_back(std::move(origin.note));
      src.resolvedFiles.push_back(incPath);
      std::vector<std::string> incLines = splitLines(incText);
      for (size_t j = 0; j < incLines.size(); ++j) {
        std::string nested;
        if (parseInclude(incLines[j], nested))
          throw ShaderSourceError(src.files[id], static_cast<int>(j) + 1,
                                  "nested #include is not supported (include '" + nested + "' from " + src.files[0] +
                                      " instead)");
        emit(incLines[j], id, static_cast<int>(j) + 1);
      }
      continue;
    }
    emit(line, 0, lineNo);
  }
  src.text = std::move(out);
  return src;
}

std::vector<ShaderMessage> parseShaderLog(const std::string& log, const ShaderSource& src) {
  const std::string main = src.files.empty() ? std::string("<shader>") : src.files[0];
  // Source string 0, expanded line L -> the file and line of the original text.
  // The note of the file a message ends up in (a stale plugin shader copy).
  std::string note;
  auto noteOf = [&](size_t f) { return f < src.notes.size() ? src.notes[f] : std::string(); };
  auto locate = [&](ShaderMessage& m, const std::string& srcNo, const std::string& lineNo) {
    size_t l = std::stoul(lineNo);
    m.file = main;
    m.line = static_cast<int>(l);
    note = noteOf(0);
    if (std::stoul(srcNo) != 0 || l == 0 || l > src.lines.size()) return;
    const auto& [f, orig] = src.lines[l - 1];
    m.file = static_cast<size_t>(f) < src.files.size() ? src.files[f] : main;
    m.line = orig;
    note = noteOf(static_cast<size_t>(f));
  };
  // "error: text" / "warning: text" at the start of a driver message.
  auto severityOf = [](std::string& text) {
    for (auto [word, sev] : {std::pair{"error", Severity::error}, std::pair{"warning", Severity::warning}}) {
      std::string w = word;
      if (text.rfind(w, 0) == 0) {
        size_t i = w.size();
        while (i < text.size() && text[i] != ':' && text[i] != ' ') ++i;  // "error C0000"
        if (i < text.size() && text[i] == ' ') {
          size_t colon = text.find(':', i);
          if (colon != std::string::npos && colon - i < 10) i = colon;
        }
        if (i < text.size() && text[i] == ':') {
          text = trimLeft(text.substr(i + 1));
          return sev;
        }
      }
    }
    return Severity::error;
  };

  std::vector<ShaderMessage> out;
  for (const auto& line : splitLines(log)) {
    if (trimLeft(line).empty()) continue;
    ShaderMessage m;
    note = noteOf(0);
    std::string srcNo, ln, col;
    Cursor c{line};
    c.spaces();
    size_t start = c.i;
    if (c.number(srcNo) && c.lit(":") && c.number(ln) && c.lit("(") && c.number(col) && c.lit("):")) {
      c.spaces();  // Mesa: 0:12(5): error: ...
      locate(m, srcNo, ln);
      m.text = c.rest();
      m.severity = severityOf(m.text);
    } else if ((c.i = start, c.number(srcNo) && c.lit("(") && c.number(ln) && c.lit(")"))) {
      c.spaces();  // NVIDIA: 0(12) : error C0000: ...
      if (c.lit(":")) {
        c.spaces();
        locate(m, srcNo, ln);
        m.text = c.rest();
        m.severity = severityOf(m.text);
      } else {
        m.file = main;
        m.text = trimLeft(line);
      }
    } else {
      c.i = start;  // glslang: ERROR: 0:12: ... (and WARNING:)
      bool error = c.lit("ERROR:");
      bool warning = !error && c.lit("WARNING:");
      c.spaces();
      size_t afterSeverity = c.i;
      m.severity = warning ? Severity::warning : Severity::error;
      if ((error || warning) && c.number(srcNo) && c.lit(":") && c.number(ln) && c.lit(":")) {
        c.spaces();
        locate(m, srcNo, ln);
        m.text = c.rest();
      } else if (error || warning) {
        c.i = afterSeverity;
        std::string rest = c.rest();
        // glslang's summary ("1 compilation errors.  No code generated.") says nothing new.
        if (rest.find("compilation errors") != std::string::npos || rest.find("compilation error") != std::string::npos)
          continue;
        m.file = main;
        m.text = rest;
      } else {
        m.file = main;
        m.text = trimLeft(line);
        m.severity = severityOf(m.text);
      }
    }
    while (!m.text.empty() && (m.text.back() == ' ' || m.text.back() == '\t')) m.text.pop_back();
    if (m.text.rfind("'' :", 0) == 0) m.text = trimLeft(m.text.substr(4));  // glslang names no token
    if (!note.empty()) m.text += " (" + note + ")";
    out.push_back(std::move(m));
  }
  return out;
}

std::string shaderErrorSummary(const std::vector<ShaderMessage>& messages, size_t maxLines) {
  static const std::string kCandidates = "; candidates are:";
  std::vector<std::pair<std::string, int>> seen;
  std::string out;
  size_t shown = 0, left = 0;
  for (const auto& m : messages) {
    if (m.severity != Severity::error) continue;
    const std::pair<std::string, int> at{m.file, m.line};
    if (m.line > 0 && std::find(seen.begin(), seen.end(), at) != seen.end()) continue;
    seen.push_back(at);
    if (shown == maxLines) {
      ++left;
      continue;
    }
    std::string text = m.text;
    if (const size_t c = text.find(kCandidates); c != std::string::npos) text.erase(c, kCandidates.size());
    if (!out.empty()) out += "\n";
    out += (m.file.empty() ? std::string("<shader>") : m.file) + (m.line > 0 ? ":" + std::to_string(m.line) : "") +
           ": error: " + text;
    ++shown;
  }
  if (left) out += "\n(" + std::to_string(left) + " more lines with errors)";
  return out;
}

std::string mapShaderLog(const std::string& log, const ShaderSource& src) {
  // Same rewriting as before the move: a located line becomes `FILE:LINE: `
  // followed by the driver's text after its location; other lines stay.
  const std::string main = src.files.empty() ? std::string("<shader>") : src.files[0];
  auto where = [&](const std::string& srcNo, const std::string& lineNo) {
    size_t l = std::stoul(lineNo);
    if (std::stoul(srcNo) != 0 || l == 0 || l > src.lines.size()) return main + ":" + lineNo;
    const auto& [f, orig] = src.lines[l - 1];
    return (static_cast<size_t>(f) < src.files.size() ? src.files[f] : main) + ":" + std::to_string(orig);
  };
  std::string out;
  for (const auto& line : splitLines(log)) {
    if (trimLeft(line).empty()) continue;
    std::string mapped = line, srcNo, ln, col;
    Cursor c{line};
    c.spaces();
    size_t start = c.i;
    if (c.number(srcNo) && c.lit(":") && c.number(ln) && c.lit("(") && c.number(col) && c.lit("):")) {
      c.spaces();  // Mesa: 0:12(5): error: ...
      mapped = where(srcNo, ln) + ": " + c.rest();
    } else if ((c.i = start, c.number(srcNo) && c.lit("(") && c.number(ln) && c.lit(")"))) {
      c.spaces();  // NVIDIA: 0(12) : error C0000: ...
      if (c.lit(":")) {
        c.spaces();
        mapped = where(srcNo, ln) + ": " + c.rest();
      }
    } else {
      c.i = start;  // ERROR: 0:12: ... (and WARNING:)
      std::string sev = c.lit("ERROR:") ? "error" : c.lit("WARNING:") ? "warning" : "";
      c.spaces();
      if (!sev.empty() && c.number(srcNo) && c.lit(":") && c.number(ln) && c.lit(":")) {
        c.spaces();
        mapped = where(srcNo, ln) + ": " + sev + ": " + c.rest();
      }
    }
    if (!out.empty()) out += "\n";
    out += mapped;
  }
  return out;
}

}  // namespace rgraph
