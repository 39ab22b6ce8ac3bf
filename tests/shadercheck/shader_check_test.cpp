// glslang shader checks without a GL context (rgraph/shader_check.h): compile
// errors located in the shader, fragment outputs vs colour attachments,
// samplers vs sampled inputs, and every shipped pipeline checked clean.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>

#include "rgraph/config.h"
#include "rgraph/registry.h"
#include "rgraph/shader_check.h"
#include "rgraph/pipeline_load.h"

#include "support/run_command.h"

namespace fs = std::filesystem;
using namespace rgraph;

namespace {

const std::string kData = std::string(RGRAPH_TEST_DATA_DIR) + "/shadercheck";
const std::string kTestShaders = kData + "/shaders";
const std::string kConfigs = kData + "/configs";

std::vector<std::string> testDirs() {
  std::vector<std::string> dirs = {kTestShaders};
  for (auto& d : defaultShaderSearchDirectories()) dirs.push_back(d);
  return dirs;
}

std::string all(const Diagnostics& diags) {
  std::string out;
  for (const auto& d : diags) out += formatDiagnostic(d) + "\n";
  return out;
}

size_t count(const Diagnostics& diags, Severity s) {
  return static_cast<size_t>(
      std::count_if(diags.begin(), diags.end(), [&](const Diagnostic& d) { return d.severity == s; }));
}

const Diagnostic* findContaining(const Diagnostics& diags, Severity s, const std::string& text) {
  for (const auto& d : diags)
    if (d.severity == s && d.message.find(text) != std::string::npos) return &d;
  return nullptr;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

const PassTypeDesc& type(const std::string& name) {
  const PassTypeDesc* t = processRegistry().find(name);
  if (!t) throw std::runtime_error("no pass type " + name);
  return *t;
}

BoundSlot slot(std::string name, Access access, std::string resource, std::optional<Format> format,
               uint32_t samples = 1) {
  BoundSlot b;
  b.slot = std::move(name);
  b.access = access;
  b.resource = std::move(resource);
  b.format = format;
  b.samples = samples;
  return b;
}

ParamSet fullscreenParams(const std::string& shader, const std::string& blend = "none") {
  ParamSet p = defaultParams(type("fullscreen").params);
  p.set("shader", shader);
  p.set("blend", blend);
  return p;
}

// Loads, builds and compiles a config against the built-in pass types, then
// runs the shader checks. The config's own diagnostics must be clean.
struct Checked {
  Diagnostics config;
  Diagnostics shaders;
};
Checked checkConfig(ShaderChecker& checker, const std::string& path) {
  Checked c;
  ConfigDocument doc = ConfigDocument::parseFile(path, c.config);
  if (!doc.ok()) return c;
  PipelineConfig pipe = doc.build(processRegistry(), c.config);
  if (hasErrors(c.config)) return c;
  Plan plan = compile(pipe.graph);
  c.config.insert(c.config.end(), plan.diagnostics.begin(), plan.diagnostics.end());
  c.shaders = checker.checkPipeline(pipe, plan, processRegistry());
  return c;
}

// The rgraph executable beside this test (both in <build>/bin), or "".
std::string rgraphCli() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  fs::path cli = exe.parent_path() / "rgraph";
  return fs::is_regular_file(cli, ec) ? cli.string() : std::string();
}

using RunResult = rgraph::testsupport::CommandResult;
RunResult run(const std::string& command) {
  return rgraph::testsupport::runCommand(command + " 2>&1");
}

std::vector<std::string> shippedPipelines() {
  std::vector<std::string> files;
  for (const char* dir : {"/pipelines", "/pipelines/examples"}) {
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(std::string(RGRAPH_SOURCE_DIR) + dir, ec))
      if (e.is_regular_file() && e.path().extension() == ".json") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// ------------------------------------------------------------ must show

TEST(ShaderCheck, ThreeAttachmentsForFourOutputsFailsNamingPassShaderAndMismatch) {
  ShaderChecker checker(testDirs());
  Checked c = checkConfig(checker, kConfigs + "/four_outputs_three_attachments.json");
  ASSERT_FALSE(hasErrors(c.config)) << all(c.config);
  ASSERT_TRUE(hasErrors(c.shaders)) << all(c.shaders);
  const Diagnostic* d = findContaining(c.shaders, Severity::error, "four_outputs.frag");
  ASSERT_NE(d, nullptr) << all(c.shaders);
  EXPECT_EQ(d->code, DiagCode::shader_error);
  EXPECT_EQ(d->pass, "mrt");
  EXPECT_NE(d->message.find("pass 'mrt'"), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("writes 4 colour outputs"), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("binds 3 colour attachments"), std::string::npos) << d->message;
  EXPECT_NE(d->message.find("output 'o_color3' (location 3) has no colour attachment"), std::string::npos)
      << d->message;
  // Located at the pass in the config.
  EXPECT_NE(d->where.file.find("four_outputs_three_attachments.json"), std::string::npos);
  EXPECT_GT(d->where.line, 0);
  EXPECT_EQ(d->where.path, "/passes/0");
  EXPECT_EQ(count(c.shaders, Severity::error), 1u) << all(c.shaders);
}

TEST(ShaderCheck, CliValidateFailsOnThreeAttachmentsForFourOutputs) {
  const std::string cli = rgraphCli();
  if (cli.empty()) GTEST_FAIL() << "rgraph executable not found beside the tests (build the rgraph_cli target)";
  RunResult r = run("RGRAPH_SHADER_DIR='" + kTestShaders + "' '" + cli + "' validate '" + kConfigs +
                    "/four_outputs_three_attachments.json'");
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_NE(r.out.find("four_outputs_three_attachments.json:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pass 'mrt' (fullscreen)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("four_outputs.frag writes 4 colour outputs"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("binds 3 colour attachments"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(": valid"), std::string::npos) << r.out;

  RunResult json = run("RGRAPH_SHADER_DIR='" + kTestShaders + "' '" + cli + "' validate --json '" + kConfigs +
                       "/four_outputs_three_attachments.json'");
  EXPECT_EQ(json.exitCode, 1) << json.out;
  EXPECT_NE(json.out.find("\"code\": \"shader_error\""), std::string::npos) << json.out;
  EXPECT_NE(json.out.find("\"pass\": \"mrt\""), std::string::npos) << json.out;
}

TEST(ShaderCheck, SyntaxErrorGivesShaderFileLineAndPass) {
  ShaderChecker checker(testDirs());
  Checked c = checkConfig(checker, kConfigs + "/syntax_error.json");
  ASSERT_FALSE(hasErrors(c.config)) << all(c.config);
  ASSERT_TRUE(hasErrors(c.shaders)) << all(c.shaders);
  const Diagnostic& d = c.shaders.front();
  EXPECT_EQ(d.code, DiagCode::shader_error);
  EXPECT_EQ(d.pass, "broken");
  EXPECT_TRUE(endsWith(d.where.file, "shaders/syntax_error.frag")) << d.where.file;
  EXPECT_EQ(d.where.line, 7);
  EXPECT_EQ(d.where.column, 0);
  const std::string line = formatDiagnostic(d);
  EXPECT_NE(line.find("syntax_error.frag:7: error: pass 'broken': "), std::string::npos) << line;
}

TEST(ShaderCheck, CliValidateReportsSyntaxErrorAtShaderLine) {
  const std::string cli = rgraphCli();
  if (cli.empty()) GTEST_FAIL() << "rgraph executable not found beside the tests (build the rgraph_cli target)";
  RunResult r = run("RGRAPH_SHADER_DIR='" + kTestShaders + "' '" + cli + "' validate '" + kConfigs + "/syntax_error.json'");
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_NE(r.out.find("syntax_error.frag:7: error: pass 'broken': "), std::string::npos) << r.out;
}

TEST(ShaderCheck, SemanticErrorNamesIdentifierAndLine) {
  ShaderChecker checker(testDirs());
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams("undeclared.frag"),
                                    {slot("color", Access::color_attachment, "out", Format::rgba8)});
  ASSERT_TRUE(hasErrors(d)) << all(d);
  EXPECT_TRUE(endsWith(d[0].where.file, "undeclared.frag"));
  EXPECT_EQ(d[0].where.line, 6);
  EXPECT_NE(d[0].message.find("undeclared_thing"), std::string::npos) << all(d);
}

TEST(ShaderCheck, ErrorInIncludedFileNamesTheIncludedFile) {
  ShaderChecker checker(testDirs());
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams("include_error.frag"),
                                    {slot("color", Access::color_attachment, "out", Format::rgba8)});
  ASSERT_TRUE(hasErrors(d)) << all(d);
  EXPECT_TRUE(endsWith(d[0].where.file, "include/bad_include.glsl")) << all(d);
  EXPECT_EQ(d[0].where.line, 3) << all(d);
  EXPECT_NE(d[0].message.find("missing_value"), std::string::npos) << all(d);
}

TEST(ShaderCheck, MissingIncludeGivesIncludingFileAndLine) {
  ShaderChecker checker(testDirs());
  Checked c = checkConfig(checker, kConfigs + "/missing_include.json");
  ASSERT_FALSE(hasErrors(c.config)) << all(c.config);
  ASSERT_EQ(count(c.shaders, Severity::error), 1u) << all(c.shaders);
  const Diagnostic& d = c.shaders.front();
  EXPECT_EQ(d.pass, "includer");
  EXPECT_TRUE(endsWith(d.where.file, "missing_include.frag")) << d.where.file;
  EXPECT_EQ(d.where.line, 3);
  EXPECT_NE(d.message.find("included file 'include/no_such_include.glsl' not found"), std::string::npos) << d.message;
}

TEST(ShaderCheck, MissingShaderFileIsAnError) {
  ShaderChecker checker(testDirs());
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams("no_such_shader.frag"),
                                    {slot("color", Access::color_attachment, "out", Format::rgba8)});
  ASSERT_EQ(count(d, Severity::error), 1u) << all(d);
  EXPECT_NE(d[0].message.find("no_such_shader.frag"), std::string::npos) << all(d);
  EXPECT_NE(d[0].message.find("not found"), std::string::npos) << all(d);
  EXPECT_EQ(d[0].pass, "p");
}

TEST(ShaderCheck, EmptyShaderParameterIsAnErrorAtThePass) {
  ShaderChecker checker(testDirs());
  SourceLocation where{"pipe.json", 4, 7, "/passes/0"};
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams(""),
                                    {slot("color", Access::color_attachment, "out", Format::rgba8)}, where);
  ASSERT_EQ(count(d, Severity::error), 1u) << all(d);
  EXPECT_NE(d[0].message.find("parameter 'shader' is empty"), std::string::npos) << all(d);
  EXPECT_EQ(d[0].where.path, "/passes/0");
}

TEST(ShaderCheck, LinkErrorIsReported) {
  ShaderChecker checker(testDirs());
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams("link_error.frag"),
                                    {slot("color", Access::color_attachment, "out", Format::rgba8)});
  ASSERT_TRUE(hasErrors(d)) << all(d);
  EXPECT_NE(d[0].message.find("link"), std::string::npos) << all(d);
  EXPECT_TRUE(endsWith(d[0].where.file, "link_error.frag")) << all(d);
}

// A scene program runs with SCENE_ANIMATION in scenes that deform (skins,
// morph targets), and validate does not know the scene: it checks both
// variants, reporting the animated one's errors with its define named.
TEST(ShaderCheck, SceneProgramsAreCheckedInTheirAnimatedVariantToo) {
  ShaderChecker checker(testDirs());
  PassTypeDesc t = type("fullscreen");
  t.programs = [](const ParamSet&) {
    return std::vector<ShaderProgramSpec>{programSpec("animation_probe/scene.vert", "vec4_out.frag")};
  };
  Diagnostics d = checker.checkPass("p", t, fullscreenParams("vec4_out.frag"),
                                    {slot("color", Access::color_attachment, "out", Format::rgba8)});
  ASSERT_TRUE(hasErrors(d)) << all(d);
  EXPECT_NE(d[0].message.find("undeclaredJointScale"), std::string::npos) << all(d);
  EXPECT_NE(d[0].message.find("with SCENE_ANIMATION"), std::string::npos) << all(d);
  EXPECT_TRUE(endsWith(d[0].where.file, "animation_probe/scene.vert")) << all(d);
  ASSERT_EQ(checker.checkedPrograms().size(), 2u);
  EXPECT_TRUE(checker.checkedPrograms()[0].spec.defines.empty());
  EXPECT_EQ(checker.checkedPrograms()[1].spec.defines, std::vector<std::string>{"SCENE_ANIMATION"});
}

// ------------------------------------------------------------ shipped pipelines

TEST(ShaderCheck, EveryShippedPipelineHasNoShaderDiagnostics) {
  ShaderChecker checker;  // the default search path: what `rgraph validate` uses
  const auto files = shippedPipelines();
  ASSERT_GE(files.size(), 8u);
  size_t checked = 0;
  const auto start = std::chrono::steady_clock::now();
  for (const auto& file : files) {
    Diagnostics parse;
    ConfigDocument doc = ConfigDocument::parseFile(file, parse);
    ASSERT_TRUE(doc.ok()) << file << "\n" << all(parse);
    if (!doc.plugins().empty()) continue;  // needs its plugins loaded: covered through the CLI below
    Checked c = checkConfig(checker, file);
    ASSERT_FALSE(hasErrors(c.config)) << file << "\n" << all(c.config);
    EXPECT_TRUE(c.shaders.empty()) << file << "\n" << all(c.shaders);
    ++checked;
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(checked, 8u);
  // Programs shared between pipelines are compiled once: 87 distinct ones in
  // 21 pipelines (the three shadow pipelines add their SHADOWS variants; the
  // optional emissive and reflectance targets their G-buffer variants; the
  // image-based lighting of deferred-pbr its pre-filter passes and
  // HAS_ENVIRONMENT; every scene program its SCENE_ANIMATION variant: 20).
  EXPECT_GT(checker.stats().cacheHits, 0u);
  EXPECT_LT(checker.stats().programsCompiled, 90u);
  // Well under a second in a release build; generous for sanitizer builds.
  EXPECT_LT(seconds, 10.0);
  std::printf("checked %zu pipelines: %zu programs compiled, %zu cache hits, %.3f s in glslang, %.3f s in all\n",
              checked, checker.stats().programsCompiled, checker.stats().cacheHits, checker.stats().seconds, seconds);
}

TEST(ShaderCheck, CliValidatesEveryShippedPipelineWithoutShaderDiagnostics) {
  const std::string cli = rgraphCli();
  if (cli.empty()) GTEST_FAIL() << "rgraph executable not found beside the tests (build the rgraph_cli target)";
  for (const auto& file : shippedPipelines()) {
    RunResult r = run("'" + cli + "' validate --json '" + file + "'");
    EXPECT_EQ(r.out.find("shader_error"), std::string::npos) << file << "\n" << r.out;
    // A pipeline whose plugins are not built here fails for that reason alone.
    if (r.out.find("\"plugin_error\"") != std::string::npos) continue;
    EXPECT_EQ(r.exitCode, 0) << file << "\n" << r.out;
  }
}

// ------------------------------------------------------------ geometry layouts

struct LayoutTargets {
  const char* layout;
  std::vector<std::pair<const char*, Format>> targets;  // colour slots the layout writes, with their formats
};

const std::vector<LayoutTargets> kLayouts = {
    {"learnopengl", {{"position", Format::rgba16f}, {"normal", Format::rgba16f}, {"albedo", Format::rgba8}}},
    {"pbr",
     {{"position", Format::rgba16f}, {"normal", Format::rgba16f}, {"albedo", Format::rgba16f}, {"material", Format::rgba16f}}},
    {"compact", {{"normal", Format::rg16f}, {"albedo", Format::rgba8}, {"material", Format::rg8}}},
    {"fp32",
     {{"position", Format::rgba32f}, {"normal", Format::rgba32f}, {"albedo", Format::rgba32f}, {"material", Format::rgba32f}}},
};

std::vector<BoundSlot> geometryBindings(const LayoutTargets& l) {
  std::vector<BoundSlot> b;
  // Config order differs from slot order on purpose: attachments follow slot order.
  for (auto it = l.targets.rbegin(); it != l.targets.rend(); ++it)
    b.push_back(slot(it->first, Access::color_attachment, std::string("g_") + it->first, it->second));
  b.push_back(slot("depth", Access::depth_attachment, "g_depth", Format::depth32f));
  return b;
}

ParamSet layoutParams(const PassTypeDesc& t, const std::string& layout) {
  ParamSet p = defaultParams(t.params);
  p.set("layout", layout);
  return p;
}

TEST(ShaderCheck, GeometryReflectionMatchesEveryLayoutsTargets) {
  ShaderChecker checker;
  const PassTypeDesc& geometry = type("geometry");
  for (const auto& l : kLayouts) {
    SCOPED_TRACE(l.layout);
    const ParamSet params = layoutParams(geometry, l.layout);
    Diagnostics d = checker.checkPass("gbuffer", geometry, params, geometryBindings(l));
    EXPECT_TRUE(d.empty()) << all(d);
    // The reflection itself: one output per target, at the target's location
    // (slot order), with the format's component count.
    const auto specs = geometry.programs(params);
    ASSERT_EQ(specs.size(), 2u);  // with and without HAS_NORMAL_MAPS
    for (const auto& spec : specs) {
      const ProgramCheck& pc = checker.program(spec);
      ASSERT_TRUE(pc.ok);
      ASSERT_EQ(pc.outputs.size(), l.targets.size());
      for (size_t i = 0; i < l.targets.size(); ++i) {
        EXPECT_EQ(pc.outputs[i].location, static_cast<int>(i));
        EXPECT_EQ(static_cast<uint32_t>(pc.outputs[i].components), formatInfo(l.targets[i].second).components)
            << l.targets[i].first;
      }
      for (const auto& s : pc.samplers)
        EXPECT_NE(std::find(spec.ownSamplers.begin(), spec.ownSamplers.end(), s.name), spec.ownSamplers.end()) << s.name;
    }
  }
}

TEST(ShaderCheck, GeometryLayoutWithoutItsMaterialTargetIsAnError) {
  ShaderChecker checker;
  const PassTypeDesc& geometry = type("geometry");
  LayoutTargets pbr = kLayouts[1];
  pbr.targets.pop_back();  // no material target
  Diagnostics d = checker.checkPass("gbuffer", geometry, layoutParams(geometry, "pbr"), geometryBindings(pbr));
  const Diagnostic* e = findContaining(d, Severity::error, "writes 4 colour outputs");
  ASSERT_NE(e, nullptr) << all(d);
  EXPECT_NE(e->message.find("binds 3 colour attachments"), std::string::npos) << e->message;
  EXPECT_NE(e->message.find("'outMaterial' (location 3)"), std::string::npos) << e->message;
}

TEST(ShaderCheck, CompactLayoutWithAPositionTargetIsAnError) {
  ShaderChecker checker;
  const PassTypeDesc& geometry = type("geometry");
  LayoutTargets compact = kLayouts[2];
  compact.targets.insert(compact.targets.begin(), {"position", Format::rgba16f});
  Diagnostics d = checker.checkPass("gbuffer", geometry, layoutParams(geometry, "compact"), geometryBindings(compact));
  const Diagnostic* e = findContaining(d, Severity::error, "is written by no output");
  ASSERT_NE(e, nullptr) << all(d);
}

TEST(ShaderCheck, CompactNormalInAnRgbaTargetWarns) {
  ShaderChecker checker;
  const PassTypeDesc& geometry = type("geometry");
  LayoutTargets compact = kLayouts[2];
  compact.targets[0].second = Format::rgba16f;
  Diagnostics d = checker.checkPass("gbuffer", geometry, layoutParams(geometry, "compact"), geometryBindings(compact));
  EXPECT_FALSE(hasErrors(d)) << all(d);
  const Diagnostic* w = findContaining(d, Severity::warning, "vec2 'outNormal'");
  ASSERT_NE(w, nullptr) << all(d);
  EXPECT_NE(w->message.find("components b, a are left undefined"), std::string::npos) << w->message;
  EXPECT_EQ(w->slot, "normal");
}

// ------------------------------------------------------------ outputs and formats

TEST(ShaderCheck, MoreComponentsThanTheFormatWarns) {
  ShaderChecker checker(testDirs());
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams("vec4_out.frag"),
                                    {slot("color", Access::color_attachment, "rg", Format::rg16f)});
  ASSERT_EQ(d.size(), 1u) << all(d);
  EXPECT_EQ(d[0].severity, Severity::warning);
  EXPECT_NE(d[0].message.find("components b, a are dropped"), std::string::npos) << all(d);
}

TEST(ShaderCheck, FewerComponentsWarnsUnlessBlendingWithSourceAlpha) {
  ShaderChecker checker(testDirs());
  const std::vector<BoundSlot> rgba = {slot("color", Access::color_attachment, "c", Format::rgba8)};
  Diagnostics none = checker.checkPass("p", type("fullscreen"), fullscreenParams("vec3_out.frag"), rgba);
  ASSERT_EQ(none.size(), 1u) << all(none);
  EXPECT_EQ(none[0].severity, Severity::warning);
  EXPECT_NE(none[0].message.find("components a are left undefined"), std::string::npos) << all(none);

  Diagnostics alpha = checker.checkPass("p", type("fullscreen"), fullscreenParams("vec3_out.frag", "alpha"), rgba);
  ASSERT_EQ(alpha.size(), 1u) << all(alpha);
  EXPECT_EQ(alpha[0].severity, Severity::error);
  EXPECT_NE(alpha[0].message.find("blends with source alpha"), std::string::npos) << all(alpha);

  // Additive blending does not read source alpha.
  Diagnostics additive = checker.checkPass("p", type("fullscreen"), fullscreenParams("vec3_out.frag", "additive"), rgba);
  EXPECT_FALSE(hasErrors(additive)) << all(additive);

  // A three-component format is written in full by a vec3.
  Diagnostics r11 = checker.checkPass("p", type("fullscreen"), fullscreenParams("vec3_out.frag"),
                                      {slot("color", Access::color_attachment, "c", Format::r11g11b10f)});
  EXPECT_TRUE(r11.empty()) << all(r11);
}

TEST(ShaderCheck, IntegerOutputIntoANormalizedFormatIsAnError) {
  ShaderChecker checker(testDirs());
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams("ivec4_out.frag"),
                                    {slot("color", Access::color_attachment, "c", Format::rgba8)});
  ASSERT_EQ(count(d, Severity::error), 1u) << all(d);
  EXPECT_NE(d[0].message.find("ivec4 'o_int'"), std::string::npos) << all(d);
}

// Ids (rg32ui, the geometry pass's object_id): unsigned outputs only.
TEST(ShaderCheck, OnlyUnsignedOutputsGoIntoAnUnsignedIntegerFormat) {
  ShaderChecker checker(testDirs());
  const std::vector<BoundSlot> ids = {slot("color", Access::color_attachment, "ids", Format::rg32ui)};
  for (const char* shader : {"vec4_out.frag", "ivec4_out.frag"}) {
    Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams(shader), ids);
    ASSERT_EQ(count(d, Severity::error), 1u) << shader << ": " << all(d);
    EXPECT_NE(d[0].message.find("only unsigned integer outputs (uint, uvec2...) are defined in an unsigned integer "
                                "format"),
              std::string::npos)
        << all(d);
  }
}

TEST(ShaderCheck, ColourAttachmentsFollowSlotOrderNotConfigOrder) {
  ShaderChecker checker(testDirs());
  // color and color2 bound (color1 not): the executor puts color2 at location 1.
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams("four_outputs.frag"),
                                    {slot("color2", Access::color_attachment, "c2", Format::rgba8),
                                     slot("color", Access::color_attachment, "c0", Format::rgba8)});
  const Diagnostic* e = findContaining(d, Severity::error, "binds 2 colour attachments");
  ASSERT_NE(e, nullptr) << all(d);
  EXPECT_NE(e->message.find("'color' (c0) at 0, 'color2' (c2) at 1"), std::string::npos) << e->message;
}

TEST(ShaderCheck, OutputsWithoutLocations) {
  ShaderChecker checker(testDirs());
  const std::vector<BoundSlot> one = {slot("color", Access::color_attachment, "c", Format::rgba8)};
  EXPECT_TRUE(checker.checkPass("p", type("fullscreen"), fullscreenParams("no_location.frag"), one).empty());
  Diagnostics two = checker.checkPass("p", type("fullscreen"), fullscreenParams("two_no_location.frag"),
                                      {slot("color", Access::color_attachment, "c", Format::rgba8),
                                       slot("color1", Access::color_attachment, "c1", Format::rgba8)});
  EXPECT_FALSE(hasErrors(two)) << all(two);
  EXPECT_NE(findContaining(two, Severity::warning, "without layout(location)"), nullptr) << all(two);
}

TEST(ShaderCheck, ArrayOutputTakesOneLocationPerElement) {
  ShaderChecker checker(testDirs());
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams("array_out.frag"),
                                    {slot("color", Access::color_attachment, "a", Format::rgba8),
                                     slot("color1", Access::color_attachment, "b", Format::rgba8),
                                     slot("color2", Access::color_attachment, "c", Format::rgba8)});
  const Diagnostic* e = findContaining(d, Severity::error, "output 'o_targets[3]' (location 3)");
  ASSERT_NE(e, nullptr) << all(d);
  Diagnostics four = checker.checkPass("p", type("fullscreen"), fullscreenParams("array_out.frag"),
                                       {slot("color", Access::color_attachment, "a", Format::rgba8),
                                        slot("color1", Access::color_attachment, "b", Format::rgba8),
                                        slot("color2", Access::color_attachment, "c", Format::rgba8),
                                        slot("color3", Access::color_attachment, "d", Format::rgba8)});
  EXPECT_TRUE(four.empty()) << all(four);
}

// ------------------------------------------------------------ samplers

TEST(ShaderCheck, BoundInputTheShaderNeverDeclaresWarns) {
  ShaderChecker checker;
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams("gradient.frag"),
                                    {slot("input0", Access::sampled, "tex", Format::rgba8),
                                     slot("color", Access::color_attachment, "c", Format::rgba8)});
  ASSERT_EQ(d.size(), 1u) << all(d);
  EXPECT_EQ(d[0].severity, Severity::warning);
  EXPECT_EQ(d[0].slot, "input0");
  EXPECT_NE(d[0].message.find("declares no sampler 'input0'"), std::string::npos) << all(d);
}

TEST(ShaderCheck, DeclaredButUnusedSamplerIsFineEitherWay) {
  ShaderChecker checker(testDirs());
  const BoundSlot out = slot("color", Access::color_attachment, "c", Format::rgba8);
  EXPECT_TRUE(checker.checkPass("p", type("fullscreen"), fullscreenParams("declared_unused_input.frag"), {out}).empty());
  EXPECT_TRUE(checker
                  .checkPass("p", type("fullscreen"), fullscreenParams("declared_unused_input.frag"),
                             {slot("input0", Access::sampled, "tex", Format::rgba8), out})
                  .empty());
}

TEST(ShaderCheck, SampledInputLeftUnboundIsAnError) {
  ShaderChecker checker(testDirs());
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams("reads_input1.frag"),
                                    {slot("input0", Access::sampled, "tex", Format::rgba8),
                                     slot("color", Access::color_attachment, "c", Format::rgba8)});
  ASSERT_EQ(count(d, Severity::error), 1u) << all(d);
  EXPECT_EQ(d[0].slot, "input1");
  EXPECT_NE(d[0].message.find("samples 'input1'"), std::string::npos) << all(d);
}

TEST(ShaderCheck, SamplerBoundToNoInputWarns) {
  ShaderChecker checker(testDirs());
  Diagnostics d = checker.checkPass("p", type("fullscreen"), fullscreenParams("unmapped_sampler.frag"),
                                    {slot("color", Access::color_attachment, "c", Format::rgba8)});
  ASSERT_EQ(d.size(), 1u) << all(d);
  EXPECT_EQ(d[0].severity, Severity::warning);
  EXPECT_NE(d[0].message.find("sampler 'u_lookup'"), std::string::npos) << all(d);
}

TEST(ShaderCheck, IntegerAndMultisampleSamplerMismatchesAreErrors) {
  ShaderChecker checker(testDirs());
  const BoundSlot out = slot("color", Access::color_attachment, "c", Format::rgba8);
  Diagnostics isampler = checker.checkPass("p", type("fullscreen"), fullscreenParams("integer_sampler.frag"),
                                           {slot("input0", Access::sampled, "tex", Format::rgba8), out});
  EXPECT_NE(findContaining(isampler, Severity::error, "integer sampler"), nullptr) << all(isampler);
  Diagnostics ms = checker.checkPass("p", type("fullscreen"), fullscreenParams("invert.frag"),
                                     {slot("input0", Access::sampled, "tex", Format::rgba8, 4), out});
  EXPECT_NE(findContaining(ms, Severity::error, "not a multisample sampler"), nullptr) << all(ms);
}

TEST(ShaderCheck, SamplerBindingMustMatchTheUnitThePassUses) {
  // A tonemap-like pass that binds its input on unit 0 and relies on the
  // shader's layout(binding).
  PassTypeDesc t = type("tonemap");
  t.name = "tonemap_test";
  t.programs = [](const ParamSet&) {
    ShaderProgramSpec s;
    s.vert = "fullscreen.vert";
    s.frag = "hdr_binding3.frag";
    s.samplers = {{"hdr", "u_hdr", 0}};
    return std::vector<ShaderProgramSpec>{s};
  };
  ShaderChecker checker(testDirs());
  Diagnostics d = checker.checkPass("tm", t, defaultParams(t.params),
                                    {slot("hdr", Access::sampled, "hdr", Format::rgba16f),
                                     slot("output", Access::color_attachment, "out", Format::rgba8)});
  const Diagnostic* e = findContaining(d, Severity::error, "layout(binding = 3)");
  ASSERT_NE(e, nullptr) << all(d);
  EXPECT_NE(e->message.find("unit 0"), std::string::npos) << e->message;
}

TEST(ShaderCheck, DeferredLightingReadsWhatItsLayoutNeeds) {
  ShaderChecker checker;
  const PassTypeDesc& lighting = type("deferred_lighting");
  const BoundSlot color = slot("color", Access::color_attachment, "hdr", Format::rgba16f);
  // learnopengl: no material target, g_material never read.
  Diagnostics lo = checker.checkPass("l", lighting, layoutParams(lighting, "learnopengl"),
                                     {slot("position", Access::sampled, "p", Format::rgba16f),
                                      slot("normal", Access::sampled, "n", Format::rgba16f),
                                      slot("albedo", Access::sampled, "a", Format::rgba8), color});
  EXPECT_TRUE(lo.empty()) << all(lo);
  // compact rebuilds position from depth: leaving depth unbound is an error.
  Diagnostics compact = checker.checkPass("l", lighting, layoutParams(lighting, "compact"),
                                          {slot("normal", Access::sampled, "n", Format::rg16f),
                                           slot("albedo", Access::sampled, "a", Format::rgba8),
                                           slot("material", Access::sampled, "m", Format::rg8), color});
  const Diagnostic* e = findContaining(compact, Severity::error, "samples 'g_depth'");
  ASSERT_NE(e, nullptr) << all(compact);
  EXPECT_EQ(e->slot, "depth");
}

// ------------------------------------------------------------ caching, fallback

TEST(ShaderCheck, ProgramsAreCompiledOncePerFilesAndDefines) {
  ShaderChecker checker;
  ShaderProgramSpec a;
  a.vert = "fullscreen.vert";
  a.frag = "invert.frag";
  const ProgramCheck& first = checker.program(a);
  EXPECT_TRUE(first.ok);
  EXPECT_EQ(checker.stats().programsCompiled, 1u);
  EXPECT_EQ(&checker.program(a), &first);
  EXPECT_EQ(checker.stats().programsCompiled, 1u);
  EXPECT_EQ(checker.stats().cacheHits, 1u);
  a.defines = {"SOMETHING=1"};
  checker.program(a);
  EXPECT_EQ(checker.stats().programsCompiled, 2u);
}

TEST(ShaderCheck, EverySamplerOfASpecNamesItsTextureUnit) {
  // The executor binds each sampled slot to the unit its spec names and sets
  // the sampler uniform to it: a spec without a unit cannot run.
  PassTypeDesc t = type("fullscreen");
  t.name = "no_unit";
  t.programs = [](const ParamSet&) {
    return std::vector{programSpec("fullscreen.vert", "invert.frag", {}, {{"input0", "input0", -1}})};
  };
  ShaderChecker checker(testDirs());
  const std::vector<BoundSlot> bound = {slot("input0", Access::sampled, "tex", Format::rgba8),
                                        slot("color", Access::color_attachment, "out", Format::rgba8)};
  Diagnostics d = checker.checkPass("p", t, defaultParams(t.params), bound);
  const Diagnostic* e = findContaining(d, Severity::error, "names no texture unit");
  ASSERT_NE(e, nullptr) << all(d);
  EXPECT_EQ(e->slot, "input0");
  // With a unit, a shader without layout(binding) reads it (the executor sets
  // the sampler uniform): no finding.
  t.programs = [](const ParamSet&) {
    return std::vector{programSpec("fullscreen.vert", "invert.frag", {}, {{"input0", "input0", 2}})};
  };
  const Diagnostics withUnit = checker.checkPass("p", t, defaultParams(t.params), bound);
  EXPECT_TRUE(withUnit.empty()) << all(withUnit);
}

TEST(ShaderCheck, PassTypesWithoutProgramsUseNoShaders) {
  PassTypeDesc t;
  t.name = "no_programs";
  ShaderChecker checker(testDirs());
  EXPECT_TRUE(checker.checkPass("p", t, ParamSet{}, {}).empty());
  EXPECT_TRUE(checker.checkedPrograms().empty());
  EXPECT_TRUE(t.shaderFiles().empty());
  // A type's shader files are derived from its programs, each once.
  EXPECT_EQ(type("forward").shaderFiles(),
            (std::vector<std::string>{"light_marker.vert", "light_marker.frag", "scene.vert", "forward_lit.frag"}));
}

TEST(ShaderCheck, PluginShadersByAbsolutePath) {
  // Plugins (PluginHost::shaderPath) and pass types of an application's own
  // name their shaders by absolute path: checked as is, inside a shader folder
  // or not (a config cannot name one: the loader refuses absolute shader
  // parameters; docs/writing-a-pass.md, "Shaders").
  const auto color = std::vector<BoundSlot>{slot("color", Access::color_attachment, "c", Format::rgba8)};
  const std::string file = kTestShaders + "/four_outputs.frag";
  Diagnostics d = ShaderChecker().checkPass("p", type("fullscreen"), fullscreenParams(file), color);
  EXPECT_EQ(findContaining(d, Severity::error, "outside the shader folders"), nullptr) << all(d);
  EXPECT_NE(findContaining(d, Severity::error, "writes 4 colour outputs"), nullptr) << all(d);
}

// ------------------------------------------------------------ sources and logs

TEST(ShaderSource, DefinesAfterVersionAndLineTable) {
  ShaderSource src = loadShaderSource("include_error.frag", {"A", "B=2"}, testDirs());
  EXPECT_EQ(src.text.rfind("#version 450 core\n#define A\n#define B 2\n", 0), 0u) << src.text;
  ASSERT_EQ(src.files.size(), 2u);
  EXPECT_TRUE(endsWith(src.files[1], "include/bad_include.glsl"));
  // Expanded line 1 is the #version (line 1), the defines map to it too.
  EXPECT_EQ(src.lines[0], std::make_pair(0, 1));
  EXPECT_EQ(src.lines[2], std::make_pair(0, 1));
  // Line 3 of the file is the #include: its lines come from file 1.
  EXPECT_EQ(src.lines[4], std::make_pair(1, 1));
  EXPECT_EQ(src.lines[6], std::make_pair(1, 3));
}

TEST(ShaderSource, LogsOfEveryDriverMapBackToFiles) {
  ShaderSource src = loadShaderSource("include_error.frag", {}, testDirs());
  // Expanded line 5 is line 3 of the include (version, comment, include lines 1, 2, 3).
  const std::string logs[] = {"ERROR: 0:5: 'missing_value' : undeclared identifier\nERROR: 1 compilation errors.  No code generated.\n",
                              "0:5(10): error: `missing_value' undeclared\n",
                              "0(5) : error C1008: undefined variable \"missing_value\"\n"};
  for (const auto& log : logs) {
    auto m = parseShaderLog(log, src);
    ASSERT_EQ(m.size(), 1u) << log;
    EXPECT_EQ(m[0].severity, Severity::error);
    EXPECT_TRUE(endsWith(m[0].file, "bad_include.glsl")) << m[0].file;
    EXPECT_EQ(m[0].line, 3) << log;
    EXPECT_NE(m[0].text.find("missing_value"), std::string::npos) << m[0].text;
    EXPECT_EQ(m[0].text.find("error"), std::string::npos) << m[0].text;
    EXPECT_NE(mapShaderLog(log, src).find("bad_include.glsl:3: "), std::string::npos);
  }
  auto w = parseShaderLog("WARNING: 0:1: something odd\n", src);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].severity, Severity::warning);
}

TEST(ShaderSource, NestedIncludeIsRefusedWithItsLocation) {
  const std::string dir = testing::TempDir() + "/rgraph_nested_include";
  fs::create_directories(dir);
  {
    FILE* f = std::fopen((dir + "/outer.frag").c_str(), "w");
    std::fputs("#version 450 core\n#include \"inner.glsl\"\nvoid main() {}\n", f);
    std::fclose(f);
    f = std::fopen((dir + "/inner.glsl").c_str(), "w");
    std::fputs("// inner\n#include \"deeper.glsl\"\n", f);
    std::fclose(f);
  }
  try {
    loadShaderSource("outer.frag", {}, {dir});
    FAIL() << "expected ShaderSourceError";
  } catch (const ShaderSourceError& e) {
    EXPECT_TRUE(endsWith(e.file(), "inner.glsl")) << e.file();
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(std::string(e.what()).find("nested #include"), std::string::npos);
  }
  fs::remove_all(dir);
}

}  // namespace
