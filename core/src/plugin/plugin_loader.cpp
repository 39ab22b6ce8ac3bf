// The plugin loader: finds plugin libraries, checks their ABI version before
// calling anything else, and registers their pass types all or nothing.
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <filesystem>
#include <spdlog/spdlog.h>

#include "rgraph/own_files.h"
#include "rgraph/plugin.h"
#include "rgraph/plugin_file_check.h"
#include "rgraph/registry.h"
#include "rgraph/shader_check.h"

#ifndef RGRAPH_PLUGIN_INSTALL_RELDIR
#define RGRAPH_PLUGIN_INSTALL_RELDIR "lib/rgraph/plugins"
#endif

namespace fs = std::filesystem;

namespace rgraph {
namespace {

std::vector<std::string> splitPath(const char* s) {
  std::vector<std::string> out;
  if (!s) return out;
  std::string v = s;
  size_t start = 0;
  while (start <= v.size()) {
    size_t end = v.find(':', start);
    if (end == std::string::npos) end = v.size();
    if (end > start) out.push_back(v.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

bool isFile(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

bool isDir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

std::string normal(const fs::path& p) {
  std::error_code ec;
  fs::path abs = p.is_absolute() ? p : fs::absolute(p, ec);
  fs::path canon = fs::weakly_canonical(abs, ec);
  return (ec ? abs.lexically_normal() : canon).string();
}

fs::path executableDir() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path{} : exe.parent_path();
}

// "librgraph_bloom.so" -> "bloom", "libfoo.so" -> "foo", "bar.so" -> "bar".
std::string nameFromFile(const std::string& path) {
  std::string stem = fs::path(path).filename().string();
  if (auto so = stem.find(".so"); so != std::string::npos) stem = stem.substr(0, so);
  for (const char* prefix : {"librgraph_", "lib"})
    if (stem.rfind(prefix, 0) == 0 && stem.size() > std::string(prefix).size()) return stem.substr(std::string(prefix).size());
  return stem;
}

bool isPathLike(const std::string& s) { return s.find('/') != std::string::npos; }

std::vector<std::string> candidateFiles(const std::string& name) {
  if (name.size() > 3 && name.compare(name.size() - 3, 3, ".so") == 0) return {name};
  return {"librgraph_" + name + ".so", name + ".so"};
}

class Host final : public PluginHost {
 public:
  Host(const PassRegistry& target, std::string path) : target_(target), path_(std::move(path)), name_(nameFromFile(path_)) {}

  uint32_t abiVersion() const override { return RGRAPH_PLUGIN_ABI_VERSION; }
  const std::string& pluginPath() const override { return path_; }
  void setPluginName(const std::string& name) override {
    if (!name.empty()) name_ = name;
  }
  const std::string& pluginName() const override { return name_; }

  std::string shaderDirectory() const override {
    const fs::path dir = fs::path(path_).parent_path();
    fs::path a = dir;
    for (int up = 0; up < 5 && !a.empty(); ++up) {
      fs::path candidate = a / "share" / "rgraph" / "plugins" / name_;
      if (isDir(candidate)) return candidate.lexically_normal().string();
      if (a == a.parent_path()) break;
      a = a.parent_path();
    }
    if (isDir(dir / name_)) return (dir / name_).lexically_normal().string();
    return {};
  }

  std::string shaderPath(const std::string& file) const override {
    const std::string dir = shaderDirectory();
    if (!dir.empty() && isFile(fs::path(dir) / file)) return (fs::path(dir) / file).lexically_normal().string();
    return file;
  }

  bool addPassType(PassTypeDesc desc) override {
    desc.origin = path_;
    if (const PassTypeDesc* existing = target_.find(desc.name)) {
      // This very library registered it there already (through another
      // loader: a registry copied after a load, like a renderer's copy of the
      // application's types): the same code, nothing to add or refuse.
      if (existing->origin == path_) {
        present_.push_back(desc.name);
        return true;
      }
      fail("pass type '" + desc.name + "' is already registered (from " + existing->origin + ")");
      return false;
    }
    std::string error;
    if (!scratch_.add(desc, &error)) {
      fail(error);
      return false;
    }
    types_.push_back(std::move(desc));
    return true;
  }

  void fail(const std::string& reason) override { errors_.push_back(reason); }
  bool failed() const override { return !errors_.empty(); }

  std::vector<PassTypeDesc>& types() { return types_; }
  // The types the registry had from this library already (addPassType).
  const std::vector<std::string>& present() const { return present_; }
  const std::vector<std::string>& errors() const { return errors_; }

 private:
  const PassRegistry& target_;
  PassRegistry scratch_;  // checks the plugin's own declarations (and duplicates among them)
  std::string path_, name_;
  std::vector<PassTypeDesc> types_;
  std::vector<std::string> present_;
  std::vector<std::string> errors_;
};

// A name as it can be shown on one line: control characters (a NUL from a
// config's "\u0000") written the way JSON writes them.
std::string shown(const std::string& s) {
  std::string out;
  for (unsigned char c : s) {
    if (c >= 0x20 && c != 0x7f) {
      out += char(c);
      continue;
    }
    char buf[8];
    std::snprintf(buf, sizeof buf, "\\u%04x", c);
    out += buf;
  }
  return out;
}

// The C library stops at a NUL: "bloom\0x" would look up "librgraph_bloom"
// and report a file that exists as missing. Refuse such a name outright.
std::string nulByteError(const std::string& nameOrPath) {
  const size_t at = nameOrPath.find('\0');
  if (at == std::string::npos) return {};
  return "plugin '" + shown(nameOrPath) + "': the name contains a NUL byte (character " + std::to_string(at + 1) +
         "); a plugin name or path cannot contain one";
}

std::string joined(const std::vector<std::string>& v, const char* sep) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

}  // namespace

PluginLoader::PluginLoader(PassRegistry& registry) : registry_(registry) {}

// Handles are deliberately not closed: factories in the registry and pass
// instances run code from the libraries until the process exits.
PluginLoader::~PluginLoader() = default;

void PluginLoader::addSearchDirectory(const std::string& dir) {
  // Front ends add their folders on every load: keep each once.
  if (!dir.empty() && std::find(dirs_.begin(), dirs_.end(), dir) == dirs_.end()) dirs_.push_back(dir);
}

std::vector<std::string> PluginLoader::searchDirectories() const {
  std::vector<std::string> out;
  auto add = [&](const fs::path& p) {
    if (p.empty()) return;
    std::string s = normal(p);
    for (const auto& o : out)
      if (o == s) return;
    out.push_back(s);
  };
  for (const auto& d : dirs_) add(d);
  for (const auto& d : splitPath(std::getenv("RGRAPH_PLUGIN_PATH"))) add(d);
  // rgraph's own plugin folder, found from where the running code is: beside
  // librgraph.so, then relative to the executable. A build tree has the
  // install's layout (<build>/lib/rgraph/plugins), so this one rule serves
  // both. No folder is baked in at build time: an installed rgraph must never
  // load stale plugins from the build tree it was built in, or from the
  // prefix it was configured for when it was installed elsewhere.
  add(ownFiles().plugins);  // <libdir>/rgraph/plugins beside librgraph.so (rgraph/own_files.h)
  if (fs::path exe = executableDir(); !exe.empty()) add(exe / ".." / RGRAPH_PLUGIN_INSTALL_RELDIR);
  return out;
}

std::string PluginLoader::find(const std::string& nameOrPath, const std::string& baseDir) const {
  if (nameOrPath.empty()) return {};
  if (isPathLike(nameOrPath)) {
    fs::path p(nameOrPath);
    if (p.is_relative() && !baseDir.empty()) p = fs::path(baseDir) / p;
    return isFile(p) ? normal(p) : std::string();
  }
  for (const auto& dir : searchDirectories())
    for (const auto& file : candidateFiles(nameOrPath))
      if (isFile(fs::path(dir) / file)) return normal(fs::path(dir) / file);
  return {};
}

const LoadedPlugin* PluginLoader::load(const std::string& nameOrPath, const std::string& baseDir, std::string& error) {
  error.clear();
  if (nameOrPath.empty()) {
    error = "plugin '': empty plugin name";
    return nullptr;
  }
  if (error = nulByteError(nameOrPath); !error.empty()) return nullptr;
  if (!isPathLike(nameOrPath))
    spdlog::debug("plugin '{}': search path {}", nameOrPath, joined(searchDirectories(), ":"));
  const std::string file = find(nameOrPath, baseDir);
  if (file.empty()) {
    if (isPathLike(nameOrPath)) {
      fs::path p(nameOrPath);
      if (p.is_relative() && !baseDir.empty()) p = fs::path(baseDir) / p;
      error = "plugin '" + nameOrPath + "': file not found: " + p.lexically_normal().string();
    } else {
      error = "plugin '" + nameOrPath + "': not found (looked for " + joined(candidateFiles(nameOrPath), ", ") +
              " in " + joined(searchDirectories(), ", ") + "; add a folder with --plugin-path or RGRAPH_PLUGIN_PATH)";
    }
    return nullptr;
  }
  return loadFile(file, error, nameOrPath);
}

namespace {
// The file check, dlopen and the ABI check: the library's registration entry
// point, or nullptr with `error` set (starting with `label`).
rgraph_plugin_register_fn openPlugin(const std::string& path, const std::string& label, std::string& error) {
  // dlopen maps the file and reads it through the mapping: a file cut short
  // inside a segment kills the process with SIGBUS there. Check it first.
  if (std::string why = checkPluginFile(path); !why.empty()) {
    error = label + ": not a loadable plugin: " + why;
    return nullptr;
  }

  dlerror();
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    error = label + ": cannot load the library: " + (why ? why : "dlopen failed");
    return nullptr;
  }
  // From here on the handle stays open even when the plugin is refused: its
  // static initialisers have run and may have left pointers behind.

  dlerror();
  auto abi = reinterpret_cast<rgraph_plugin_abi_version_fn>(dlsym(handle, RGRAPH_PLUGIN_ABI_SYMBOL));
  if (!abi) {
    error = label + ": not an rgraph plugin: no entry point '" RGRAPH_PLUGIN_ABI_SYMBOL
                    "' (define it with RGRAPH_PLUGIN in rgraph/plugin.h)";
    return nullptr;
  }
  const uint32_t found = abi();
  if (found != RGRAPH_PLUGIN_ABI_VERSION) {
    error = label + ": ABI version mismatch: expected " + std::to_string(RGRAPH_PLUGIN_ABI_VERSION) + ", found " +
            std::to_string(found) + " (rebuild the plugin against this rgraph)";
    return nullptr;
  }
  auto reg = reinterpret_cast<rgraph_plugin_register_fn>(dlsym(handle, RGRAPH_PLUGIN_REGISTER_SYMBOL));
  if (!reg) {
    error = label + ": not an rgraph plugin: no entry point '" RGRAPH_PLUGIN_REGISTER_SYMBOL
                    "' (define it with RGRAPH_PLUGIN in rgraph/plugin.h)";
    return nullptr;
  }
  return reg;
}
}  // namespace

std::optional<PluginLoader::Provider> PluginLoader::findProvider(const std::string& type) const {
  for (const auto& dir : searchDirectories()) {
    std::error_code ec;
    std::vector<std::string> files;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
      const std::string file = it->path().filename().string();
      if (file.rfind("librgraph_", 0) == 0 && file.size() > 3 && file.compare(file.size() - 3, 3, ".so") == 0)
        files.push_back(normal(it->path()));
    }
    std::sort(files.begin(), files.end());
    for (const auto& path : files) {
      const bool loaded = std::any_of(loaded_.begin(), loaded_.end(), [&](const LoadedPlugin& p) { return p.path == path; });
      if (loaded || !isFile(path)) continue;
      auto [probe, fresh] = probed_.try_emplace(path);
      if (fresh) {
        std::string error;
        if (rgraph_plugin_register_fn reg = openPlugin(path, "plugin " + path, error)) {
          const PassRegistry none;
          Host host(none, path);
          if (reg(&host) == 0 && !host.failed())
            for (const auto& desc : host.types()) probe->second.push_back(desc.name);
        }
        spdlog::debug("probed {} for pass types: {}", path, error.empty() ? joined(probe->second, ", ") : error);
      }
      if (std::find(probe->second.begin(), probe->second.end(), type) == probe->second.end()) continue;
      const std::string name = nameFromFile(path);
      return Provider{find(name) == path ? name : path, path};
    }
  }
  return std::nullopt;
}

const LoadedPlugin* PluginLoader::loadFile(const std::string& pathIn, std::string& error, const std::string& displayName) {
  if (error = nulByteError(pathIn); !error.empty()) return nullptr;
  const std::string path = normal(pathIn);
  const std::string label =
      "plugin '" + (displayName.empty() ? nameFromFile(path) : displayName) + "' (" + path + ")";
  for (const auto& p : loaded_)
    if (p.path == path) return &p;
  if (!isFile(path)) {
    error = label + ": file not found";
    return nullptr;
  }
  rgraph_plugin_register_fn reg = openPlugin(path, label, error);
  if (!reg) return nullptr;

  Host host(registry_, path);
  const int rc = reg(&host);
  if (rc != 0 || host.failed()) {
    std::string why = host.errors().empty() ? "rgraph_plugin_register returned " + std::to_string(rc)
                                            : joined(host.errors(), "; ");
    error = label + ": registration failed: " + why;
    return nullptr;
  }

  LoadedPlugin loaded;
  loaded.name = host.pluginName();
  loaded.path = path;
  for (auto& desc : host.types()) {
    std::string name = desc.name, why;
    if (!registry_.add(std::move(desc), &why)) {
      // Checked in addPassType; only a registry changed under our feet gets here.
      error = label + ": registration failed: " + why;
      return nullptr;
    }
    loaded.passTypes.push_back(std::move(name));
  }
  for (const auto& name : host.present()) loaded.passTypes.push_back(name);
  spdlog::debug("loaded plugin '{}' from {} ({} pass types)", loaded.name, path, loaded.passTypes.size());
  // Its shaders are read from its own folder: make that a shader folder.
  addPluginShaderDirectory(host.shaderDirectory());
  loaded_.push_back(std::move(loaded));
  return &loaded_.back();
}

}  // namespace rgraph
