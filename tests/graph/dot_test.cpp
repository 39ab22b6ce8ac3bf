// Graphviz export.
#include <gtest/gtest.h>

#include <regex>

#include "graph_builder.h"
#include "rgraph/graph.h"

using namespace rgraph;
using namespace rgraph::testgen;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// The node id of the line whose label starts with `label`.
std::string nodeId(const std::string& dot, const std::string& label) {
  std::smatch m;
  std::regex re("\\n  ([pv][0-9]+) \\[[^\\n]*label=\"" + label + "[\\\\\"]");
  if (std::regex_search(dot, m, re)) return m[1];
  return "";
}

std::string lineOf(const std::string& dot, const std::string& id) {
  size_t at = dot.find("\n  " + id + " [");
  if (at == std::string::npos) return "";
  size_t end = dot.find('\n', at + 1);
  return dot.substr(at + 1, end - at - 1);
}

TEST(Dot, PassesVersionsEdgesCullingAndAliasing) {
  GraphDesc d;
  d.resources = {tex("t0"), tex("t1"), tex("t2"), tex("debug_view"), importedTex("out", false)};
  d.passes = {
      pass("p0", {wr("color", "t0")}),
      pass("p1", {rd("src", "t0"), wr("color", "t1")}),
      pass("p2", {rd("src", "t1"), wr("color", "t2")}),
      pass("debug", {rd("src", "t1"), wr("color", "debug_view")}),
      pass("present", {rd("src", "t2"), wr("color", "out")}),
      pass("blend", {rmw("color", "out", "out_ui")}),
  };
  d.output = "out_ui";  // the final version (naming "out" would show the image before blend)
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  ASSERT_EQ(plan.resources[0].physical, plan.resources[2].physical);  // t0 and t2 alias
  const std::string dot = toDot(d, plan);

  EXPECT_EQ(dot.rfind("digraph", 0), 0u);
  EXPECT_EQ(dot.back(), '\n');
  EXPECT_TRUE(contains(dot, "}\n"));
  const std::string p1 = nodeId(dot, "p1"), debug = nodeId(dot, "debug"), blend = nodeId(dot, "blend");
  const std::string t0 = nodeId(dot, "t0"), t1 = nodeId(dot, "t1"), t2 = nodeId(dot, "t2");
  const std::string out = nodeId(dot, "out"), outUi = nodeId(dot, "out_ui");
  for (const auto* id : {&p1, &debug, &blend, &t0, &t1, &t2, &out, &outUi}) ASSERT_FALSE(id->empty()) << dot;
  // Shapes.
  EXPECT_TRUE(contains(lineOf(dot, p1), "shape=box"));
  EXPECT_TRUE(contains(lineOf(dot, t1), "shape=ellipse"));
  // Edges: version -> pass for reads, pass -> version for writes, loads too.
  EXPECT_TRUE(contains(dot, "  " + t0 + " -> " + p1 + " ")) << dot;
  EXPECT_TRUE(contains(dot, "  " + p1 + " -> " + t1 + " ")) << dot;
  EXPECT_TRUE(contains(dot, "  " + out + " -> " + blend + " ")) << dot;
  EXPECT_TRUE(contains(dot, "  " + blend + " -> " + outUi + " ")) << dot;
  // The culled pass is dashed grey and says why.
  const std::string debugLine = lineOf(dot, debug);
  EXPECT_TRUE(contains(debugLine, "style=dashed")) << debugLine;
  EXPECT_TRUE(contains(debugLine, "color=grey")) << debugLine;
  EXPECT_TRUE(contains(debugLine, "never read")) << debugLine;
  EXPECT_FALSE(contains(lineOf(dot, p1), "dashed"));
  // Aliased t0/t2 share a fill colour and a "phys #N" line; t1 differs.
  const std::string phys = "phys #" + std::to_string(plan.resources[0].physical.value());
  EXPECT_TRUE(contains(lineOf(dot, t0), phys)) << lineOf(dot, t0);
  EXPECT_TRUE(contains(lineOf(dot, t2), phys)) << lineOf(dot, t2);
  EXPECT_FALSE(contains(lineOf(dot, t1), phys));
  auto fill = [&](const std::string& id) {
    std::smatch m;
    std::string line = lineOf(dot, id);
    return std::regex_search(line, m, std::regex("fillcolor=\"([^\"]+)\"")) ? std::string(m[1]) : std::string();
  };
  EXPECT_FALSE(fill(t0).empty());
  EXPECT_EQ(fill(t0), fill(t2));
  EXPECT_NE(fill(t0), fill(t1));
  // The output version is marked.
  EXPECT_TRUE(contains(lineOf(dot, outUi), "(output)"));
}

TEST(Dot, EscapesQuotesInNames) {
  GraphDesc d;
  d.resources = {tex("my \"tex\""), importedTex("out", false)};
  d.passes = {pass("say \"hi\"", {wr("color", "my \"tex\"")}),
              pass("present", {rd("src", "my \"tex\""), wr("color", "out")})};
  d.output = "out";
  Plan plan = compile(d);
  ASSERT_TRUE(plan.ok()) << dumpDiagnostics(plan);
  const std::string dot = toDot(d, plan);
  EXPECT_TRUE(contains(dot, "label=\"say \\\"hi\\\"")) << dot;
  EXPECT_TRUE(contains(dot, "label=\"my \\\"tex\\\"")) << dot;
  EXPECT_FALSE(contains(dot, "say \"hi")) << dot;
}

}  // namespace
