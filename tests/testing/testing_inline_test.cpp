// rgraph/testing.h on inline JSON: errors with their codes and locations,
// culling, aliasing, pass and shader checks, plugins, unknown names.
#include <gtest/gtest.h>

#include "rgraph/testing.h"

namespace rt = rgraph::testing;
using rgraph::DiagCode;

namespace {

rt::Options small() {
  rt::Options o;
  o.size = {64, 32};
  return o;
}

// A gradient, a chain of two inverts and a present; `extra` adds passes.
std::string chain(const std::string& extraResources = "", const std::string& extraPasses = "") {
  return R"({
  "version": 1,
  "resources": {
    "a": { "format": "rgba8" },
    "b": { "format": "rgba8" },
    "c": { "format": "rgba8" },)" +
         extraResources + R"(
    "output": { "format": "rgba8" }
  },
  "passes": [
    { "name": "fill", "type": "fullscreen", "params": { "shader": "gradient.frag" }, "outputs": { "color": "a" } },
    { "name": "inv1", "type": "fullscreen", "params": { "shader": "invert.frag" }, "inputs": { "input0": "a" }, "outputs": { "color": "b" } },
    { "name": "inv2", "type": "fullscreen", "params": { "shader": "invert.frag" }, "inputs": { "input0": "b" }, "outputs": { "color": "c" } },)" +
         extraPasses + R"(
    { "name": "show", "type": "present", "inputs": { "src": "c" }, "outputs": { "dst": "output" } }
  ],
  "output": "output"
})";
}

}  // namespace

TEST(TestingInline, ChainOrderLifetimesAliasingAndMemory) {
  const rt::CompiledPipeline p = rt::compileText(chain(), small());
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_EQ(p.source(), "<inline>");
  EXPECT_EQ(p.order(), (std::vector<std::string>{"fill", "inv1", "inv2", "show"}));
  // a lives over steps 0-1, c over 2-3: same descriptor, no overlap, one texture.
  EXPECT_EQ(p.lifetime("a").value().first, 0u);
  EXPECT_EQ(p.lifetime("a").value().last, 1u);
  EXPECT_EQ(p.lifetime("c").value().first, 2u);
  EXPECT_EQ(p.lifetime("c").value().lastPass, "show");
  EXPECT_TRUE(p.aliased("a", "c"));
  EXPECT_FALSE(p.aliased("a", "b"));
  EXPECT_EQ(p.aliasGroups(), (std::vector<std::vector<std::string>>{{"a", "c"}}));
  // rgba8 64x32 = 8192 bytes; three transients, two textures.
  EXPECT_EQ(p.bytes("a"), 8192u);
  EXPECT_EQ(p.naiveBytes(), 3u * 8192u);
  EXPECT_EQ(p.allocatedBytes(), 2u * 8192u);
  EXPECT_EQ(p.peakLiveBytes(), 2u * 8192u);  // two live at inv1 and at inv2
  const std::string d = p.describe();
  EXPECT_NE(d.find("pipeline <inline> at 64x32: ok (0 errors, 0 warnings)"), std::string::npos) << d;
  EXPECT_NE(d.find("order: fill -> inv1 -> inv2 -> show"), std::string::npos) << d;
  EXPECT_NE(d.find(": a, c\n"), std::string::npos) << d;
  EXPECT_NE(d.find("memory: naive 0.02 MiB (24576 bytes), allocated 0.02 MiB (16384 bytes), peak live 0.02 MiB "
                   "(16384 bytes)"),
            std::string::npos)
      << d;
  EXPECT_NE(p.describeResource("c").find("used from step 2 (inv2) to step 3 (show)"), std::string::npos)
      << p.describeResource("c");
  EXPECT_NE(p.describeResource("c").find("shared with a, c"), std::string::npos) << p.describeResource("c");
}

TEST(TestingInline, DisabledAndUnreadPassesAreCulledWithTheirReasons) {
  const std::string json = chain(R"(
    "side": { "format": "rgba8" },)",
                                 R"(
    { "name": "unread", "type": "fullscreen", "params": { "shader": "gradient.frag" }, "outputs": { "color": "side" } },
    { "name": "off", "type": "fullscreen", "enabled": false, "params": { "shader": "invert.frag" },
      "inputs": { "color": "c" }, "outputs": { "color": "c_off" } },)");
  const rt::CompiledPipeline p = rt::compileText(json, small());
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_EQ(p.culledPasses(), (std::vector<std::string>{"unread", "off"}));
  EXPECT_EQ(p.cullReason("off"), "disabled");
  EXPECT_EQ(p.cullReason("unread"), "its outputs (side) are never read by a pass that reaches the output");
  EXPECT_EQ(p.order(), (std::vector<std::string>{"fill", "inv1", "inv2", "show"}));
  EXPECT_FALSE(p.used("side"));
}

TEST(TestingInline, OutputAnIntermediateVersionCullsTheLaterWriter) {
  std::string json = chain("", R"(
    { "name": "tint", "type": "fullscreen", "params": { "shader": "invert.frag" },
      "inputs": { "color": "c" }, "outputs": { "color": "c_tinted" } },)");
  json.replace(json.find(R"("output": "output")"), 18, R"("output": "c")");
  const rt::CompiledPipeline p = rt::compileText(json, small());
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_EQ(p.outputResource(), "c");
  EXPECT_EQ(p.outputVersion(), "c");
  EXPECT_TRUE(p.culled("tint"));
  EXPECT_NE(p.cullReason("tint").find("a later version of 'c' than the output 'c'"), std::string::npos)
      << p.cullReason("tint");
}

TEST(TestingInline, GraphErrorHasCodeAndFileLineColumn) {
  std::string json = chain();
  json.replace(json.find(R"("src": "c")"), 10, R"("src": "cc")");
  const rt::CompiledPipeline p = rt::compileText(json, small(), "mine.json");
  EXPECT_FALSE(p.ok());
  ASSERT_TRUE(p.hasError(DiagCode::unknown_resource)) << p.describe();
  EXPECT_FALSE(p.hasError(DiagCode::cycle));
  EXPECT_TRUE(p.hasMessage("input 'src' reads 'cc'"));
  EXPECT_FALSE(p.hasMessage("no such text anywhere"));
  ASSERT_EQ(p.errors().size(), 1u) << p.describe();
  const rgraph::Diagnostic d = p.errors()[0];
  EXPECT_EQ(d.where.file, "mine.json");
  EXPECT_EQ(d.where.line, 13);  // the "show" pass's line in chain()
  EXPECT_EQ(d.where.path, "/passes/3/inputs/src");
  ASSERT_EQ(p.diagnosticLines().size(), 1u);
  EXPECT_EQ(p.diagnosticLines()[0].rfind("mine.json:13:" + std::to_string(d.where.column) +
                                             ": error: /passes/3/inputs/src: input 'src' reads 'cc'",
                                         0),
            0u)
      << p.diagnosticLines()[0];
  EXPECT_GT(d.where.column, 1);
  EXPECT_NE(p.describe().find("mine.json:13:"), std::string::npos) << p.describe();
}

TEST(TestingInline, ConfigErrorLeavesNothingLoaded) {
  const rt::CompiledPipeline p = rt::compileText(R"({ "version": 1, "resources": { "a": { "format": "rgba9" } },
  "passes": [], "output": "a" })",
                                                 small());
  EXPECT_FALSE(p.loaded());
  EXPECT_FALSE(p.ok());
  EXPECT_TRUE(p.hasError(DiagCode::format_not_allowed) || p.hasError(DiagCode::config_schema)) << p.describe();
  EXPECT_EQ(p.find(DiagCode::json_syntax), nullptr);
  // Every query answers "nothing", none crashes.
  EXPECT_TRUE(p.order().empty());
  EXPECT_TRUE(p.passes().empty());
  EXPECT_FALSE(p.hasResource("a"));
  EXPECT_EQ(p.outputResource(), "");
  EXPECT_EQ(p.naiveBytes(), 0u);
  EXPECT_NE(p.describe().find("not loaded"), std::string::npos) << p.describe();
  EXPECT_EQ(p.describePass("x"), "no pass named 'x': <inline> did not load (see its diagnostics)");
}

TEST(TestingInline, JsonSyntaxErrorAndMissingFile) {
  const rt::CompiledPipeline bad = rt::compileText("{ \"version\": 1,\n  \"passes\": [ }", small(), "broken.json");
  ASSERT_TRUE(bad.hasError(DiagCode::json_syntax)) << bad.describe();
  EXPECT_EQ(bad.find(DiagCode::json_syntax)->where.line, 2);
  EXPECT_EQ(bad.diagnosticLines()[0].rfind("broken.json:2:", 0), 0u) << bad.diagnosticLines()[0];

  const rt::CompiledPipeline missing = rt::compileFile("/nonexistent/pipeline.json", small());
  EXPECT_FALSE(missing.loaded());
  EXPECT_TRUE(missing.hasError(DiagCode::file_not_found)) << missing.describe();
  EXPECT_TRUE(missing.hasMessage("/nonexistent/pipeline.json"));
}

TEST(TestingInline, PassChecksRunUnlessTurnedOff) {
  // present refuses a depth image as its source (its own check hook).
  const std::string json = R"({
  "version": 1,
  "resources": { "d": { "format": "depth32f" }, "output": { "format": "rgba8" } },
  "passes": [
    { "name": "depth", "type": "fullscreen", "params": { "shader": "gradient.frag" },
      "outputs": { "color": "output_tmp", "depth": "d" } },
    { "name": "show", "type": "present", "inputs": { "src": "d" }, "outputs": { "dst": "output" } }
  ],
  "output": "output"
})";
  std::string withColour = json;
  withColour.replace(withColour.find(R"("d": { "format": "depth32f" },)"), 30,
                     R"("d": { "format": "depth32f" }, "output_tmp": { "format": "rgba8" },)");
  const rt::CompiledPipeline p = rt::compileText(withColour, small());
  ASSERT_TRUE(p.loaded()) << p.describe();
  ASSERT_TRUE(p.hasError(DiagCode::pass_check)) << p.describe();
  EXPECT_EQ(p.find(DiagCode::pass_check)->pass, "show");
  EXPECT_TRUE(p.hasMessage("present shows colour images"));
  rt::Options off = small();
  off.passChecks = false;
  const rt::CompiledPipeline q = rt::compileText(withColour, off);
  EXPECT_FALSE(q.hasDiagnostic(DiagCode::pass_check)) << q.describe();
}

TEST(TestingInline, ShaderChecksOnlyWhenAsked) {
  std::string json = chain();
  json.replace(json.find("gradient.frag"), 13, "no-such-shader.frag");
  const rt::CompiledPipeline plain = rt::compileText(json, small());
  EXPECT_FALSE(plain.hasDiagnostic(DiagCode::shader_error)) << plain.describe();
  rt::Options o = small();
  o.shaderChecks = true;
  const rt::CompiledPipeline checked = rt::compileText(json, o);
  ASSERT_TRUE(checked.hasError(DiagCode::shader_error)) << checked.describe();
  EXPECT_TRUE(checked.hasMessage("no-such-shader.frag")) << checked.describe();
  EXPECT_EQ(checked.find(DiagCode::shader_error)->pass, "fill");
}

TEST(TestingInline, MissingPluginIsAPluginErrorAtItsName) {
  std::string json = chain();
  json.replace(json.find(R"("version": 1,)"), 13, R"("version": 1, "plugins": ["no_such_plugin_xyz"],)");
  rt::Options o = small();
  o.pluginDirectories = {"/nonexistent/plugins"};
  const rt::CompiledPipeline p = rt::compileText(json, o, "plugins.json");
  EXPECT_FALSE(p.loaded());
  ASSERT_TRUE(p.hasError(DiagCode::plugin_error)) << p.describe();
  const rgraph::Diagnostic* d = p.find(DiagCode::plugin_error);
  EXPECT_EQ(d->where.path, "/plugins/0");
  EXPECT_EQ(d->where.line, 2);
  EXPECT_TRUE(p.hasMessage("/nonexistent/plugins")) << p.describe();  // the folder searched
}

TEST(TestingInline, UnknownNamesGetClearAnswers) {
  const rt::CompiledPipeline p = rt::compileText(chain(), small());
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_FALSE(p.hasPass("nope"));
  EXPECT_FALSE(p.runs("nope"));
  EXPECT_FALSE(p.culled("nope"));
  EXPECT_EQ(p.cullReason("nope"), "");
  EXPECT_FALSE(p.step("nope").has_value());
  EXPECT_FALSE(p.runsBefore("nope", "show"));
  EXPECT_TRUE(p.bindings("nope").empty());
  EXPECT_FALSE(p.binding("show", "nope").has_value());
  EXPECT_FALSE(p.binding("nope", "src").has_value());
  EXPECT_FALSE(p.hasResource("nope"));
  EXPECT_EQ(p.resourceOf("nope"), "");
  EXPECT_TRUE(p.versions("nope").empty());
  EXPECT_FALSE(p.lifetime("nope").has_value());
  EXPECT_FALSE(p.texture("nope").has_value());
  EXPECT_TRUE(p.sharing("nope").empty());
  EXPECT_FALSE(p.aliased("nope", "a"));
  EXPECT_EQ(p.extent("nope"), (rgraph::Extent{}));
  EXPECT_EQ(p.bytes("nope"), 0u);
  EXPECT_EQ(p.describePass("nope"), "no pass named 'nope' (passes: fill, inv1, inv2, show)");
  EXPECT_EQ(p.describeResource("nope"), "no resource or version named 'nope' (resources: a, b, c, output)");
}

TEST(TestingInline, MaxTextureSizeIsChecked) {
  rt::Options o;
  o.size = {4096, 4096};
  o.maxTextureSize = 2048;
  const rt::CompiledPipeline p = rt::compileText(chain(), o);
  EXPECT_TRUE(p.hasError(DiagCode::invalid_resource)) << p.describe();
  EXPECT_TRUE(p.hasMessage("rgraph::testing::Options::maxTextureSize")) << p.describe();
}

TEST(TestingInline, WarningsAreNotErrors) {
  // An output of its own fixed size: shown as it is, with a warning.
  std::string json = chain();
  const std::string output = R"("output": { "format": "rgba8" })";
  json.replace(json.find(output), output.size(), R"("output": { "format": "rgba8", "size": [16, 16] })");
  const rt::CompiledPipeline p = rt::compileText(json, small());
  EXPECT_TRUE(p.ok()) << p.describe();
  ASSERT_EQ(p.warnings().size(), 1u) << p.describe();
  EXPECT_TRUE(p.errors().empty());
  EXPECT_EQ(p.warnings()[0].code, DiagCode::output_size);
  EXPECT_TRUE(p.hasDiagnostic(DiagCode::output_size));
  EXPECT_FALSE(p.hasError(DiagCode::output_size));
  EXPECT_NE(p.describe().find("ok (0 errors, 1 warnings)"), std::string::npos) << p.describe();
  EXPECT_EQ(p.extent("output"), (rgraph::Extent{16, 16}));
}

// A plan with errors promises only one entry per pass and resource (graph.h):
// every query on every name still answers, from what the plan has.
TEST(TestingInline, CycleIsReportedAndEveryQueryStillAnswers) {
  const std::string json = R"({
  "version": 1,
  "resources": { "x": { "format": "rgba8" }, "y": { "format": "rgba8" }, "output": { "format": "rgba8" } },
  "passes": [
    { "name": "p1", "type": "fullscreen", "params": { "shader": "invert.frag" }, "inputs": { "input0": "y" }, "outputs": { "color": "x" } },
    { "name": "p2", "type": "fullscreen", "params": { "shader": "invert.frag" }, "inputs": { "input0": "x" }, "outputs": { "color": "y" } },
    { "name": "show", "type": "present", "inputs": { "src": "x" }, "outputs": { "dst": "output" } }
  ],
  "output": "output"
})";
  const rt::CompiledPipeline p = rt::compileText(json, small(), "cycle.json");
  ASSERT_TRUE(p.loaded()) << p.describe();
  EXPECT_FALSE(p.ok());
  ASSERT_TRUE(p.hasError(DiagCode::cycle)) << p.describe();
  EXPECT_EQ(p.find(DiagCode::cycle)->where.file, "cycle.json");
  EXPECT_EQ(p.passes(), (std::vector<std::string>{"p1", "p2", "show"}));
  for (const auto& pass : p.passes()) {
    EXPECT_FALSE(p.describePass(pass).empty());
    (void)p.bindings(pass);
    (void)p.step(pass);
  }
  for (const char* r : {"x", "y", "output"}) {
    EXPECT_TRUE(p.hasResource(r));
    EXPECT_FALSE(p.describeResource(r).empty());
    (void)p.lifetime(r);
    (void)p.texture(r);
  }
  EXPECT_NE(p.describe().find("cycle.json:"), std::string::npos) << p.describe();
}

// A mip chain in a user's test: the part each slot binds, and culling per level.
TEST(TestingInline, SubresourceBindingsAndPerLevelCulling) {
  const std::string text = R"({
  "version": 1,
  "resources": {
    "a": { "format": "rgba8", "mips": 3 },
    "output": { "format": "rgba8" }
  },
  "passes": [
    { "name": "fill", "type": "fullscreen", "params": { "shader": "gradient.frag" }, "outputs": { "color": "a.mip[0]" } },
    { "name": "half", "type": "fullscreen", "params": { "shader": "invert.frag" }, "inputs": { "input0": "a.mip[0]" }, "outputs": { "color": "a.mip[1]" } },
    { "name": "quarter", "type": "fullscreen", "params": { "shader": "invert.frag" }, "inputs": { "input0": "a.mip[1]" }, "outputs": { "color": "a.mip[2]" } },
    { "name": "show", "type": "present", "inputs": { "src": "a.mip[1]" }, "outputs": { "dst": "output" } }
  ],
  "output": "output"
})";
  rt::Options o = small();
  o.passChecks = false;  // present wants equal sizes; this test is about the plan
  const rt::CompiledPipeline p = rt::compileText(text, o);
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_EQ(p.order(), (std::vector<std::string>{"fill", "half", "show"}));
  EXPECT_EQ(p.culledPasses(), (std::vector<std::string>{"quarter"}));
  const auto src = p.binding("half", "input0");
  ASSERT_TRUE(src.has_value());
  EXPECT_EQ(src->resource, "a");
  EXPECT_EQ(src->readVersion, "a");
  EXPECT_EQ(src->sub, (rgraph::Subresource{0, 1, 0, 1}));
  EXPECT_EQ(p.binding("half", "color")->sub, (rgraph::Subresource{1, 1, 0, 1}));
  EXPECT_EQ(p.binding("show", "dst")->sub, (rgraph::Subresource{0, 1, 0, 1}));
}
