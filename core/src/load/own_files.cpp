// rgraph's own folders, found from where its code was loaded (own_files.h).
#include "rgraph/own_files.h"

#include <dlfcn.h>
#include <link.h>

#include <filesystem>
#include <fstream>
#include <spdlog/spdlog.h>

// From <libdir> to <prefix>/share/rgraph in the install (core/CMakeLists.txt).
#ifndef RGRAPH_SHARE_FROM_LIBDIR
#define RGRAPH_SHARE_FROM_LIBDIR "../share/rgraph"
#endif

namespace fs = std::filesystem;

namespace rgraph {

const char* const kBuildTreeMarker = "rgraph-build-tree.txt";

namespace {

// The file this code is in: librgraph.so, or the program linking it statically
// (for the program dladdr gives argv[0], which may be a bare name: its link
// map entry has no name then, and /proc/self/exe is the file).
fs::path codeFile() {
  Dl_info info{};
  struct link_map* map = nullptr;
  static const int anchor = 0;
  if (!dladdr1(static_cast<const void*>(&anchor), &info, reinterpret_cast<void**>(&map), RTLD_DL_LINKMAP)) return {};
  std::error_code ec;
  fs::path p;
  if (map && map->l_name && *map->l_name)
    p = fs::absolute(map->l_name, ec);
  else
    p = fs::read_symlink("/proc/self/exe", ec);
  if (ec || p.empty()) return {};
  fs::path canon = fs::weakly_canonical(p, ec);  // symlinks resolved: the real file's folder
  return ec ? p.lexically_normal() : canon;
}

std::string normal(const fs::path& p) { return p.lexically_normal().string(); }

// Reads the build tree's marker; false when there is none.
bool readMarker(const fs::path& marker, OwnFiles& out) {
  std::ifstream in(marker);
  if (!in) return false;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t eq = line.find('=');
    if (line.empty() || line[0] == '#' || eq == std::string::npos) continue;
    const std::string key = line.substr(0, eq), value = line.substr(eq + 1);
    if (key == "shaders") out.shaders = normal(value);
    if (key == "pipelines") out.pipelines = normal(value);
  }
  return true;
}

OwnFiles find() {
  const fs::path code = codeFile();
  if (code.empty()) {
    spdlog::warn("rgraph cannot tell which file its code was loaded from: no built-in shaders or pipelines");
    return {};
  }
  OwnFiles out = ownFilesBeside(code.string());
  spdlog::debug("rgraph's own files ({} {}): shaders {}, pipelines {}, plugins {}",
                out.buildTree ? "a build tree, per the marker beside" : "an install, relative to", out.codeFile,
                out.shaders, out.pipelines, out.plugins);
  return out;
}

}  // namespace

OwnFiles ownFilesBeside(const std::string& file) {
  OwnFiles out;
  out.codeFile = file;
  const fs::path dir = fs::path(file).parent_path();
  out.plugins = normal(dir / "rgraph" / "plugins");
  out.buildTree = readMarker(dir / kBuildTreeMarker, out);
  if (!out.buildTree) {
    const fs::path share = dir / RGRAPH_SHARE_FROM_LIBDIR;
    out.shaders = normal(share / "shaders");
    out.pipelines = normal(share / "pipelines");
  }
  return out;
}

const OwnFiles& ownFiles() {
  static const OwnFiles files = find();
  return files;
}

}  // namespace rgraph
