// The pass registry: every pass type the config may name. Built-in passes
// register themselves at static-initialisation time with RGRAPH_REGISTER_PASS;
// plugins register through the entry point the plugin loader calls.
//
// One registry per user, never a shared one: a Renderer, each
// rgraph::testing::compileFile/compileText call and the command line work on
// their own copy of builtins(), with the types the application adds
// (RendererOptions::registry, testing::Options::registry) and the plugins
// their pipelines load on top. builtins() itself holds the built-in types
// only and cannot be changed, so nothing one renderer or one test loads or
// adds is seen by another (docs/writing-a-pass.md, "Pass types of your own").
//
//   PassRegistry types = PassRegistry::builtins();   // a copy
//   types.add(makeOutlinePassType());                // your own, in-process
//   RendererOptions options;
//   options.registry = &types;                       // copied by the renderer
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "rgraph/pass.h"

namespace rgraph {

class PassRegistry {
 public:
  // Adds a type. Returns false (and sets *error) on a duplicate name or an
  // inconsistent declaration (duplicate slot/param, default out of range).
  bool add(PassTypeDesc desc, std::string* error = nullptr);
  const PassTypeDesc* find(std::string_view name) const;
  std::vector<const PassTypeDesc*> all() const;  // sorted by name
  // Closest registered name within a small edit distance, or "".
  std::string suggest(std::string_view name) const;

  // The built-in pass types, complete once librgraph is loaded and never
  // changed afterwards (read-only: copy it to add types of your own).
  static const PassRegistry& builtins();
  // Built-in types that failed to register (a bug in rgraph itself); the CLI
  // prints these instead of aborting during static initialisation.
  static std::vector<std::string>& builtinErrors();

 private:
  friend struct PassRegistrar;
  static PassRegistry& mutableBuiltins();  // RGRAPH_REGISTER_PASS only
  std::map<std::string, PassTypeDesc, std::less<>> types_;
};

struct PassRegistrar {
  explicit PassRegistrar(PassTypeDesc (*make)());
};

}  // namespace rgraph

#define RGRAPH_CONCAT_INNER(a, b) a##b
#define RGRAPH_CONCAT(a, b) RGRAPH_CONCAT_INNER(a, b)
// In a pass folder's .cpp: RGRAPH_REGISTER_PASS(makeMyPassType);
#define RGRAPH_REGISTER_PASS(fn) \
  static const ::rgraph::PassRegistrar RGRAPH_CONCAT(rgraph_registrar_, __LINE__){fn}
