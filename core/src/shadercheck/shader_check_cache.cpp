#include "rgraph/shader_check_cache.h"

#include <unistd.h>

#include <atomic>
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
constexpr const char* kCacheVersion = "rgraph-shadercheck-cache-1";

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
      << r.texture.samples << ' ' << r.imported << "\n";
  for (size_t p = 0; p < g.passes.size(); ++p) {
    const PassDecl& pd = g.passes[p];
    k << "pass " << pd.name << ' ' << pd.type << ' ' << pd.enabled;
    appendLocation(k, pd.where);
    k << "\n";
    for (const auto& u : pd.uses) {
      k << " use " << u.slot << ' ' << static_cast<int>(u.access) << ' ' << u.input << ' ' << u.output;
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

nlohmann::json toJson(const Diagnostics& diags) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& d : diags)
    out.push_back({static_cast<int>(d.code), static_cast<int>(d.severity), d.message, d.pass, d.slot, d.resource,
                   d.where.file, d.where.line, d.where.column, d.where.path});
  return out;
}

Diagnostics fromJson(const nlohmann::json& j) {
  Diagnostics out;
  for (const auto& e : j) {
    Diagnostic d;
    d.code = static_cast<DiagCode>(e.at(0).get<int>());
    d.severity = static_cast<Severity>(e.at(1).get<int>());
    d.message = e.at(2).get<std::string>();
    d.pass = e.at(3).get<std::string>();
    d.slot = e.at(4).get<std::string>();
    d.resource = e.at(5).get<std::string>();
    d.where.file = e.at(6).get<std::string>();
    d.where.line = e.at(7).get<int>();
    d.where.column = e.at(8).get<int>();
    d.where.path = e.at(9).get<std::string>();
    out.push_back(std::move(d));
  }
  return out;
}

std::optional<Diagnostics> readEntry(const fs::path& path, const std::string& check) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("check").get<std::string>() != check) return std::nullopt;
    return fromJson(j.at("diagnostics"));
  } catch (const std::exception&) {
    return std::nullopt;  // damaged or foreign: treated as absent, rewritten below
  }
}

// A temporary file renamed into place: readers see the old entry or the whole new one.
void writeEntry(const fs::path& dir, const fs::path& path, const std::string& check, const Diagnostics& diags) {
  static std::atomic<unsigned> counter{0};
  std::error_code ec;
  fs::create_directories(dir, ec);
  const fs::path tmp =
      dir / (path.filename().string() + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++));
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return;
    out << nlohmann::json{{"check", check}, {"diagnostics", toJson(diags)}}.dump();
    if (!out.flush()) {
      out.close();
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
  if (auto cached = readEntry(path, check)) {
    result.diagnostics = std::move(*cached);
    result.hit = true;
    return result;
  }
  result.diagnostics = checker.checkPipeline(pipeline, plan, registry);
  writeEntry(dir, path, check, result.diagnostics);
  return result;
}

}  // namespace rgraph
