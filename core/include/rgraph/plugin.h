// Pass plugins: shared libraries that add pass types at run time.
//
// A plugin exports two C functions, both defined by RGRAPH_PLUGIN:
//
//   extern "C" uint32_t rgraph_plugin_abi_version(void);          // RGRAPH_PLUGIN_ABI_VERSION it was built with
//   extern "C" int rgraph_plugin_register(rgraph::PluginHost* h);  // 0 on success
//
// The loader (PluginLoader) dlopens the library, reads the ABI version and
// refuses the plugin unless it equals its own RGRAPH_PLUGIN_ABI_VERSION; only
// then it calls rgraph_plugin_register, which registers pass types through
// the host. Registration is all or nothing: when any type is refused
// (duplicate name, bad declaration) or the entry point fails, none of the
// plugin's types is added.
//
// A plugin, in full:
//
//   #include "rgraph/plugin.h"
//   namespace {
//   class MyPass final : public rgraph::gl::FullscreenPass { ... };   // rgraph/gl/fullscreen.h
//   void registerTypes(rgraph::PluginHost& host) {
//     rgraph::PassTypeDesc d;
//     d.name = "my_pass";
//     ...
//     // fullscreen.vert + the plugin's shader (absolute path in its shader
//     // folder), its sampler u_src reading slot "src" on unit 0
//     d.programs = rgraph::gl::fullscreenPrograms(host.shaderPath("my_pass.frag"), {{"src", "u_src", 0}});
//     d.create = [] { return std::make_unique<MyPass>(); };
//     host.addPassType(std::move(d));
//   }
//   }  // namespace
//   RGRAPH_PLUGIN("my_plugin", registerTypes)
//
// Do not use RGRAPH_REGISTER_PASS in a plugin: it registers into the built-in
// registry at load time, before the ABI check, without the plugin's origin.
// See docs/writing-a-pass.md.
#pragma once

#include <cstdint>
#include <deque>
#include <exception>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rgraph/pass.h"

// The plugin ABI version. Bumped whenever a type or function a plugin
// compiles against changes in a way that breaks already-built plugins
// (PassTypeDesc, SlotDecl, ParamDecl, ParamSet, PassInstance, PassContext,
// PluginHost, ShaderLibrary, the gl/ helpers) or the entry points change.
// 2: PassTypeDesc::programs is the one program list (the executor builds it,
// PassContext::program, `shaders` removed, sampler units mandatory),
// PassTypeDesc::check and needsScene, gl::FullscreenPass and gl::Uniform.
// 3: PassContext::historyValid and frameIndex (history resources), the Frame
// block's motion and jitter members, GpuScene::updateFrame with FrameMotion.
// 4: CheckedSlot::kind and bufferBytes (check hooks see a buffer's size);
// PassTypeDesc::rules (PassRule: a check with the sentence `rgraph passes` prints);
// PassInstance::changedState, PassContext::emptyVertexArray and bindings().
// 5: PassContext::framebuffer(attachments) and texture(slot, sub) (the
// executor's framebuffer cache and texture views), gl::bindPassFramebuffer
// with attachments; textures of every shape (layers, cubes).
// 6: CheckedSlot::mips (check hooks see the mip levels a binding covers),
// PassCheckContext::writer (the pass that wrote a read version: cross-pass
// rules), rgraph/format_sets.h.
// 7: SceneFeatures's shadow facts (shadowCasters, shadowLights,
// unshadowedLights), PassAdaptation::expand and ::reshape (ExpandedPass).
// 8: SceneFeatures's light-marker facts (lightMarkers, markerSizeLimit), emissive and
// reflectance (optional G-buffer targets), environment (image-based lighting),
// PointLight::marker.
#define RGRAPH_PLUGIN_ABI_VERSION 8u

#define RGRAPH_PLUGIN_ABI_SYMBOL "rgraph_plugin_abi_version"
#define RGRAPH_PLUGIN_REGISTER_SYMBOL "rgraph_plugin_register"

namespace rgraph {

inline constexpr uint32_t kPluginAbiVersion = RGRAPH_PLUGIN_ABI_VERSION;

// What the loader hands to a plugin's entry point.
class PluginHost {
 public:
  virtual ~PluginHost() = default;

  // The ABI version of the rgraph that loads the plugin.
  virtual uint32_t abiVersion() const = 0;
  // Absolute path of the plugin library (the `origin` of its pass types).
  virtual const std::string& pluginPath() const = 0;

  // Set by RGRAPH_PLUGIN before the plugin's function runs: the plugin's name
  // names its data folder (shaders), see shaderDirectory().
  virtual void setPluginName(const std::string& name) = 0;
  virtual const std::string& pluginName() const = 0;

  // The folder holding the plugin's shaders, or "" when there is none:
  // the first that exists of
  //   <ancestor of the library's folder>/share/rgraph/plugins/<name>
  //       (an install: <prefix>/lib/rgraph/plugins/librgraph_<name>.so ->
  //        <prefix>/share/rgraph/plugins/<name>; a build tree mirrors it),
  //   <library's folder>/<name>.
  virtual std::string shaderDirectory() const = 0;
  // Absolute path of `file` in shaderDirectory(); `file` unchanged when that
  // folder does not have it (it is then looked up in the ShaderLibrary's
  // search path like a built-in shader).
  virtual std::string shaderPath(const std::string& file) const = 0;

  // Registers a pass type (origin set to pluginPath()). Returns false when the
  // type is refused (duplicate name, inconsistent declaration); the reason is
  // recorded and the whole plugin is refused.
  virtual bool addPassType(PassTypeDesc desc) = 0;
  // Refuses the plugin with a reason (e.g. a missing resource of its own).
  virtual void fail(const std::string& reason) = 0;
  virtual bool failed() const = 0;
};

namespace detail {
// The body of rgraph_plugin_register: no exception crosses the C boundary.
inline int runPluginRegister(PluginHost* host, const char* name, void (*fn)(PluginHost&)) {
  if (!host) return 1;
  try {
    host->setPluginName(name);
    fn(*host);
  } catch (const std::exception& e) {
    host->fail(std::string("registration threw: ") + e.what());
  } catch (...) {
    host->fail("registration threw an unknown exception");
  }
  return host->failed() ? 1 : 0;
}
}  // namespace detail

}  // namespace rgraph

extern "C" {
typedef uint32_t (*rgraph_plugin_abi_version_fn)(void);
typedef int (*rgraph_plugin_register_fn)(rgraph::PluginHost* host);
}

#define RGRAPH_PLUGIN_EXPORT extern "C" __attribute__((visibility("default")))

// Defines both entry points. NAME: the plugin's name (a string literal, e.g.
// "bloom"); REGISTER_FN: void fn(rgraph::PluginHost&), which registers the
// plugin's pass types with host.addPassType. Use once per plugin, at global
// scope.
#define RGRAPH_PLUGIN(NAME, REGISTER_FN)                                                  \
  RGRAPH_PLUGIN_EXPORT uint32_t rgraph_plugin_abi_version(void) {                         \
    return RGRAPH_PLUGIN_ABI_VERSION;                                                     \
  }                                                                                       \
  RGRAPH_PLUGIN_EXPORT int rgraph_plugin_register(::rgraph::PluginHost* host) {           \
    return ::rgraph::detail::runPluginRegister(host, NAME, REGISTER_FN);                  \
  }

namespace rgraph {

class PassRegistry;

// One loaded plugin.
struct LoadedPlugin {
  std::string name;          // as the plugin names itself (RGRAPH_PLUGIN)
  std::string path;          // absolute path of the library
  std::vector<std::string> passTypes;  // the types it registered
};

// Finds, loads and registers plugins into one registry. Libraries stay loaded
// for the rest of the process (pass instances and factories run their code),
// even after the loader is destroyed.
//
// A plugin is named either by a path (anything containing '/', or an
// absolute path; relative paths are relative to `baseDir`, e.g. the config
// file's folder) or by a name, looked up as librgraph_<name>.so, then
// <name>.so (a name ending in ".so" is looked up as is) in, in order:
//   1. directories given to addSearchDirectory (e.g. --plugin-path), in order;
//   2. $RGRAPH_PLUGIN_PATH (':'-separated);
//   3. rgraph's own plugin folder: <libdir>/rgraph/plugins beside
//      librgraph.so, and <exe>/../<libdir>/rgraph/plugins. A build tree has
//      the install's layout (<build>/lib/rgraph/plugins), so the rgraph of a
//      build tree finds that tree's plugins and an installed one only its
//      prefix's: no folder is baked in at build time.
//
// Every failure is a one-line message naming the plugin and the reason:
// not found (with the folders searched), a name with a NUL byte, a file that
// is not a loadable library for this machine (checked before dlopen, see
// plugin_file_check.h: a truncated file would crash inside it), dlopen
// failure (dlerror), no entry point, ABI mismatch (expected vs found),
// refused registration.
class PluginLoader {
 public:
  explicit PluginLoader(PassRegistry& registry);
  ~PluginLoader();
  PluginLoader(const PluginLoader&) = delete;
  PluginLoader& operator=(const PluginLoader&) = delete;

  void addSearchDirectory(const std::string& dir);
  // Every folder searched for a plugin name, in order (existing or not).
  std::vector<std::string> searchDirectories() const;

  // The file a name or path refers to; "" when no file matches.
  std::string find(const std::string& nameOrPath, const std::string& baseDir = {}) const;

  // Finds, loads and registers. Loading the same file again is a no-op that
  // returns the same plugin. On failure returns nullptr and sets `error` to
  // one line, e.g.
  //   plugin 'bloom': not found (looked for librgraph_bloom.so, bloom.so in /a, /b)
  //   plugin 'x' (/p/librgraph_x.so): ABI version mismatch: expected 1, found 7 (rebuild the plugin ...)
  const LoadedPlugin* load(const std::string& nameOrPath, const std::string& baseDir, std::string& error);
  // Loads a library file (absolute, or relative to the working directory).
  const LoadedPlugin* loadFile(const std::string& path, std::string& error, const std::string& displayName = {});

  const std::deque<LoadedPlugin>& loaded() const { return loaded_; }

  // A plugin on the search path, not loaded, that provides pass type `type`:
  // what "unknown pass type" suggests adding to a config's "plugins". Every
  // librgraph_*.so in searchDirectories() is probed (once per loader) the way
  // loadFile loads it (file check, dlopen, ABI check) and its registration
  // runs into a scratch registry: its types never reach this loader's
  // registry. A file that fails any step is skipped (a damaged plugin on the
  // path costs nothing but its own suggestion). Libraries stay mapped, as
  // loaded ones do (their initialisers have run).
  struct Provider {
    std::string name;  // what a config's "plugins" names it by: its name, or its path when another file shadows it
    std::string path;  // the library
  };
  std::optional<Provider> findProvider(const std::string& type) const;

 private:
  PassRegistry& registry_;
  std::vector<std::string> dirs_;
  std::deque<LoadedPlugin> loaded_;  // stable addresses
  mutable std::map<std::string, std::vector<std::string>> probed_;  // library -> the types it registers
};

}  // namespace rgraph
