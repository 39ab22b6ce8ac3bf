// The pass key "samplers" (per-slot sampler-state overrides, see
// docs/pipeline-format.md): what it builds, and every diagnostic it gives,
// located at the value at fault (file:line:col and JSON path).
#include <gtest/gtest.h>

#include <string>

#include "rgraph/pass.h"
#include "test_registry.h"

namespace rgraph {
namespace {

// The test registry's fullscreen type (source, aux sampled; color written),
// and "shadowed": the same with a declared state on "source".
SamplerState declaredState() {
  SamplerState s;
  s.filter = SamplerState::Filter::nearest;
  s.compare = SamplerState::Compare::less_equal;
  s.wrap = {SamplerState::Wrap::border, SamplerState::Wrap::border, SamplerState::Wrap::border};
  s.border = {1.0f, 1.0f, 1.0f, 1.0f};
  return s;
}

const PassRegistry& registry() {
  static const PassRegistry r = [] {
    PassRegistry out;
    PassTypeDesc plain = *test::testRegistry().find("fullscreen");
    PassTypeDesc shadowed = plain;
    shadowed.name = "shadowed";
    for (auto& s : shadowed.slots)
      if (s.name == "source") s.sampler = declaredState();
    out.add(std::move(plain));
    out.add(std::move(shadowed));
    return out;
  }();
  return r;
}

// A pipeline whose second pass (type `type`) has `"samplers": SAMPLERS` on
// line 10, starting at column 19.
std::string pipeline(const std::string& samplers, const std::string& type = "fullscreen") {
  return R"({
  "version": 1,
  "resources": {
    "a": { "format": "rgba8", "size": "output" },
    "b": { "format": "rgba8", "size": "output" }
  },
  "passes": [
    { "name": "first", "type": "fullscreen", "inputs": { "source": "a" }, "outputs": { "color": "a" } },
    { "name": "second", "type": ")" + type + R"(", "inputs": { "source": "a" }, "outputs": { "color": "b" },
      "samplers": )" + samplers + R"( }
  ],
  "output": "b"
})";
}

struct Built {
  std::string text;
  Diagnostics diags;
  PipelineConfig config;
};

Built build(const std::string& samplers, const std::string& type = "fullscreen") {
  Built b;
  b.text = pipeline(samplers, type);
  ConfigDocument doc = ConfigDocument::parseText(b.text, "inline.json", b.diags);
  EXPECT_TRUE(doc.ok()) << b.text;
  b.config = doc.build(registry(), b.diags);
  return b;
}

std::string all(const Diagnostics& diags) {
  std::string out;
  for (const auto& d : diags) out += formatDiagnostic(d) + "\n";
  return out;
}

// The one diagnostic `b` gave: its severity, path, a text it contains, and
// its line:col equal to where `token` first appears on the samplers line.
void expectOne(const Built& b, Severity sev, const std::string& path, const std::string& text,
               const std::string& token) {
  ASSERT_EQ(b.diags.size(), 1u) << all(b.diags);
  const Diagnostic& d = b.diags[0];
  EXPECT_EQ(d.severity, sev) << formatDiagnostic(d);
  EXPECT_EQ(d.where.file, "inline.json");
  EXPECT_EQ(d.where.path, path) << formatDiagnostic(d);
  EXPECT_NE(d.message.find(text), std::string::npos) << formatDiagnostic(d);
  EXPECT_EQ(d.pass, "second") << formatDiagnostic(d);
  const size_t lineStart = b.text.find("      \"samplers\": ");
  ASSERT_NE(lineStart, std::string::npos);
  const size_t at = b.text.find(token, lineStart);
  ASSERT_NE(at, std::string::npos) << token;
  EXPECT_EQ(d.where.line, 10) << formatDiagnostic(d);
  EXPECT_EQ(d.where.column, static_cast<int>(at - lineStart) + 1) << formatDiagnostic(d);
}

const SlotDecl& slotOf(const std::string& type, const std::string& slot) {
  return *registry().find(type)->findSlot(slot);
}

TEST(SamplerConfig, EveryKeyIsRead) {
  Built b = build(R"({ "source": { "filter": "nearest", "mip": "linear", "wrap": { "s": "repeat", "t": "mirror", "r": "border" },
      "border": [0.25, 0.5, 0.75, 1], "compare": "greater_equal", "anisotropy": 8 } })");
  ASSERT_TRUE(b.diags.empty()) << all(b.diags);
  ASSERT_EQ(b.config.samplers.size(), 2u);
  EXPECT_TRUE(b.config.samplers[0].empty());
  ASSERT_EQ(b.config.samplers[1].size(), 1u);
  const SamplerOverride& o = b.config.samplers[1][0];
  EXPECT_EQ(o.slot, "source");
  EXPECT_EQ(o.where.line, 10);
  EXPECT_EQ(o.where.path, "/passes/1/samplers/source");
  const SamplerState& s = o.state;
  EXPECT_EQ(s.filter, SamplerState::Filter::nearest);
  EXPECT_EQ(s.mip, SamplerState::MipFilter::linear);
  EXPECT_EQ(s.wrap[0], SamplerState::Wrap::repeat);
  EXPECT_EQ(s.wrap[1], SamplerState::Wrap::mirror);
  EXPECT_EQ(s.wrap[2], SamplerState::Wrap::border);
  EXPECT_EQ(s.border, (std::array<float, 4>{0.25f, 0.5f, 0.75f, 1.0f}));
  EXPECT_EQ(s.compare, SamplerState::Compare::greater_equal);
  EXPECT_EQ(s.anisotropy, 8.0f);
}

TEST(SamplerConfig, OneWrapForEveryAxis) {
  Built b = build(R"({ "aux": { "wrap": "border" } })");  // every axis
  ASSERT_TRUE(b.diags.empty()) << all(b.diags);
  const SamplerState& s = b.config.samplers[1][0].state;
  EXPECT_EQ(s.wrap, (std::array<SamplerState::Wrap, 3>{SamplerState::Wrap::border, SamplerState::Wrap::border,
                                                         SamplerState::Wrap::border}));
}

// The override applies on top of the declared state; passes without one keep it.
TEST(SamplerConfig, OverrideAppliesOnTopOfTheDeclaredState) {
  Built b = build(R"({ "source": { "filter": "linear" } })", "shadowed");
  ASSERT_TRUE(b.diags.empty()) << all(b.diags);
  SamplerState want = declaredState();
  want.filter = SamplerState::Filter::linear;
  SourceLocation where;
  std::optional<SamplerState> s = slotSamplerState(b.config, 1, slotOf("shadowed", "source"), &where);
  ASSERT_TRUE(s.has_value());
  EXPECT_EQ(*s, want);
  EXPECT_EQ(where.path, "/passes/1/samplers/source");
  // "aux" declares none and is not overridden: the texture's own parameters.
  EXPECT_FALSE(slotSamplerState(b.config, 1, slotOf("shadowed", "aux")).has_value());
  // Pass 0 (no "samplers") and a pass index past the list: the declaration.
  EXPECT_EQ(slotSamplerState(b.config, 0, slotOf("shadowed", "source")), declaredState());
  EXPECT_EQ(slotSamplerState(b.config, 7, slotOf("shadowed", "source")), declaredState());
  EXPECT_FALSE(slotSamplerState(b.config, 0, slotOf("fullscreen", "source")).has_value());
}

TEST(SamplerConfig, NotAnObject) {
  expectOne(build(R"("nearest")"), Severity::error, "/passes/1/samplers",
            "expected an object mapping sampled slots to sampler states, got string", "\"nearest\"");
}

TEST(SamplerConfig, UnknownSlot) {
  expectOne(build(R"({ "sorce": { "filter": "nearest" } })"), Severity::error, "/passes/1/samplers/sorce",
            "has no slot 'sorce' (did you mean 'source'?)", "\"sorce\"");
  expectOne(build(R"({ "zzzzzzzz": {} })"), Severity::error, "/passes/1/samplers/zzzzzzzz",
            "its sampled slots are 'source', 'aux'", "\"zzzzzzzz\"");
  EXPECT_EQ(build(R"({ "sorce": {} })").diags[0].code, DiagCode::unknown_slot);
}

TEST(SamplerConfig, SlotThatIsNotSampled) {
  expectOne(build(R"({ "color": { "filter": "nearest" } })"), Severity::error, "/passes/1/samplers/color",
            "slot 'color' of pass 'second' (type fullscreen) is not sampled (color_attachment)", "\"color\"");
}

TEST(SamplerConfig, StateNotAnObject) {
  expectOne(build(R"({ "source": "nearest" })"), Severity::error, "/passes/1/samplers/source",
            "expected a sampler state object (keys 'filter', 'mip', 'wrap', 'border', 'compare', 'anisotropy')",
            "\"nearest\"");
}

TEST(SamplerConfig, UnknownKey) {
  expectOne(build(R"({ "source": { "filtr": "nearest" } })"), Severity::error, "/passes/1/samplers/source/filtr",
            "unknown sampler key 'filtr' (did you mean 'filter'?)", "\"filtr\"");
}

TEST(SamplerConfig, BadFilter) {
  expectOne(build(R"({ "source": { "filter": "neerest" } })"), Severity::error, "/passes/1/samplers/source/filter",
            "unknown filter 'neerest' (did you mean 'nearest'?)", "\"neerest\"");
  expectOne(build(R"({ "source": { "filter": "cubicspline" } })"), Severity::error,
            "/passes/1/samplers/source/filter", "unknown filter 'cubicspline'; expected one of 'nearest', 'linear'",
            "\"cubicspline\"");
  expectOne(build(R"({ "source": { "filter": 2 } })"), Severity::error, "/passes/1/samplers/source/filter",
            "expected a filter name (one of 'nearest', 'linear'), got int", "2");
}

TEST(SamplerConfig, BadMipFilter) {
  expectOne(build(R"({ "source": { "mip": "trilinear" } })"), Severity::error, "/passes/1/samplers/source/mip",
            "unknown mip filter 'trilinear'", "\"trilinear\"");
}

TEST(SamplerConfig, BadCompare) {
  expectOne(build(R"({ "source": { "compare": "lequal" } })"), Severity::error, "/passes/1/samplers/source/compare",
            "unknown compare mode 'lequal'", "\"lequal\"");
  expectOne(build(R"({ "source": { "compare": true } })"), Severity::error, "/passes/1/samplers/source/compare",
            "expected a compare mode name (one of 'none', 'never', 'less', 'less_equal'", "true");
}

TEST(SamplerConfig, BadWrap) {
  expectOne(build(R"({ "source": { "wrap": "wrapped" } })"), Severity::error, "/passes/1/samplers/source/wrap",
            "unknown wrap mode 'wrapped'; expected one of 'clamp', 'repeat', 'mirror', 'border'", "\"wrapped\"");
  expectOne(build(R"({ "source": { "wrap": 1 } })"), Severity::error, "/passes/1/samplers/source/wrap",
            "expected a wrap mode (one of 'clamp', 'repeat', 'mirror', 'border') or an object of axes", "1");
  expectOne(build(R"({ "source": { "wrap": { "x": "repeat" } } })"), Severity::error,
            "/passes/1/samplers/source/wrap/x", "unknown wrap axis 'x'", "\"x\"");
  expectOne(build(R"({ "source": { "wrap": { "t": "repaet" } } })"), Severity::error,
            "/passes/1/samplers/source/wrap/t", "unknown wrap mode 'repaet' (did you mean 'repeat'?)", "\"repaet\"");
}

TEST(SamplerConfig, BadBorder) {
  expectOne(build(R"({ "source": { "wrap": "border", "border": "white" } })"), Severity::error,
            "/passes/1/samplers/source/border", "expected a border colour (an array of 4 numbers), got string",
            "\"white\"");
  expectOne(build(R"({ "source": { "wrap": "border", "border": [1, 1, 1] } })"), Severity::error,
            "/passes/1/samplers/source/border", "a border colour has 4 components (r, g, b, a), got 3", "[1, 1, 1]");
  expectOne(build(R"({ "source": { "wrap": "border", "border": [1, "x", 1, 1] } })"), Severity::error,
            "/passes/1/samplers/source/border/1", "expected a number, got string", "\"x\"");
  expectOne(build(R"({ "source": { "wrap": "border", "border": [1, 1, 1e300, 1] } })"), Severity::error,
            "/passes/1/samplers/source/border/2", "border colour component 1e+300", "1e300");
}

TEST(SamplerConfig, BorderWithoutBorderWrapIsAWarning) {
  Built b = build(R"({ "source": { "border": [1, 0, 0, 1] } })");
  expectOne(b, Severity::warning, "/passes/1/samplers/source/border",
            "a border colour has no effect unless an axis wraps with \"border\"", "[1, 0, 0, 1]");
  EXPECT_FALSE(hasErrors(b.diags));
  // One axis with border is enough.
  EXPECT_TRUE(build(R"({ "source": { "border": [1, 0, 0, 1], "wrap": { "t": "border" } } })").diags.empty());
}

TEST(SamplerConfig, BadAnisotropy) {
  expectOne(build(R"({ "source": { "anisotropy": 17 } })"), Severity::error, "/passes/1/samplers/source/anisotropy",
            "anisotropy 17 is out of range: from 1 (off) to 16", "17");
  expectOne(build(R"({ "source": { "anisotropy": 0.5 } })"), Severity::error,
            "/passes/1/samplers/source/anisotropy", "anisotropy 0.5 is out of range", "0.5");
  expectOne(build(R"({ "source": { "anisotropy": "max" } })"), Severity::error,
            "/passes/1/samplers/source/anisotropy", "expected a number from 1 to 16, got string", "\"max\"");
}

// Several problems in one entry are all reported, and the good keys still read.
TEST(SamplerConfig, AllProblemsReportedGoodKeysKept) {
  Built b = build(R"({ "source": { "filter": "nearest", "mip": 3, "compare": "less", "anisotropy": 99 } })");
  EXPECT_EQ(b.diags.size(), 2u) << all(b.diags);
  ASSERT_EQ(b.config.samplers.size(), 2u);
  ASSERT_EQ(b.config.samplers[1].size(), 1u);
  EXPECT_EQ(b.config.samplers[1][0].state.filter, SamplerState::Filter::nearest);
  EXPECT_EQ(b.config.samplers[1][0].state.compare, SamplerState::Compare::less);
}

TEST(SamplerState, NamesRoundTrip) {
  for (const auto& n : filterNames()) EXPECT_EQ(filterName(*parseFilter(n)), n);
  for (const auto& n : mipFilterNames()) EXPECT_EQ(mipFilterName(*parseMipFilter(n)), n);
  for (const auto& n : wrapNames()) EXPECT_EQ(wrapName(*parseWrap(n)), n);
  for (const auto& n : compareNames()) EXPECT_EQ(compareName(*parseCompare(n)), n);
  EXPECT_EQ(compareNames().size(), 9u);
  EXPECT_FALSE(parseCompare("lequal").has_value());
  EXPECT_EQ(describeSampler(declaredState()), "nearest, mip none, wrap border (border 1 1 1 1), compare less_equal");
}

}  // namespace
}  // namespace rgraph
