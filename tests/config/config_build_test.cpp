// Valid configs build the expected GraphDesc; several errors in one file are
// all reported, in file order.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "test_registry.h"

namespace rgraph {
namespace {

std::string validPath(const std::string& name) { return test::configsDir() + "/valid/" + name; }

PipelineConfig load(const std::string& path, Diagnostics& diags) {
  ConfigDocument doc = ConfigDocument::parseFile(path, diags);
  EXPECT_TRUE(doc.ok());
  return doc.build(test::testRegistry(), diags);
}

PipelineConfig loadText(const std::string& text, Diagnostics& diags) {
  ConfigDocument doc = ConfigDocument::parseText(text, "inline.json", diags);
  EXPECT_TRUE(doc.ok());
  return doc.build(test::testRegistry(), diags);
}

std::string allDiagnostics(const Diagnostics& diags) {
  std::string out;
  for (const auto& d : diags) out += formatDiagnostic(d) + "\n";
  return out;
}

const ResourceDecl* findResource(const GraphDesc& g, const std::string& name) {
  for (const auto& r : g.resources)
    if (r.name == name) return &r;
  return nullptr;
}

const ResourceUse* findUse(const PassDecl& p, const std::string& slot) {
  for (const auto& u : p.uses)
    if (u.slot == slot) return &u;
  return nullptr;
}

void expectAt(const SourceLocation& where, int line, int column, const std::string& path) {
  EXPECT_EQ(where.line, line) << where.path;
  EXPECT_EQ(where.column, column) << where.path;
  EXPECT_EQ(where.path, path);
}

// A pipeline with every valid configs file's features; see deferred.json.
TEST(ConfigBuild, DeferredPipeline) {
  Diagnostics diags;
  const std::string path = validPath("deferred.json");
  PipelineConfig cfg = load(path, diags);
  ASSERT_TRUE(diags.empty()) << allDiagnostics(diags);
  const GraphDesc& g = cfg.graph;

  EXPECT_EQ(cfg.file, path);
  EXPECT_EQ(cfg.version, 1);
  EXPECT_EQ(cfg.plugins, std::vector<std::string>{"libextra_passes.so"});

  // Resources, in file order.
  ASSERT_EQ(g.resources.size(), 7u);
  std::vector<std::string> names;
  for (const auto& r : g.resources) names.push_back(r.name);
  EXPECT_EQ(names,
            (std::vector<std::string>{"scene_color", "scene_depth", "resolved", "bloom", "hdr", "thumbnail", "ldr"}));

  const ResourceDecl& color = g.resources[0];
  EXPECT_EQ(color.kind, ResourceKind::texture);
  EXPECT_EQ(color.texture.format, Format::rgba16f);
  EXPECT_EQ(color.texture.samples, 4u);
  EXPECT_EQ(color.texture.mips, 1u);
  EXPECT_EQ(color.texture.size.kind, SizeSpec::Kind::output);
  ASSERT_TRUE(color.texture.clear.has_value());
  EXPECT_EQ(*color.texture.clear, (std::vector<float>{0.1f, 0.2f, 0.3f, 1.0f}));
  EXPECT_FALSE(color.imported);
  EXPECT_EQ(color.where.file, path);
  expectAt(color.where, 6, 20, "/resources/scene_color");

  const ResourceDecl& depth = g.resources[1];
  EXPECT_EQ(depth.texture.format, Format::depth32f);
  ASSERT_TRUE(depth.texture.clear.has_value());
  EXPECT_EQ(*depth.texture.clear, std::vector<float>{1.0f});

  const ResourceDecl& resolved = g.resources[2];
  EXPECT_EQ(resolved.texture.samples, 1u);
  EXPECT_FALSE(resolved.texture.clear.has_value());

  const ResourceDecl& bloom = g.resources[3];
  EXPECT_EQ(bloom.texture.format, Format::r11g11b10f);
  EXPECT_EQ(bloom.texture.size.kind, SizeSpec::Kind::scale);
  EXPECT_FLOAT_EQ(bloom.texture.size.scale, 0.5f);
  EXPECT_EQ(bloom.texture.mips, 0u);

  const ResourceDecl& thumb = g.resources[5];
  EXPECT_EQ(thumb.texture.size.kind, SizeSpec::Kind::absolute);
  EXPECT_EQ(thumb.texture.size.width, 256u);
  EXPECT_EQ(thumb.texture.size.height, 144u);
  EXPECT_FALSE(thumb.imported);

  // "output" names a version of ldr: ldr is the imported output image.
  const ResourceDecl& ldr = g.resources[6];
  EXPECT_EQ(ldr.texture.format, Format::srgb8_alpha8);
  EXPECT_TRUE(ldr.imported);
  EXPECT_FALSE(ldr.importedHasContent);
  expectAt(ldr.where, 12, 12, "/resources/ldr");
  EXPECT_EQ(g.output, "ldr_final");
  expectAt(g.outputWhere, 74, 13, "/output");
  for (const auto& r : g.resources)
    if (r.name != "ldr") {
      EXPECT_FALSE(r.imported) << r.name;
    }

  // Passes, in file order, with one params set each.
  ASSERT_EQ(g.passes.size(), 8u);
  ASSERT_EQ(cfg.params.size(), 8u);

  const PassDecl& gbuffer = g.passes[0];
  EXPECT_EQ(gbuffer.name, "gbuffer");
  EXPECT_EQ(gbuffer.type, "geometry");
  EXPECT_TRUE(gbuffer.enabled);
  EXPECT_FALSE(gbuffer.sideEffect);
  expectAt(gbuffer.where, 15, 5, "/passes/0");
  ASSERT_EQ(gbuffer.uses.size(), 2u);
  EXPECT_EQ(gbuffer.uses[0].slot, "color");  // slot-declaration order
  EXPECT_EQ(gbuffer.uses[0].access, Access::color_attachment);
  EXPECT_EQ(gbuffer.uses[0].input, "");
  EXPECT_EQ(gbuffer.uses[0].output, "scene_color");
  EXPECT_TRUE(gbuffer.uses[0].acceptsMultisample);
  expectAt(gbuffer.uses[0].outputWhere, 18, 28, "/passes/0/outputs/color");
  EXPECT_FALSE(gbuffer.uses[0].inputWhere.known());
  EXPECT_EQ(gbuffer.uses[1].slot, "depth");
  EXPECT_EQ(gbuffer.uses[1].access, Access::depth_attachment);
  EXPECT_EQ(gbuffer.uses[1].output, "scene_depth");
  expectAt(gbuffer.uses[1].outputWhere, 18, 52, "/passes/0/outputs/depth");

  const PassDecl& resolve = g.passes[1];
  ASSERT_EQ(resolve.uses.size(), 2u);
  EXPECT_EQ(resolve.uses[0].slot, "src");
  EXPECT_EQ(resolve.uses[0].access, Access::sampled);
  EXPECT_EQ(resolve.uses[0].input, "scene_color");
  EXPECT_EQ(resolve.uses[0].output, "");
  EXPECT_TRUE(resolve.uses[0].acceptsMultisample);
  expectAt(resolve.uses[0].inputWhere, 23, 25, "/passes/1/inputs/src");
  EXPECT_EQ(resolve.uses[1].output, "resolved");
  EXPECT_FALSE(resolve.uses[1].acceptsMultisample);

  // An integer accepted for a float parameter.
  const PassDecl& bloomDown = g.passes[2];
  EXPECT_TRUE(bloomDown.enabled);
  const ParamValue* exposure = cfg.params[2].find("exposure");
  ASSERT_NE(exposure, nullptr);
  ASSERT_TRUE(std::holds_alternative<double>(*exposure));
  EXPECT_DOUBLE_EQ(std::get<double>(*exposure), 2.0);

  // Optional input bound; default parameter filled in.
  const PassDecl& lighting = g.passes[3];
  ASSERT_EQ(lighting.uses.size(), 3u);
  EXPECT_EQ(lighting.uses[0].input, "resolved");
  EXPECT_EQ(lighting.uses[1].slot, "aux");
  EXPECT_EQ(lighting.uses[1].input, "bloom");
  EXPECT_EQ(lighting.uses[2].output, "hdr");
  EXPECT_DOUBLE_EQ(cfg.params[3].getNumber("exposure"), 1.0);

  // Read-modify-write, disabled: a new version of hdr; the unbound optional slot has no use.
  const PassDecl& ui = g.passes[4];
  EXPECT_FALSE(ui.enabled);
  ASSERT_EQ(ui.uses.size(), 1u);
  EXPECT_EQ(ui.uses[0].slot, "color");
  EXPECT_EQ(ui.uses[0].input, "hdr");
  EXPECT_EQ(ui.uses[0].output, "hdr_ui");
  expectAt(ui.uses[0].inputWhere, 43, 27, "/passes/4/inputs/color");
  expectAt(ui.uses[0].outputWhere, 44, 28, "/passes/4/outputs/color");

  // Side effect from the config; parameters of every type.
  const PassDecl& grade = g.passes[5];
  EXPECT_TRUE(grade.sideEffect);
  const ParamSet& p = cfg.params[5];
  EXPECT_TRUE(p.getBool("flag"));
  ASSERT_TRUE(p.find("count") && std::holds_alternative<int64_t>(*p.find("count")));
  EXPECT_EQ(p.getInt("count"), 8);
  EXPECT_DOUBLE_EQ(p.getNumber("gain"), 2.5);
  EXPECT_EQ(p.getString("label"), "grade \"A\" \xC3\xA9");
  EXPECT_EQ(p.getString("mode"), "exact");
  EXPECT_EQ(p.getVector("tint"), (std::vector<double>{1, 0.5, 0.25}));
  EXPECT_EQ(p.getVector("rect"), (std::vector<double>{0, 0, 0.5, 0.5}));
  ASSERT_TRUE(p.has("bias"));  // default
  EXPECT_DOUBLE_EQ(p.getNumber("bias", 99), 0.0);
  EXPECT_EQ(p.getString("program"), "x.frag");  // default
  EXPECT_EQ(p.values().size(), 10u);             // every declared parameter

  // Blit into the output image, loading its previous version.
  const PassDecl& copy = g.passes[6];
  ASSERT_EQ(copy.uses.size(), 2u);
  EXPECT_EQ(copy.uses[0].access, Access::blit_src);
  EXPECT_EQ(copy.uses[0].input, "hdr_ui");
  EXPECT_EQ(copy.uses[1].access, Access::blit_dst);
  EXPECT_EQ(copy.uses[1].input, "ldr");
  EXPECT_EQ(copy.uses[1].output, "ldr_final");
  expectAt(copy.uses[1].inputWhere, 64, 42, "/passes/6/inputs/dst");
  expectAt(copy.uses[1].outputWhere, 65, 26, "/passes/6/outputs/dst");

  const PassDecl& thumbPass = g.passes[7];
  ASSERT_EQ(thumbPass.uses.size(), 2u);
  EXPECT_EQ(thumbPass.uses[1].input, "");
  EXPECT_EQ(thumbPass.uses[1].output, "thumbnail");
}

TEST(ConfigBuild, PluginsAndTheirLocations) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseFile(validPath("deferred.json"), diags);
  ASSERT_TRUE(doc.ok());
  EXPECT_EQ(doc.plugins(), std::vector<std::string>{"libextra_passes.so"});
  expectAt(doc.pluginLocation(0), 4, 15, "/plugins/0");
  EXPECT_TRUE(diags.empty());
}

TEST(ConfigBuild, BuffersAndTypeSideEffects) {
  Diagnostics diags;
  PipelineConfig cfg = load(validPath("compute.json"), diags);
  ASSERT_TRUE(diags.empty()) << allDiagnostics(diags);
  const ResourceDecl* bins = findResource(cfg.graph, "bins");
  ASSERT_NE(bins, nullptr);
  EXPECT_EQ(bins->kind, ResourceKind::buffer);
  EXPECT_EQ(bins->bufferBytes, 1024u);
  EXPECT_FALSE(bins->imported);
  const ResourceDecl* image = findResource(cfg.graph, "image");
  ASSERT_NE(image, nullptr);
  EXPECT_TRUE(image->imported);
  ASSERT_EQ(cfg.graph.passes.size(), 3u);
  const ResourceUse* use = findUse(cfg.graph.passes[1], "bins");
  ASSERT_NE(use, nullptr);
  EXPECT_EQ(use->access, Access::storage_write);
  EXPECT_EQ(use->output, "bins");
  EXPECT_TRUE(cfg.graph.passes[2].sideEffect);  // declared by the readback type
  EXPECT_FALSE(cfg.graph.passes[0].sideEffect);
}

TEST(ConfigBuild, MinimalPipeline) {
  Diagnostics diags;
  PipelineConfig cfg = load(validPath("minimal.json"), diags);
  ASSERT_TRUE(diags.empty()) << allDiagnostics(diags);
  ASSERT_EQ(cfg.graph.resources.size(), 1u);
  EXPECT_TRUE(cfg.graph.resources[0].imported);
  EXPECT_TRUE(cfg.plugins.empty());
  ASSERT_EQ(cfg.params.size(), 1u);
  EXPECT_EQ(cfg.params[0].getString("mode"), "nice");  // every default filled in
  EXPECT_EQ(cfg.params[0].getInt("count"), 4);
}

TEST(ConfigBuild, UnknownOutputAndVersionNamesAreLeftToCompile) {
  Diagnostics diags;
  PipelineConfig cfg = loadText(R"({
  "version": 1,
  "resources": {"a": {"format": "rgba8"}},
  "passes": [
    {"name": "p", "type": "geometry", "outputs": {"color": "nowhere", "depth": "a_2"}}
  ],
  "output": "missing"
})",
                                diags);
  EXPECT_TRUE(diags.empty()) << allDiagnostics(diags);
  EXPECT_EQ(cfg.graph.output, "missing");
  EXPECT_FALSE(cfg.graph.resources[0].imported);
}

TEST(ConfigBuild, IntegralFloatIsAnInteger) {
  Diagnostics diags;
  PipelineConfig cfg = loadText(R"({"version": 1.0, "resources": {"a": {"format": "rgba8", "samples": 2.0}},
    "passes": [{"name": "t", "type": "tweak", "outputs": {"color": "a"}, "params": {"count": 3.0}}],
    "output": "a"})",
                                diags);
  ASSERT_TRUE(diags.empty()) << allDiagnostics(diags);
  EXPECT_EQ(cfg.graph.resources[0].texture.samples, 2u);
  ASSERT_TRUE(std::holds_alternative<int64_t>(*cfg.params[0].find("count")));
  EXPECT_EQ(cfg.params[0].getInt("count"), 3);
}

// Params that declare no minimum or no maximum (a string, an unbounded vec4, a
// number with only a minimum): checking their values must not read the bound
// they lack (an empty std::optional; caught by -D_GLIBCXX_ASSERTIONS, which the
// sanitizer build defines). issue 25.
TEST(ConfigBuild, ParamsWithoutBoundsAreChecked) {
  Diagnostics diags;
  PipelineConfig cfg = loadText(R"({"version": 1, "resources": {"a": {"format": "rgba8"}},
    "passes": [{"name": "t", "type": "tweak", "outputs": {"color": "a"},
                "params": {"label": "y", "rect": [0, 0, 2, 2], "big": 7, "bias": 5}}],
    "output": "a"})",
                                diags);
  ASSERT_TRUE(diags.empty()) << allDiagnostics(diags);
  EXPECT_EQ(cfg.params[0].getInt("big"), 7);
  Diagnostics below;
  loadText(R"({"version": 1, "resources": {"a": {"format": "rgba8"}},
    "passes": [{"name": "t", "type": "tweak", "outputs": {"color": "a"}, "params": {"bias": -2}}],
    "output": "a"})",
           below);
  ASSERT_EQ(below.size(), 1u) << allDiagnostics(below);
  EXPECT_NE(below[0].message.find("value -2, below its minimum -1"), std::string::npos) << below[0].message;
}

TEST(ConfigBuild, ReportsEveryErrorInFileOrder) {
  Diagnostics diags;
  loadText(R"({
  "version": 2,
  "resources": {
    "a": {"format": "rgba9"},
    "b": {"format": "rgba8", "samples": 5}
  },
  "passes": [
    {"name": "p", "type": "tweek", "outputs": {"color": "a"}},
    {"name": "q", "type": "tweak", "outputs": {"color": "b"}, "params": {"gain": 11, "mode": 3}},
    {"name": "p", "type": "fullscreen", "inputs": {"source": "a"}, "outputs": {"color": "b"}}
  ],
  "output": "b",
  "extra": true
})",
           diags);
  std::vector<std::string> lines;
  for (const auto& d : diags) lines.push_back(formatDiagnostic(d));
  EXPECT_EQ(lines, (std::vector<std::string>{
                       "inline.json:2:14: error: /version: unsupported version 2: this rgraph reads version 1",
                       "inline.json:4:21: error: /resources/a/format: unknown format 'rgba9' (did you mean 'rgba8'?)",
                       "inline.json:5:41: error: /resources/b/samples: samples must be 1, 2, 4 or 8, got 5",
                       "inline.json:8:27: error: /passes/0/type: unknown pass type 'tweek' (did you mean 'tweak'?)",
                       "inline.json:9:82: error: /passes/1/params/gain: parameter 'gain' of pass 'q' (type tweak): "
                       "value 11, outside its range [0, 10]",
                       "inline.json:9:94: error: /passes/1/params/mode: parameter 'mode' of pass 'q' (type tweak): "
                       "expected one of 'fast', 'nice', 'exact', got int",
                       "inline.json:10:14: error: /passes/2/name: pass name 'p' is already used (first at line 8)",
                       "inline.json:13:3: error: /extra: unknown top-level key 'extra'; expected one of 'version', "
                       "'description', 'plugins', 'resources', 'passes', 'output', 'jitter'",
                   }))
      << allDiagnostics(diags);
  // Structured fields for tools.
  auto dup =
      std::find_if(diags.begin(), diags.end(), [](const Diagnostic& d) { return d.code == DiagCode::duplicate_pass; });
  ASSERT_NE(dup, diags.end());
  EXPECT_EQ(dup->pass, "p");
}

TEST(ConfigBuild, TyposDoNotCascade) {
  Diagnostics diags;
  loadText(R"({"version": 1, "resources": {"a": {"fromat": "rgba8"}, "d": {"format": "depth24"}},
    "pases": [],
    "output": "a"})",
           diags);
  ASSERT_EQ(diags.size(), 2u) << allDiagnostics(diags);
  EXPECT_NE(diags[0].message.find("did you mean 'format'"), std::string::npos);
  EXPECT_NE(diags[1].message.find("did you mean 'passes'"), std::string::npos);

  diags.clear();
  loadText(R"({"version": 1, "resources": {"a": {"format": "rgba8"}, "d": {"format": "depth24"}},
    "passes": [{"name": "g", "type": "geometry", "outputz": {"color": "a", "depth": "d"}},
               {"name": "h", "type": "geometry", "outputs": {"colour": "a", "depth": "d"}}],
    "output": "a"})",
           diags);
  ASSERT_EQ(diags.size(), 2u) << allDiagnostics(diags);
  EXPECT_EQ(diags[0].code, DiagCode::config_schema);
  EXPECT_EQ(diags[0].where.path, "/passes/0/outputz");
  EXPECT_EQ(diags[1].code, DiagCode::unknown_slot);
  EXPECT_EQ(diags[1].slot, "colour");
  EXPECT_EQ(diags[1].pass, "h");
}

TEST(ConfigBuild, SlotChecks) {
  Diagnostics diags;
  loadText(R"({"version": 1, "resources": {"a": {"format": "rgba8"}, "b": {"format": "rgba8"}},
    "passes": [
      {"name": "f", "type": "fullscreen", "inputs": {"color": "a"}},
      {"name": "x", "type": "blit", "inputs": {"src": "a", "dst": "b"}, "outputs": {"dst": "b2", "zzz": "a"}},
      {"name": "d", "type": "decal", "inputs": {"color": "a"}},
      {"name": "e", "type": "decal"}
    ],
    "output": "b2"})",
           diags);
  std::vector<std::string> lines;
  for (const auto& d : diags) lines.push_back(formatDiagnostic(d));
  EXPECT_EQ(lines, (std::vector<std::string>{
                       "inline.json:3:7: error: /passes/0: output 'color' of pass 'f' (type fullscreen) is "
                       "required but not bound",
                       "inline.json:3:53: error: /passes/0/inputs: input 'source' of pass 'f' (type fullscreen) is "
                       "required but not bound",
                       "inline.json:4:98: error: /passes/1/outputs/zzz: pass 'x' (type blit) has no output slot "
                       "'zzz'; its slots are 'src', 'dst'",
                       "inline.json:5:7: error: /passes/2: output 'color' of pass 'd' (type decal) is "
                       "not bound but its input is: name the version the pass produces",
                   }))
      << allDiagnostics(diags);
}

TEST(ConfigBuild, NoSuggestionForFarNames) {
  Diagnostics diags;
  loadText(
      R"({"version": 1, "resources": {}, "passes": [{"name": "p", "type": "completely_different"}], "output": "x"})",
      diags);
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, DiagCode::unknown_pass_type);
  EXPECT_EQ(diags[0].message, "unknown pass type 'completely_different'");
}

TEST(ConfigBuild, BuildOnAFailedDocumentAddsNothing) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText("{", "bad.json", diags);
  EXPECT_FALSE(doc.ok());
  ASSERT_EQ(diags.size(), 1u);
  PipelineConfig cfg = doc.build(test::testRegistry(), diags);
  EXPECT_EQ(diags.size(), 1u);
  EXPECT_TRUE(cfg.graph.passes.empty());
  EXPECT_EQ(cfg.file, "bad.json");
}

TEST(ConfigBuild, MissingFile) {
  Diagnostics diags;
  const std::string path = test::configsDir() + "/does/not/exist.json";
  ConfigDocument doc = ConfigDocument::parseFile(path, diags);
  EXPECT_FALSE(doc.ok());
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, DiagCode::file_not_found);
  EXPECT_EQ(diags[0].where.file, path);
  EXPECT_EQ(formatDiagnostic(diags[0]),
            path + ": error: cannot read config file '" + path + "': No such file or directory");

  diags.clear();
  ConfigDocument dir = ConfigDocument::parseFile(test::configsDir(), diags);
  EXPECT_FALSE(dir.ok());
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, DiagCode::file_not_found);
  EXPECT_NE(diags[0].message.find("Is a directory"), std::string::npos) << diags[0].message;
}

TEST(ConfigBuild, MovedDocumentKeepsWorking) {
  Diagnostics diags;
  ConfigDocument a = ConfigDocument::parseText(R"({"x": 1})", "m.json", diags);
  ConfigDocument b = std::move(a);
  EXPECT_TRUE(b.ok());
  EXPECT_EQ(b.locate("/x").column, 7);
  ConfigDocument c;
  c = std::move(b);
  EXPECT_EQ(c.file(), "m.json");
  EXPECT_FALSE(c.build(test::testRegistry(), diags).graph.output.size());
  EXPECT_TRUE(hasErrors(diags));  // not a pipeline: missing keys, unknown key
}

}  // namespace
}  // namespace rgraph
