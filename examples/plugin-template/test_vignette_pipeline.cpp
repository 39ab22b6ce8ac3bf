// A unit test of this template's own pipeline (vignette.json) with
// rgraph/testing.h: it is compiled the way `rgraph validate` does it, with
// the plugin built next door, and no GL context. Build and run:
//   cmake --build build && ctest --test-dir build
#include <gtest/gtest.h>

#include "rgraph/hazard_check.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"
#include "rgraph/testing.h"

namespace rt = rgraph::testing;

namespace {

// The pipeline and where this build puts the plugin and where the installed
// rgraph keeps its shaders (both passed in by CMakeLists.txt).
rt::CompiledPipeline compileVignette() {
  rt::Options options;
  options.size = {64, 64};
  options.pluginDirectories = {VIGNETTE_PLUGIN_DIR};
  options.shaderChecks = true;  // glslang: the plugin's shader against its bindings
  options.shaderDirectories = {RGRAPH_SHADER_DIR};
  return rt::compileFile(VIGNETTE_PIPELINE, options);
}

}  // namespace

TEST(VignettePipeline, CompilesWithoutDiagnostics) {
  const rt::CompiledPipeline p = compileVignette();
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_TRUE(p.diagnostics().empty()) << p.describe();  // no warnings either
}

TEST(VignettePipeline, VignetteRunsLastAndIsNotCulled) {
  const rt::CompiledPipeline p = compileVignette();
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_EQ(p.order(), (std::vector<std::string>{"gbuffer", "lighting", "tonemap", "vignette"})) << p.describe();
  EXPECT_FALSE(p.culled("vignette")) << p.cullReason("vignette");
  EXPECT_TRUE(p.runsBefore("tonemap", "vignette"));
  // It reads the tone-mapped image and writes the output.
  EXPECT_EQ(p.binding("vignette", "src").value_or(rt::Binding{}).resource, "ldr");
  EXPECT_EQ(p.binding("vignette", "dst").value_or(rt::Binding{}).resource, p.outputResource());
}

TEST(VignettePipeline, Memory) {
  const rt::CompiledPipeline p = compileVignette();
  ASSERT_TRUE(p.ok()) << p.describe();
  // At 64x64: four rgba16f G-buffer targets and hdr (32 KiB each), depth32f
  // and ldr (16 KiB each); the output is imported. All are alive together
  // at the lighting pass, so nothing can share memory.
  EXPECT_EQ(p.naiveBytes(), 5u * 32768u + 2u * 16384u) << p.describe();
  EXPECT_EQ(p.allocatedBytes(), p.naiveBytes()) << p.describe();
  // The vignette adds only ldr, alive from tonemap to vignette.
  const auto ldr = p.lifetime("ldr");
  ASSERT_TRUE(ldr.has_value());
  EXPECT_EQ(ldr->firstPass, "tonemap");
  EXPECT_EQ(ldr->lastPass, "vignette");
}

// A pass type of the test's own, registered in-process under the plugin's
// type name. Each compile copies Options::registry (or the built-in types)
// and loads the config's plugins into its copy, so nothing one test registers
// or loads is seen by another: the tests above and this one pass in any order
// (CMakeLists.txt runs them shuffled, three times over).
TEST(VignettePipeline, AnInProcessTypeOfThePluginsNameStaysInItsTest) {
  using namespace rgraph;
  PassRegistry types = PassRegistry::builtins();  // a copy: the built-in types, then the test's own
  PassTypeDesc stub = decl::passType("vignette", "a stand-in declared by the test");
  stub.slots = {decl::slot("src", Access::sampled, true, SlotDecl::Load::never, "the image"),
                decl::slot("dst", Access::color_attachment, true, SlotDecl::Load::never, "the result")};
  stub.create = [] { return std::unique_ptr<PassInstance>(); };  // never called: nothing runs here
  std::string error;
  ASSERT_TRUE(types.add(std::move(stub), &error)) << error;
  rt::Options options;
  options.size = {64, 64};
  options.registry = &types;
  const rt::CompiledPipeline p = rt::compileText(R"({
    "version": 1,
    "resources": { "ldr": { "format": "rgba8", "imported": true }, "output": { "format": "rgba8" } },
    "passes": [ { "name": "v", "type": "vignette", "inputs": { "src": "ldr" }, "outputs": { "dst": "output" } } ],
    "output": "output"
  })", options, "stub.json");
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_EQ(p.order(), (std::vector<std::string>{"v"}));
  // The plugin's own vignette still loads for the next compile: no "already registered".
  EXPECT_TRUE(compileVignette().ok()) << compileVignette().describe();
}

// The hazard harness (docs/testing.md, "Hazard modes"): the pipeline rendered
// plainly and under each hazard mode (poisoned transients, no aliasing, other
// aliasing, other valid orders, hostile GL state before each pass, nothing
// culled) keeps the same images, bit for bit: the vignette reads only what the
// graph promises it and leaves no state behind. On a finding, describe() names
// the mode, the pass (with its line in vignette.json), the resource and the
// pixels. Renders in a headless GL context.
TEST(VignettePipeline, IsHazardFree) {
  rgraph::HazardCheckOptions options;
  options.size = {32, 32};
  options.frames = 2;
  options.renderer.pluginDirectories = {VIGNETTE_PLUGIN_DIR};
  const rgraph::HazardReport report = rt::expectHazardFree(VIGNETTE_PIPELINE, options);
  EXPECT_TRUE(report.hazardFree()) << report.describe();
}
