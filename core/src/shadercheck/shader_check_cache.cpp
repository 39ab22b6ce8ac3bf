#include "rgraph/shader_check_cache.h"

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "rgraph/config.h"
#include "rgraph/registry.h"
#include "rgraph/shader_check.h"

namespace rgraph {
namespace fs = std::filesystem;

namespace {

// Bumped when the entry format or the key's contents change.
constexpr const char* kCacheVersion = "rgraph-shadercheck-cache-3";

// Two unrelated 64-bit hashes of the key text: the first names the entry, the
// second is stored in it and checked, so a collision of one is not enough.
uint64_t fnv1a(const std::string& s) {
  uint64_t h = 14695981039346656037ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

uint64_t mixHash(const std::string& s) {
  uint64_t h = 0x243F6A8885A308D3ull ^ s.size();
  for (unsigned char c : s) {
    h = (h ^ c) * 0x9E3779B97F4A7C15ull;
    h ^= h >> 29;
  }
  return h;
}

std::string hex(uint64_t v) {
  char b[17];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(v));
  return b;
}

// Path, size and modification time: changes whenever the file is rebuilt.
std::string fileIdentity(const std::string& path) {
  std::error_code ec;
  const auto size = fs::file_size(path, ec);
  if (ec) return path + " (unreadable)";
  const auto time = fs::last_write_time(path, ec).time_since_epoch().count();
  return path + " " + std::to_string(size) + " " + std::to_string(time);
}

std::string paramText(const ParamValue& v) {
  return std::visit(
      [](const auto& x) {
        nlohmann::json j = x;
        return j.dump();
      },
      v);
}

void appendLocation(std::ostringstream& k, const SourceLocation& w) {
  k << " @" << w.file << ':' << w.line << ':' << w.column << ':' << w.path;
}

// The pipeline as the checks see it: every field they read, located.
void appendPipeline(std::ostringstream& k, const PipelineConfig& pipeline) {
  const GraphDesc& g = pipeline.graph;
  k << "file " << pipeline.file << "\n";
  for (const auto& r : g.resources)
    k << "resource " << r.name << ' ' << static_cast<int>(r.kind) << ' ' << formatName(r.texture.format) << ' '
      << r.texture.samples << ' ' << r.imported << ' ' << r.texture.layers << ' ' << r.texture.cube << "\n";
  for (size_t p = 0; p < g.passes.size(); ++p) {
    const PassDecl& pd = g.passes[p];
    k << "pass " << pd.name << ' ' << pd.type << ' ' << pd.enabled;
    appendLocation(k, pd.where);
    k << "\n";
    for (const auto& u : pd.uses) {
      k << " use " << u.slot << ' ' << static_cast<int>(u.access) << ' ' << u.input << ' ' << u.output << ' '
        << subresourceLabel("", u.sub);
      appendLocation(k, u.inputWhere);
      appendLocation(k, u.outputWhere);
      k << "\n";
    }
    if (p < pipeline.params.size())
      for (const auto& [name, value] : pipeline.params[p].values())
        k << " param " << name << '=' << paramText(value) << "\n";
  }
  k << "output " << g.output << "\n";
}

// The expanded sources of every program the enabled passes build, and the
// plugin files their types come from.
void appendPrograms(std::ostringstream& k, const PipelineConfig& pipeline, const PassRegistry& registry,
                    const std::vector<std::string>& dirs) {
  std::set<std::string> origins;
  for (size_t p = 0; p < pipeline.graph.passes.size(); ++p) {
    const PassDecl& pd = pipeline.graph.passes[p];
    const PassTypeDesc* type = pd.enabled ? registry.find(pd.type) : nullptr;
    if (!type) continue;
    origins.insert(type->origin);
    if (!type->programs) continue;
    // The sampler states the checks compare with shadow samplers (declared
    // by the type or overridden by the pass, located).
    for (const SlotDecl& slot : type->slots) {
      SourceLocation w;
      if (std::optional<SamplerState> st = slotSamplerState(pipeline, p, slot, &w)) {
        k << " sampler " << slot.name << ": " << describeSampler(*st);
        appendLocation(k, w);
        k << "\n";
      }
    }
    ParamSet params = defaultParams(type->params);
    if (p < pipeline.params.size())
      for (const auto& [name, value] : pipeline.params[p].values()) params.set(name, value);
    std::vector<ShaderProgramSpec> specs;
    try {
      specs = type->programs(params);
    } catch (const std::exception& e) {
      k << "programs of " << pd.name << " refused: " << e.what() << "\n";
      continue;
    }
    for (const auto& spec : specs) {
      for (const std::string* file : {&spec.vert, &spec.frag, &spec.comp}) {
        if (file->empty()) continue;
        k << "shader " << *file;
        for (const auto& d : spec.defines) k << " -D" << d;
        k << "\n";
        try {
          const ShaderSource src = loadShaderSource(*file, spec.defines, dirs);
          k << src.path << "\n" << src.text << "\n";
          // The names messages give the files (a plugin shader's copy names
          // its source, or says it is stale): part of the cached result.
          for (size_t f = 0; f < src.files.size(); ++f)
            k << "shown " << src.files[f] << "\t" << (f < src.notes.size() ? src.notes[f] : "") << "\n";
        } catch (const std::exception& e) {
          k << "unloadable: " << e.what() << "\n";
        }
      }
    }
  }
  for (const auto& origin : origins) k << "origin " << (origin == "built-in" ? origin : fileIdentity(origin)) << "\n";
}

std::string cacheKey(const ShaderChecker& checker, const PipelineConfig& pipeline, const PassRegistry& registry) {
  std::ostringstream k;
  std::error_code ec;
  k << kCacheVersion << "\nexe " << fileIdentity(fs::read_symlink("/proc/self/exe", ec).string()) << "\ncwd "
    << fs::current_path(ec).string() << "\n";
  for (const auto& d : checker.searchDirectories()) k << "dir " << d << "\n";
  appendPipeline(k, pipeline);
  appendPrograms(k, pipeline, registry, checker.searchDirectories());
  return k.str();
}

// An entry holds a verdict, never messages: {"check": SECOND_HASH, "clean": true},
// written only for checks that found nothing. Diagnostics are not stored, so
// nothing read from the cache is ever printed (a crafted entry once replayed
// "error:" lines while render exited 0); a check that found something runs
// again next time, which is what its author is about to fix anyway.
constexpr size_t kMaxEntryBytes = 4096;

// The entry's text, read only from a regular file: opened non-blocking (a FIFO
// at the entry's path would block open() forever) and checked with fstat on
// the opened file (no race with a swap after a stat of the path).
std::optional<std::string> readEntryText(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) return std::nullopt;
  std::optional<std::string> text;
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size >= 0 &&
      static_cast<uint64_t>(st.st_size) <= kMaxEntryBytes) {
    std::string buf(kMaxEntryBytes + 1, '\0');
    size_t got = 0;
    for (;;) {
      const ssize_t n = ::read(fd, buf.data() + got, buf.size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        if (n == 0 && got <= kMaxEntryBytes) text = buf.substr(0, got);
        break;
      }
      got += static_cast<size_t>(n);
      if (got > kMaxEntryBytes) break;  // grew since fstat: not an entry rgraph wrote
    }
  }
  ::close(fd);
  return text;
}

// true only for an entry exactly as writeEntry writes it for this key; any
// other content (damaged, foreign, crafted) is a miss, recomputed and rewritten.
bool entrySaysClean(const fs::path& path, const std::string& check) {
  const std::optional<std::string> text = readEntryText(path);
  if (!text) return false;
  const nlohmann::json j = nlohmann::json::parse(*text, nullptr, /*allow_exceptions=*/false);
  const bool ok = j.is_object() && j.size() == 2 && j.contains("check") && j["check"] == check &&
                  j.contains("clean") && j["clean"] == true;
  if (!ok) spdlog::debug("shader-check cache: {} is not an entry for this pipeline: a miss", path.string());
  return ok;
}

// A temporary file renamed into place: readers see the old entry or the whole
// new one, and whatever was at the path (a FIFO, a symbolic link) is replaced,
// never written through (so not writeOutputFile, which follows links and
// writes devices in place). A cache that cannot be written is skipped.
void writeEntry(const fs::path& dir, const fs::path& path, const std::string& check) {
  static std::atomic<unsigned> counter{0};
  std::error_code ec;
  fs::create_directories(dir, ec);
  const fs::path tmp =
      dir / (path.filename().string() + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return;
    out << nlohmann::json{{"check", check}, {"clean", true}}.dump();
    out.close();
    if (!out) {
      fs::remove(tmp, ec);
      return;
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) fs::remove(tmp, ec);
}

}  // namespace

std::string defaultShaderCheckCacheDir() {
  auto env = [](const char* name) -> std::string {
    const char* v = std::getenv(name);
    return v && *v ? v : "";
  };
  std::string base = env("RGRAPH_CACHE_DIR");
  if (base.empty() && !env("XDG_CACHE_HOME").empty()) base = env("XDG_CACHE_HOME") + "/rgraph";
  if (base.empty() && !env("HOME").empty()) base = env("HOME") + "/.cache/rgraph";
  return base.empty() ? "" : base + "/shadercheck";
}

CachedShaderCheck checkPipelineCached(ShaderChecker& checker, const PipelineConfig& pipeline, const Plan& plan,
                                      const PassRegistry& registry, const std::string& cacheDir) {
  CachedShaderCheck result;
  if (cacheDir.empty()) {
    result.diagnostics = checker.checkPipeline(pipeline, plan, registry);
    return result;
  }
  const std::string key = cacheKey(checker, pipeline, registry);
  const fs::path dir(cacheDir);
  const fs::path path = dir / (hex(fnv1a(key)) + ".json");
  const std::string check = hex(mixHash(key));
  if (entrySaysClean(path, check)) {
    result.hit = true;
    return result;
  }
  result.diagnostics = checker.checkPipeline(pipeline, plan, registry);
  if (result.diagnostics.empty()) writeEntry(dir, path, check);
  return result;
}

}  // namespace rgraph
