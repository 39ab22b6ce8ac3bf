// rgraph/testing.h: every compile has its own pass types (a copy of
// Options::registry or of the built-ins) and loads its config's plugins into
// that copy alone. A plugin one test loads is not registered for the next,
// and a test's own in-process type may share a plugin type's name: these
// tests pass in any order and repeated (--gtest_shuffle --gtest_repeat=3),
// which with one process-wide registry they did not ("already registered").
#include <gtest/gtest.h>

#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"
#include "rgraph/testing.h"

namespace rt = rgraph::testing;
using namespace rgraph;

namespace {

class NoopPass : public PassInstance {
 public:
  void execute(PassContext&) override {}
};

// A test's own pass type named like the fxaa plugin's, with other slots (src, dst).
PassRegistry typesWithOwnFxaa() {
  PassRegistry r = PassRegistry::builtins();
  PassTypeDesc d = decl::passType("fxaa", "the test's own, not the plugin's");
  d.slots = {decl::slot("src", Access::sampled, true, SlotDecl::Load::never, "the image"),
             decl::slot("dst", Access::color_attachment, true, SlotDecl::Load::never, "the result")};
  d.create = [] { return std::make_unique<NoopPass>(); };
  std::string error;
  EXPECT_TRUE(r.add(std::move(d), &error)) << error;
  return r;
}

const char* kWithPlugin = R"({
  "version": 1,
  "plugins": ["fxaa"],
  "resources": { "ldr": { "format": "rgba8", "imported": true }, "output": { "format": "rgba8" } },
  "passes": [ { "name": "aa", "type": "fxaa", "inputs": { "input": "ldr" }, "outputs": { "output": "output" } } ],
  "output": "output"
})";

const char* kOwnType = R"({
  "version": 1,
  "resources": { "a": { "format": "rgba8", "imported": true }, "output": { "format": "rgba8" } },
  "passes": [ { "name": "aa", "type": "fxaa", "inputs": { "src": "a" }, "outputs": { "dst": "output" } } ],
  "output": "output"
})";

}  // namespace

TEST(TestingOwnTypes, APluginLoadedByOneCompileIsNotRegisteredForTheNext) {
  const rt::CompiledPipeline withPlugin = rt::compileText(kWithPlugin, {}, "with-plugin.json");
  EXPECT_TRUE(withPlugin.loaded()) << withPlugin.describe();
  EXPECT_FALSE(withPlugin.hasError(DiagCode::unknown_pass_type)) << withPlugin.describe();
  EXPECT_EQ(PassRegistry::builtins().find("fxaa"), nullptr) << "the built-in types are never changed";

  // The same type without the plugin entry: unknown again (and the plugin is suggested).
  std::string text = kWithPlugin;
  text.erase(text.find("\"plugins\": [\"fxaa\"],"), std::string("\"plugins\": [\"fxaa\"],").size());
  const rt::CompiledPipeline without = rt::compileText(text, {}, "without.json");
  EXPECT_TRUE(without.hasError(DiagCode::unknown_pass_type)) << without.describe();
  EXPECT_TRUE(without.hasMessage("plugin \"fxaa\"")) << without.describe();
}

TEST(TestingOwnTypes, AnInProcessTypeMaySharePluginTypesName) {
  const PassRegistry types = typesWithOwnFxaa();
  rt::Options o;
  o.size = {16, 16};
  o.registry = &types;
  const rt::CompiledPipeline own = rt::compileText(kOwnType, o, "own.json");
  ASSERT_TRUE(own.ok()) << own.describe();
  EXPECT_EQ(own.order(), (std::vector<std::string>{"aa"}));
  EXPECT_EQ(own.binding("aa", "src").value_or(rt::Binding{}).resource, "a");
  // The plugin's fxaa in the same compile clashes: one registry, one type of a name.
  const rt::CompiledPipeline both = rt::compileText(kWithPlugin, o, "both.json");
  EXPECT_TRUE(both.hasError(DiagCode::plugin_error)) << both.describe();
  EXPECT_TRUE(both.hasMessage("pass type 'fxaa' is already registered")) << both.describe();
  EXPECT_EQ(types.find("fxaa")->description, "the test's own, not the plugin's") << "the caller's registry is copied";
}

TEST(TestingOwnTypes, ThePluginsTypeWithoutTheTestsOwn) {
  const rt::CompiledPipeline p = rt::compileText(kWithPlugin, {}, "plugin.json");
  EXPECT_FALSE(p.hasError(DiagCode::plugin_error)) << p.describe();
  EXPECT_FALSE(p.hasError(DiagCode::unknown_pass_type)) << p.describe();
}
