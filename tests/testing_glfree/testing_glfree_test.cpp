// rgraph/testing.h from a program linked only to the GL-free library
// (rgraph_check: graph, config, registry, plugin loader, shader checks): it
// links, and it works with a registry of the program's own pass types.
#include <gtest/gtest.h>

#include "rgraph/pass_check.h"
#include "rgraph/pass_decl.h"
#include "rgraph/registry.h"
#include "rgraph/testing.h"

namespace rt = rgraph::testing;
using namespace rgraph;

namespace {

// A pass type needs a factory; this one is never run (nothing executes here).
class NoopPass : public PassInstance {
 public:
  void execute(PassContext&) override {}
};

// Two GL-free pass types: "draw" writes a colour target (optionally reading
// one), "show" copies into the output and refuses different sizes (a check hook).
PassRegistry& ownRegistry() {
  static PassRegistry registry = [] {
    PassRegistry r;
    PassTypeDesc draw;
    draw.name = "draw";
    draw.slots = {decl::slot("in", Access::sampled, false, SlotDecl::Load::never, "input"),
                  decl::slot("out", Access::color_attachment, true, SlotDecl::Load::never, "output")};
    PassTypeDesc show;
    show.name = "show";
    show.slots = {decl::slot("src", Access::sampled, true, SlotDecl::Load::never, "source"),
                  decl::slot("dst", Access::color_attachment, true, SlotDecl::Load::never, "output")};
    show.check = [](const PassCheckContext& ctx, PassChecks& checks) { checkSameSize(ctx, checks, "src", "dst"); };
    draw.create = show.create = [] { return std::make_unique<NoopPass>(); };
    std::string error;
    if (!r.add(draw, &error) || !r.add(show, &error)) ADD_FAILURE() << error;
    return r;
  }();
  return registry;
}

const char* kPipeline = R"({
  "version": 1,
  "resources": {
    "a": { "format": "rgba16f" }, "b": { "format": "rgba16f" }, "c": { "format": "rgba16f" },
    "unused": { "format": "rgba8" }, "output": { "format": "rgba8" }
  },
  "passes": [
    { "name": "first", "type": "draw", "outputs": { "out": "a" } },
    { "name": "second", "type": "draw", "inputs": { "in": "a" }, "outputs": { "out": "b" } },
    { "name": "third", "type": "draw", "inputs": { "in": "b" }, "outputs": { "out": "c" } },
    { "name": "dangling", "type": "draw", "outputs": { "out": "unused" } },
    { "name": "present", "type": "show", "inputs": { "src": "c" }, "outputs": { "dst": "output" } }
  ],
  "output": "output"
})";

}  // namespace

TEST(TestingGlFree, OwnRegistryCompilesWithoutGl) {
  rt::Options o;
  o.size = {32, 16};
  o.registry = &ownRegistry();
  const rt::CompiledPipeline p = rt::compileText(kPipeline, o);
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_EQ(p.order(), (std::vector<std::string>{"first", "second", "third", "present"}));
  EXPECT_TRUE(p.culled("dangling"));
  EXPECT_TRUE(p.aliased("a", "c"));
  EXPECT_EQ(p.naiveBytes(), 3u * 32u * 16u * 8u);
  EXPECT_EQ(p.allocatedBytes(), 2u * 32u * 16u * 8u);
}

TEST(TestingGlFree, OwnCheckHookRuns) {
  std::string json = kPipeline;
  const std::string output = R"("output": { "format": "rgba8" })";
  json.replace(json.find(output), output.size(), R"("output": { "format": "rgba8", "size": [8, 8] })");
  rt::Options o;
  o.size = {32, 16};
  o.registry = &ownRegistry();
  const rt::CompiledPipeline p = rt::compileText(json, o);
  EXPECT_TRUE(p.hasError(DiagCode::pass_check)) << p.describe();
  EXPECT_TRUE(p.hasMessage("32x16")) << p.describe();
}

// Without librgraph nothing registers the built-in types: the default
// registry knows none, and says so per pass rather than crashing.
TEST(TestingGlFree, DefaultRegistryHasNoBuiltinsHere) {
  const rt::CompiledPipeline p = rt::compileText(kPipeline);
  EXPECT_FALSE(p.loaded());
  EXPECT_TRUE(p.hasError(DiagCode::unknown_pass_type)) << p.describe();
}

// History resources through rgraph/testing.h: the pass that only feeds the
// next frame runs, and describe()/describeResource() say why and what is kept.
TEST(TestingGlFree, HistoryIsDescribed) {
  const char* json = R"({
    "version": 1,
    "resources": {
      "a": { "format": "rgba16f" }, "trail": { "format": "rgba16f" }, "trail_prev": { "history_of": "trail" },
      "output": { "format": "rgba8" }
    },
    "passes": [
      { "name": "first", "type": "draw", "inputs": { "in": "trail_prev" }, "outputs": { "out": "a" } },
      { "name": "feed", "type": "draw", "inputs": { "in": "a" }, "outputs": { "out": "trail" } },
      { "name": "present", "type": "show", "inputs": { "src": "a" }, "outputs": { "dst": "output" } }
    ],
    "output": "output"
  })";
  rt::Options o;
  o.size = {32, 16};
  o.registry = &ownRegistry();
  const rt::CompiledPipeline p = rt::compileText(json, o);
  ASSERT_TRUE(p.ok()) << p.describe();
  EXPECT_EQ(p.order(), (std::vector<std::string>{"first", "feed", "present"}));
  EXPECT_FALSE(p.aliased("a", "trail")) << p.describe();
  const std::string d = p.describe();
  EXPECT_NE(d.find("kept: feed: it feeds 'trail', whose history 'trail_prev' is read in the next frame"),
            std::string::npos)
      << d;
  EXPECT_NE(d.find("history: trail_prev holds the previous frame of trail"), std::string::npos) << d;
  EXPECT_NE(p.describeResource("trail_prev").find("history of 'trail' (kept across frames)"), std::string::npos)
      << p.describeResource("trail_prev");
  EXPECT_NE(p.describeResource("trail").find("kept across frames in 'trail_prev'"), std::string::npos);
}
