// History resources and jitter in configs: "history_of" (the descriptor keys
// it omits come from its source), the top-level "jitter" and the pass key
// "jitter"; compile()'s history errors located in the file (line, column and
// JSON path).
#include <gtest/gtest.h>

#include <string>

#include "test_registry.h"

namespace rgraph {
namespace {

struct Loaded {
  PipelineConfig config;
  Diagnostics diags;  // the loader's, then compile()'s
  Plan plan;
};

Loaded loadAndCompile(const std::string& text) {
  Loaded out;
  ConfigDocument doc = ConfigDocument::parseText(text, "h.json", out.diags);
  EXPECT_TRUE(doc.ok());
  out.config = doc.build(test::testRegistry(), out.diags);
  out.plan = compile(out.config.graph);
  out.diags.insert(out.diags.end(), out.plan.diagnostics.begin(), out.plan.diagnostics.end());
  return out;
}

std::string lines(const Diagnostics& diags) {
  std::string s;
  for (const auto& d : diags) s += formatDiagnostic(d) + "\n";
  return s;
}

// resolved_prev's declaration is line 6; `prev` is its body.
std::string taa(const std::string& prev, const std::string& extraPass = "", const std::string& top = "") {
  return "{\n"
         "  \"version\": 1," +
         top +
         "\n"
         "  \"resources\": {\n"
         "    \"scene\": {\"format\": \"rgba16f\"}, \"depth\": {\"format\": \"depth32f\"},\n"
         "    \"resolved\": {\"format\": \"rgba16f\"},\n"
         "    \"resolved_prev\": " +
         prev +
         ",\n"
         "    \"ldr\": {\"format\": \"rgba8\"}\n"
         "  },\n"
         "  \"passes\": [\n"
         "    {\"name\": \"draw\", \"type\": \"geometry\", \"outputs\": {\"color\": \"scene\", \"depth\": "
         "\"depth\"}},\n"
         "    {\"name\": \"taa\", \"type\": \"fullscreen\", \"inputs\": {\"source\": \"scene\", \"aux\": "
         "\"resolved_prev\"},"
         " \"outputs\": {\"color\": \"resolved\"}},\n"
         "    {\"name\": \"present\", \"type\": \"fullscreen\", \"inputs\": {\"source\": \"resolved\"},"
         " \"outputs\": {\"color\": \"ldr\"}}" +
         extraPass +
         "\n"
         "  ],\n"
         "  \"output\": \"ldr\"\n"
         "}\n";
}

const Diagnostic* first(const Diagnostics& diags, DiagCode code) {
  for (const auto& d : diags)
    if (d.code == code) return &d;
  return nullptr;
}

TEST(HistoryConfig, ShippedExampleBuildsInheritsAndCompiles) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseFile(test::configsDir() + "/valid/history.json", diags);
  PipelineConfig cfg = doc.build(test::testRegistry(), diags);
  ASSERT_TRUE(diags.empty()) << lines(diags);
  EXPECT_EQ(cfg.jitterPhases, 8u);
  const ResourceDecl* prev = nullptr;
  for (const auto& r : cfg.graph.resources)
    if (r.name == "resolved_prev") prev = &r;
  ASSERT_NE(prev, nullptr);
  EXPECT_EQ(prev->historyOf, "resolved");
  EXPECT_EQ(prev->historyWhere.line, 9);
  EXPECT_EQ(prev->historyWhere.column, 37);
  EXPECT_EQ(prev->historyWhere.path, "/resources/resolved_prev/history_of");
  EXPECT_EQ(prev->texture.format, Format::rgba16f) << "format taken from the source";
  for (const auto& p : cfg.graph.passes) EXPECT_EQ(p.jitter, p.name != "overlay") << p.name;
  Plan plan = compile(cfg.graph);
  ASSERT_TRUE(plan.ok()) << lines(plan.diagnostics);
  EXPECT_TRUE(plan.resources[3].historyOf.valid());
  EXPECT_EQ(checkPlanContract(plan), "");
}

TEST(HistoryConfig, OmittedKeysComeFromTheSourceGivenOnesMustMatch) {
  Loaded same = loadAndCompile(taa(R"({"history_of": "resolved", "format": "rgba16f", "size": "output"})"));
  EXPECT_TRUE(same.plan.ok()) << lines(same.diags);

  Loaded ok = loadAndCompile(taa(R"({"history_of": "resolved"})"));
  EXPECT_FALSE(hasErrors(ok.diags)) << lines(ok.diags);

  Loaded bad = loadAndCompile(taa(R"({"history_of": "resolved", "size": {"scale": 0.5}})"));
  const Diagnostic* e = first(bad.diags, DiagCode::history_error);
  ASSERT_NE(e, nullptr) << lines(bad.diags);
  EXPECT_EQ(formatDiagnostic(*e),
            "h.json:6:22: error: /resources/resolved_prev: history resource 'resolved_prev' (rgba16f, scale 0.5 "
            "(640x360), 1 sample, 1 mip level) does not match its source 'resolved' (rgba16f, output size "
            "(1280x720), 1 sample, 1 mip level); a history holds its source's previous content and must have the "
            "same format, size, samples, mips and layers (leave them out to take the source's)");
}

TEST(HistoryConfig, ErrorsPointAtTheHistoryOfValue) {
  Loaded typo = loadAndCompile(taa(R"({"history_of": "resolvd"})"));
  const Diagnostic* e = first(typo.diags, DiagCode::history_error);
  ASSERT_NE(e, nullptr) << lines(typo.diags);
  EXPECT_EQ(formatDiagnostic(*e),
            "h.json:6:37: error: /resources/resolved_prev/history_of: history resource 'resolved_prev': "
            "\"history_of\" names 'resolvd', which is not a declared resource (did you mean 'resolved'?)");

  // The config makes the output imported: the graph cannot keep it.
  Loaded output = loadAndCompile(taa(R"({"history_of": "ldr"})"));
  e = first(output.diags, DiagCode::history_error);
  ASSERT_NE(e, nullptr) << lines(output.diags);
  EXPECT_EQ(e->where.path, "/resources/resolved_prev/history_of");
  EXPECT_NE(e->message.find("keeps the output image 'ldr'"), std::string::npos) << e->message;
}

TEST(HistoryConfig, PassWritingAHistoryIsAnErrorAtItsOutput) {
  Loaded l = loadAndCompile(
      taa(R"({"history_of": "resolved"})",
          ",\n    {\"name\": \"w\", \"type\": \"readback\", \"inputs\": {\"src\": \"resolved\"}},"
          "\n    {\"name\": \"bad\", \"type\": \"decal\", \"outputs\": {\"color\": \"resolved_prev\"}}"));
  const Diagnostic* e = first(l.diags, DiagCode::history_error);
  ASSERT_NE(e, nullptr) << lines(l.diags);
  EXPECT_EQ(e->where.line, 14);
  EXPECT_EQ(e->where.path, "/passes/4/outputs/color");
  EXPECT_NE(e->message.find("written by the executor, not by passes"), std::string::npos) << e->message;
}

TEST(HistoryConfig, HistoryOfKeyValues) {
  Loaded notString = loadAndCompile(taa(R"({"history_of": 3})"));
  EXPECT_NE(lines(notString.diags)
                .find("h.json:6:37: error: /resources/resolved_prev/history_of: expected the name "
                      "of the resource whose previous frame this one holds, got int"),
            std::string::npos)
      << lines(notString.diags);
  EXPECT_EQ(lines(notString.diags).find("has no \"format\""), std::string::npos)
      << "a declared history (even a wrong one) needs no format\n"
      << lines(notString.diags);
  Loaded typoKey = loadAndCompile(taa(R"({"histroy_of": "resolved", "format": "rgba16f"})"));
  EXPECT_NE(lines(typoKey.diags).find("unknown resource key 'histroy_of' (did you mean 'history_of'?)"),
            std::string::npos)
      << lines(typoKey.diags);
}

TEST(HistoryConfig, JitterPhases) {
  struct Case {
    const char* value;
    const char* message;  // empty: accepted
    uint32_t phases;
  } cases[] = {
      {"0", "", 0},
      {"2", "", 2},
      {"16", "", 16},
      {"64", "", 64},
      {"1", "h.json:2:27: error: /jitter: jitter 1 is a fixed offset, not jitter", 0},
      {"65", "h.json:2:27: error: /jitter: jitter 65 is too large", 0},
      {"-2", "h.json:2:27: error: /jitter: jitter -2 is too small", 0},
      {"\"8\"", "h.json:2:27: error: /jitter: expected an integer (0: off, or 2 to 64 Halton phases), got string", 0},
      {"2.5", "h.json:2:27: error: /jitter:", 0},
  };
  for (const Case& c : cases) {
    Loaded l = loadAndCompile(taa(R"({"history_of": "resolved"})", "", std::string(" \"jitter\": ") + c.value + ","));
    if (*c.message == 0) {
      EXPECT_FALSE(hasErrors(l.diags)) << c.value << "\n" << lines(l.diags);
      EXPECT_EQ(l.config.jitterPhases, c.phases) << c.value;
    } else {
      EXPECT_NE(lines(l.diags).find(c.message), std::string::npos) << c.value << "\n" << lines(l.diags);
      EXPECT_EQ(l.config.jitterPhases, 0u) << c.value;
    }
  }
}

TEST(HistoryConfig, PassJitterKey) {
  Loaded l = loadAndCompile(
      taa(R"({"history_of": "resolved"})",
          ",\n    {\"name\": \"ui\", \"type\": \"decal\", \"jitter\": \"off\", \"outputs\": {\"color\": \"scene\"}}"));
  EXPECT_NE(lines(l.diags).find("h.json:13:47: error: /passes/3/jitter: expected true or false, got string"),
            std::string::npos)
      << lines(l.diags);
}

}  // namespace
}  // namespace rgraph

namespace rgraph {
namespace {

// "persistent" (ResourceDecl::persistent): true or false, anything else located.
TEST(PersistentConfig, ParsedAndAWrongTypeIsLocated) {
  Loaded l = loadAndCompile(R"({
  "version": 1,
  "resources": {
    "lut": {"format": "rgba8", "size": [4, 4], "persistent": true},
    "bad": {"format": "rgba8", "size": [4, 4], "persistent": "yes"},
    "out": {"format": "rgba8"}
  },
  "passes": [
    {"name": "a", "type": "fullscreen", "outputs": {"color": "lut"}},
    {"name": "b", "type": "fullscreen", "inputs": {"source": "lut"}, "outputs": {"color": "out"}}
  ],
  "output": "out"
})");
  bool lutPersistent = false;
  for (const auto& r : l.config.graph.resources)
    if (r.name == "lut") lutPersistent = r.persistent;
  EXPECT_TRUE(lutPersistent);
  const std::string all = lines(l.diags);
  EXPECT_NE(all.find("h.json:5:62"), std::string::npos) << all;
  EXPECT_NE(all.find("/resources/bad/persistent"), std::string::npos) << all;
  EXPECT_NE(all.find("true or false"), std::string::npos) << all;
}

}  // namespace
}  // namespace rgraph
