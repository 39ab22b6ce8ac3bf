// A check that spans two passes: a G-buffer reader's "layout" against the
// layout its writer wrote the G-buffer with (gbuffer::sameLayoutAsWriterRule,
// through PassCheckContext::writer), run without GL by runPassChecks.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string>

#include "rgraph/config.h"
#include "rgraph/registry.h"
#include "rgraph/pipeline_load.h"

namespace fs = std::filesystem;
using namespace rgraph;

namespace {

const std::string kChecks = std::string(RGRAPH_SOURCE_DIR) + "/tests/configs/invalid/checks";

std::string lines(const Diagnostics& diags) {
  std::string out;
  for (const auto& d : diags) out += formatDiagnostic(d) + "\n";
  return out;
}

struct Loaded {
  PipelineConfig pipeline;
  Plan plan;
};

Loaded load(const std::string& path, const PassRegistry& registry = processRegistry()) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseFile(path, diags);
  EXPECT_TRUE(doc.ok()) << lines(diags);
  Loaded l;
  l.pipeline = doc.build(registry, diags);
  EXPECT_FALSE(hasErrors(diags)) << lines(diags);
  l.plan = compile(l.pipeline.graph);
  EXPECT_TRUE(l.plan.ok());
  return l;
}

// A pipeline file of the test's own, removed at the end.
class TempPipeline {
 public:
  TempPipeline(const std::string& name, const std::string& text)
      : path_(fs::temp_directory_path() / ("rgraph-" + name + "-" + std::to_string(::getpid()) + ".json")) {
    std::ofstream(path_) << text;
  }
  ~TempPipeline() {
    std::error_code ec;
    fs::remove(path_, ec);
  }
  std::string str() const { return path_.string(); }

 private:
  fs::path path_;
};

TEST(GBufferLayoutCheck, AReaderOfAnotherLayoutThanItsWriterIsRefusedNamingBothPassesAndPlaces) {
  const std::string file = kChecks + "/gbuffer_layout_mismatch.json";
  Loaded l = load(file);
  const Diagnostics d = runPassChecks(l.pipeline, l.plan, processRegistry());
  ASSERT_EQ(d.size(), 1u) << lines(d);  // once per writer, not once per slot it wrote
  EXPECT_EQ(d[0].code, DiagCode::pass_check);
  EXPECT_EQ(d[0].pass, "lighting");
  // At the reader's layout ...
  EXPECT_EQ(d[0].where.path, "/passes/1/params/layout");
  EXPECT_EQ(d[0].where.line, 16);
  EXPECT_EQ(d[0].where.column, 76);
  // ... naming the writer, what it wrote and where its own layout is set.
  EXPECT_EQ(d[0].message,
            "deferred_lighting pass 'lighting': layout 'learnopengl' is not the layout of the G-buffer it reads: "
            "geometry pass 'gbuffer' writes 'gPosition' ('position') with layout 'pbr' (" +
                file + ":14:66); give both passes the same \"layout\"");
}

// A reader that leaves "layout" at its default (pbr) under a compact writer:
// located at the reader pass (no param to point at), the writer's at its param.
TEST(GBufferLayoutCheck, ADefaultLayoutIsComparedToo) {
  TempPipeline p("layout-default",
                 "{\"version\": 1, \"resources\": {\"n\": {\"format\": \"rg16f\"}, \"a\": {\"format\": \"rgba8\"},\n"
                 "  \"m\": {\"format\": \"rg8\"}, \"d\": {\"format\": \"depth32f\"}, \"o\": {\"format\": \"rgba8\"}},\n"
                 " \"passes\": [{\"name\": \"g\", \"type\": \"geometry\", \"params\": {\"layout\": \"compact\"},\n"
                 "   \"outputs\": {\"normal\": \"n\", \"albedo\": \"a\", \"material\": \"m\", \"depth\": \"d\"}},\n"
                 "  {\"name\": \"v\", \"type\": \"gbuffer_view\", \"inputs\": {\"normal\": \"n\", \"albedo\": \"a\",\n"
                 "   \"material\": \"m\", \"depth\": \"d\", \"position\": \"n\"}, \"outputs\": {\"color\": \"o\"}}],\n"
                 " \"output\": \"o\"}\n");
  Loaded l = load(p.str());
  const Diagnostics d = runPassChecks(l.pipeline, l.plan, processRegistry());
  const Diagnostic* layout = nullptr;
  for (const auto& x : d)
    if (x.message.find("is not the layout of the G-buffer") != std::string::npos) layout = &x;
  ASSERT_NE(layout, nullptr) << lines(d);
  EXPECT_EQ(layout->where.path, "/passes/1");
  EXPECT_NE(layout->message.find("layout 'pbr' is not the layout"), std::string::npos) << layout->message;
  // position is bound to n, which g wrote through 'normal': only same-named slots count, so 'normal' is named.
  EXPECT_NE(layout->message.find("geometry pass 'g' writes 'n' ('normal') with layout 'compact' (" + p.str() + ":3:68)"),
            std::string::npos)
      << layout->message;
}

// Matching layouts pass (every shipped pipeline validates: the cli tests).
TEST(GBufferLayoutCheck, MatchingLayoutsPass) {
  Loaded l = load(std::string(RGRAPH_SOURCE_DIR) + "/pipelines/deferred-compact.json");
  EXPECT_EQ(lines(runPassChecks(l.pipeline, l.plan, processRegistry())), "");
}

// What PassCheckContext::writer gives a check: the writing pass, its slot and
// params (defaults filled in), and where its params are; nothing for a
// written slot, an unbound one or a version no pass writes.
TEST(GBufferLayoutCheck, WriterFindsThePassThatWroteTheVersionASlotReads) {
  PassRegistry registry;
  ParamDecl level;
  level.name = "level";
  level.type = ParamType::integer;
  level.defaultValue = int64_t{7};
  PassTypeDesc writer;
  writer.name = "writer";
  writer.slots = {SlotDecl{"color", Access::color_attachment}};
  writer.params = {level};
  writer.create = [] { return std::unique_ptr<PassInstance>(); };  // never run here
  struct Seen {
    std::optional<SlotWriter> src, unbound, color;
    int64_t level = 0;
    SourceLocation levelWhere;
  };
  static Seen seen;
  PassTypeDesc reader;
  reader.name = "reader";
  reader.slots = {SlotDecl{"src", Access::sampled}, SlotDecl{"aux", Access::sampled, false},
                  SlotDecl{"color", Access::color_attachment}};
  reader.check = [](const PassCheckContext& ctx, PassChecks&) {
    seen.src = ctx.writer("src");
    seen.unbound = ctx.writer("aux");
    seen.color = ctx.writer("color");
    if (seen.src) {
      seen.level = seen.src->params->getInt("level");
      seen.levelWhere = seen.src->paramWhere("level");
    }
  };
  reader.create = writer.create;
  std::string error;
  ASSERT_TRUE(registry.add(writer, &error)) << error;
  ASSERT_TRUE(registry.add(reader, &error)) << error;
  TempPipeline p("writer", "{\"version\": 1, \"resources\": {\"a\": {\"format\": \"rgba8\"}, \"o\": {\"format\": \"rgba8\"}},\n"
                           " \"passes\": [{\"name\": \"w\", \"type\": \"writer\", \"outputs\": {\"color\": \"a\"}},\n"
                           "   {\"name\": \"r\", \"type\": \"reader\", \"inputs\": {\"src\": \"a\"}, \"outputs\": {\"color\": \"o\"}}],\n"
                           " \"output\": \"o\"}\n");
  Loaded l = load(p.str(), registry);
  EXPECT_EQ(lines(runPassChecks(l.pipeline, l.plan, registry)), "");
  ASSERT_TRUE(seen.src.has_value());
  EXPECT_EQ(seen.src->pass, "w");
  EXPECT_EQ(seen.src->type, "writer");
  EXPECT_EQ(seen.src->slot, "color");
  EXPECT_EQ(seen.level, 7);  // the declared default: the config sets none
  EXPECT_EQ(seen.levelWhere.path, "/passes/0");  // left at its default: the pass
  EXPECT_EQ(seen.levelWhere.line, 2);
  EXPECT_FALSE(seen.unbound.has_value());
  EXPECT_FALSE(seen.color.has_value());
}

}  // namespace
