// Pass check hooks run without GL (rgraph/pass_check.h), and the on-disk cache
// of the shader checks (rgraph/shader_check_cache.h).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "rgraph/config.h"
#include "rgraph/registry.h"
#include "rgraph/shader_check.h"
#include "rgraph/shader_check_cache.h"
#include "rgraph/pipeline_load.h"

namespace fs = std::filesystem;
using namespace rgraph;

namespace {

const std::string kChecks = std::string(RGRAPH_SOURCE_DIR) + "/tests/configs/invalid/checks";
const std::string kPipelines = std::string(RGRAPH_SOURCE_DIR) + "/pipelines";

struct Loaded {
  PipelineConfig pipeline;
  Plan plan;
};

Loaded load(const std::string& path) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseFile(path, diags);
  EXPECT_TRUE(doc.ok());
  Loaded l;
  l.pipeline = doc.build(processRegistry(), diags);
  EXPECT_FALSE(hasErrors(diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  l.plan = compile(l.pipeline.graph);
  return l;
}

std::string lines(const Diagnostics& diags) {
  std::string out;
  for (const auto& d : diags) out += formatDiagnostic(d) + "\n";
  return out;
}

class TempDir {
 public:
  TempDir() : path_(fs::temp_directory_path() / ("rgraph-cache-test-" + std::to_string(::getpid()))) {
    fs::remove_all(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string str() const { return path_.string(); }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

TEST(PassChecks, ShippedPipelinesPassEveryCheckWithAScene) {
  for (const char* name : {"default.json", "deferred-pbr.json", "deferred-tiled.json", "deferred-compact.json",
                           "forward.json", "gbuffer-debug.json"}) {
    Loaded l = load(kPipelines + "/" + name);
    PassCheckOptions o;
    o.scenePresent = true;
    EXPECT_EQ(lines(runPassChecks(l.pipeline, l.plan, processRegistry(), o)), "") << name;
  }
}

TEST(PassChecks, SceneIsRequiredOnlyWhenKnownToBeAbsent) {
  Loaded l = load(kPipelines + "/deferred-pbr.json");
  PassCheckOptions unknown;  // plain validate: no scene named, none refused
  EXPECT_EQ(lines(runPassChecks(l.pipeline, l.plan, processRegistry(), unknown)), "");
  PassCheckOptions none;
  none.scenePresent = false;
  const Diagnostics d = runPassChecks(l.pipeline, l.plan, processRegistry(), none);
  // geometry, deferred_lighting and forward draw the scene, environment_background and
  // environment_cube read its environment; depth_blit, the other pre-filter passes and tonemap do not.
  ASSERT_EQ(d.size(), 5u) << lines(d);
  EXPECT_EQ(d[0].code, DiagCode::needs_scene);
  EXPECT_EQ(d[0].pass, "gbuffer");
  EXPECT_EQ(d[0].where.path, "/passes/0");
  EXPECT_GT(d[0].where.line, 0);
  EXPECT_NE(d[0].message.find("needs a scene"), std::string::npos) << d[0].message;
  EXPECT_EQ(d[1].pass, "lighting");
  EXPECT_EQ(d[2].pass, "forward");
  EXPECT_EQ(d[3].pass, "background");
  EXPECT_EQ(d[4].pass, "environment");
}

TEST(PassChecks, SizesComeFromThePlanAtItsOutputSize) {
  Loaded l = load(kChecks + "/tonemap_half_size_hdr.json");
  CompileOptions small;
  small.output = {64, 32};
  const Plan plan = compile(l.pipeline.graph, small);
  const Diagnostics d = runPassChecks(l.pipeline, plan, processRegistry());
  ASSERT_EQ(d.size(), 1u) << lines(d);
  EXPECT_EQ(d[0].code, DiagCode::pass_check);
  EXPECT_EQ(d[0].slot, "hdr");
  EXPECT_EQ(d[0].where.path, "/passes/4/inputs/hdr");
  EXPECT_NE(d[0].message.find("'hdr' (32x16) and 'output' (64x32)"), std::string::npos) << d[0].message;
}

// CheckedSlot::mips: the levels a binding covers, from its first level on
// (the texture's "mips", capped by its full chain) or the bound range's.
TEST(PassChecks, SlotsCountTheMipLevelsTheyBind) {
  const std::string text = R"({"version": 1, "resources": {
      "hdr": {"format": "rgba16f", "size": [64, 64]},
      "five": {"format": "rgba16f", "size": [64, 64], "mips": 5},
      "full": {"format": "rgba16f", "size": [64, 32], "mips": "full"}},
    "passes": [
      {"name": "a", "type": "fullscreen", "inputs": {"input0": "hdr"}, "outputs": {"color": "five"}},
      {"name": "b", "type": "fullscreen", "inputs": {"input0": "five.mip[1..2]"}, "outputs": {"color": "full"}},
      {"name": "c", "type": "fullscreen", "inputs": {"input0": "full.mip[2]", "color": "five.mip[3]"},
       "outputs": {"color": "five_3.mip[3]"}}],
    "output": "hdr"})";
  Diagnostics diags;
  PipelineConfig pipeline = ConfigDocument::parseText(text, "mips.json", diags).build(processRegistry(), diags);
  ASSERT_FALSE(hasErrors(diags)) << lines(diags);
  const Plan plan = compile(pipeline.graph);
  auto slot = [&](size_t pass, const std::string& name) {
    for (const CheckedSlot& s : planSlots(pipeline.graph, plan, pass))
      if (s.slot == name) return s;
    ADD_FAILURE() << "no slot " << name;
    return CheckedSlot{};
  };
  EXPECT_EQ(slot(0, "input0").mips, 1u);  // a plain texture
  EXPECT_EQ(slot(0, "color").mips, 5u);   // the whole of "mips": 5
  EXPECT_EQ(slot(1, "input0").mips, 2u);  // mip[1..2]
  EXPECT_EQ(slot(1, "color").mips, 7u);   // "full" at 64x32: 64, 32, ..., 1
  EXPECT_EQ(slot(2, "input0").mips, 1u);  // mip[2]
  EXPECT_EQ(slot(2, "color").mips, 1u);   // mip[3], loaded and written
  EXPECT_EQ(slot(2, "color").extent, (Extent{8, 8}));
}

TEST(PassChecks, ParamErrorsPointAtTheParam) {
  // A pass type of this test whose hook refuses a parameter.
  PassRegistry registry;
  PassTypeDesc t;
  t.name = "picky";
  t.slots = {SlotDecl{"color", Access::color_attachment}};
  ParamDecl p;
  p.name = "level";
  p.type = ParamType::integer;
  p.defaultValue = int64_t{1};
  t.params = {p};
  t.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    if (ctx.params().getInt("level") > 2) checks.paramError("level", "level above 2 is not supported");
  };
  t.create = [] { return std::unique_ptr<PassInstance>(); };  // never run here
  std::string error;
  ASSERT_TRUE(registry.add(t, &error)) << error;
  const fs::path file = fs::temp_directory_path() / ("rgraph-picky-" + std::to_string(::getpid()) + ".json");
  std::ofstream(file) << "{\"version\": 1, \"resources\": {\"out\": {\"format\": \"rgba8\"}},\n"
                         " \"passes\": [{\"name\": \"p\", \"type\": \"picky\",\n"
                         "   \"params\": {\"level\": 3}, \"outputs\": {\"color\": \"out\"}}],\n"
                         " \"output\": \"out\"}\n";
  Diagnostics diags;
  PipelineConfig pipeline = ConfigDocument::parseFile(file.string(), diags).build(registry, diags);
  ASSERT_FALSE(hasErrors(diags)) << lines(diags);
  const Diagnostics d = runPassChecks(pipeline, compile(pipeline.graph), registry);
  fs::remove(file);
  ASSERT_EQ(d.size(), 1u) << lines(d);
  EXPECT_EQ(d[0].where.path, "/passes/0/params/level");
  EXPECT_EQ(d[0].where.line, 3);
  EXPECT_EQ(d[0].where.column, 24);
  EXPECT_EQ(d[0].message, "picky pass 'p': level above 2 is not supported");
}

// PassTypeDesc::rules run like the check hook, each reporting at its slot;
// a rule without its sentence or its check is refused at registration.
TEST(PassChecks, RulesRunAndMustHaveASentenceAndACheck) {
  PassRegistry registry;
  PassTypeDesc t;
  t.name = "ruled";
  t.slots = {SlotDecl{"src", Access::sampled, false}, SlotDecl{"color", Access::color_attachment}};
  t.rules = {sameSizeRule({"src", "color"})};
  t.create = [] { return std::unique_ptr<PassInstance>(); };  // never run here
  EXPECT_EQ(t.rules[0].text, "src and color must have the same size");
  EXPECT_EQ(sameSizeRule({"a", "b", "c"}).text, "a, b and c must have the same size");
  PassTypeDesc noText = t, noCheck = t;
  noText.rules[0].text.clear();
  noCheck.rules[0].check = nullptr;
  std::string error;
  EXPECT_FALSE(registry.add(noText, &error));
  EXPECT_EQ(error, "pass type 'ruled' has a rule without a sentence");
  EXPECT_FALSE(registry.add(noCheck, &error));
  EXPECT_EQ(error, "pass type 'ruled' has a rule without a check");
  ASSERT_TRUE(registry.add(t, &error)) << error;

  const fs::path file = fs::temp_directory_path() / ("rgraph-ruled-" + std::to_string(::getpid()) + ".json");
  std::ofstream(file) << "{\"version\": 1, \"resources\": {\"half\": {\"format\": \"rgba8\", \"size\": {\"scale\": 0.5}},\n"
                         "  \"out\": {\"format\": \"rgba8\"}},\n"
                         " \"passes\": [{\"name\": \"fill\", \"type\": \"ruled\", \"outputs\": {\"color\": \"half\"}},\n"
                         "   {\"name\": \"p\", \"type\": \"ruled\", \"inputs\": {\"src\": \"half\"}, \"outputs\": {\"color\": \"out\"}}],\n"
                         " \"output\": \"out\"}\n";
  Diagnostics diags;
  PipelineConfig pipeline = ConfigDocument::parseFile(file.string(), diags).build(registry, diags);
  ASSERT_FALSE(hasErrors(diags)) << lines(diags);
  CompileOptions options;
  options.output = {64, 32};
  const Diagnostics d = runPassChecks(pipeline, compile(pipeline.graph, options), registry);
  fs::remove(file);
  ASSERT_EQ(d.size(), 1u) << lines(d);
  EXPECT_EQ(d[0].slot, "src");
  EXPECT_EQ(d[0].where.path, "/passes/1/inputs/src");
  EXPECT_NE(d[0].message.find("'src' (32x16) and 'color' (64x32) must have the same size"), std::string::npos)
      << d[0].message;
}

TEST(ShaderCheckCache, ACleanPipelineIsAHitTheSecondTime) {
  TempDir dir;
  Loaded l = load(kPipelines + "/deferred-pbr.json");
  ShaderChecker first;
  const CachedShaderCheck a = checkPipelineCached(first, l.pipeline, l.plan, processRegistry(), dir.str());
  EXPECT_FALSE(a.hit);
  EXPECT_GT(first.stats().programsCompiled, 0u);
  ASSERT_TRUE(a.diagnostics.empty()) << lines(a.diagnostics);
  ShaderChecker second;
  const CachedShaderCheck b = checkPipelineCached(second, l.pipeline, l.plan, processRegistry(), dir.str());
  EXPECT_TRUE(b.hit);
  EXPECT_EQ(second.stats().programsCompiled, 0u) << "a hit must not run glslang";
  EXPECT_TRUE(b.diagnostics.empty());
}

// Only verdicts are cached: what a failed check says is never read back from disk.
TEST(ShaderCheckCache, AFailedCheckIsCheckedAgainEveryTime) {
  TempDir dir;
  Loaded l = load(kChecks + "/lighting_missing_material.json");  // has shader errors and warnings
  ShaderChecker first;
  const CachedShaderCheck a = checkPipelineCached(first, l.pipeline, l.plan, processRegistry(), dir.str());
  ASSERT_TRUE(hasErrors(a.diagnostics));
  ShaderChecker second;
  const CachedShaderCheck b = checkPipelineCached(second, l.pipeline, l.plan, processRegistry(), dir.str());
  EXPECT_FALSE(b.hit);
  EXPECT_GT(second.stats().programsCompiled, 0u);
  EXPECT_EQ(lines(b.diagnostics), lines(a.diagnostics));
  EXPECT_FALSE(fs::exists(dir.path())) << "an entry was written for a failed check";
}

TEST(ShaderCheckCache, ADifferentParamIsAMiss) {
  TempDir dir;
  Loaded l = load(kPipelines + "/deferred-pbr.json");
  ShaderChecker c;
  EXPECT_FALSE(checkPipelineCached(c, l.pipeline, l.plan, processRegistry(), dir.str()).hit);
  l.pipeline.params[1].set("model", std::string("blinn_phong"));  // other defines for the lighting program
  EXPECT_FALSE(checkPipelineCached(c, l.pipeline, l.plan, processRegistry(), dir.str()).hit);
  EXPECT_TRUE(checkPipelineCached(c, l.pipeline, l.plan, processRegistry(), dir.str()).hit);
}

// The one entry a clean check of `l` leaves in `dir`.
fs::path onlyEntry(const TempDir& dir) {
  std::vector<fs::path> entries;
  for (const auto& e : fs::directory_iterator(dir.path())) entries.push_back(e.path());
  EXPECT_EQ(entries.size(), 1u) << "one entry, no temporary file left behind";
  return entries.empty() ? fs::path() : entries[0];
}

// The entry a first check of `l` writes into `dir` (empty, with a failure, when not exactly one).
fs::path firstEntry(const TempDir& dir, const Loaded& l) {
  ShaderChecker c;
  checkPipelineCached(c, l.pipeline, l.plan, processRegistry(), dir.str());
  return onlyEntry(dir);
}

TEST(ShaderCheckCache, DamagedEntriesAreIgnoredAndRewritten) {
  TempDir dir;
  Loaded l = load(kPipelines + "/deferred-pbr.json");
  ShaderChecker c;
  const CachedShaderCheck fresh = checkPipelineCached(c, l.pipeline, l.plan, processRegistry(), dir.str());
  ASSERT_TRUE(fresh.diagnostics.empty()) << lines(fresh.diagnostics);
  const fs::path entry = onlyEntry(dir);
  ASSERT_FALSE(entry.empty());
  const std::string text = [&] {
    std::ifstream in(entry);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  const std::string check = text.substr(0, text.find(','));  // {"check":"..."
  for (const std::string& damaged :
       {text.substr(0, text.size() / 2), std::string("\x01garbage"), std::string(),
        std::string("{\"check\": \"0000000000000000\", \"clean\": true}"), check + ",\"clean\":false}",
        check + ",\"clean\":\"yes\"}", check + ",\"clean\":true,\"more\":1}", text + std::string(5000, ' ')}) {
    std::ofstream(entry, std::ios::trunc) << damaged;
    ShaderChecker again;
    const CachedShaderCheck r = checkPipelineCached(again, l.pipeline, l.plan, processRegistry(), dir.str());
    EXPECT_FALSE(r.hit) << "damaged entry used: " << damaged.substr(0, 60);
    EXPECT_EQ(lines(r.diagnostics), lines(fresh.diagnostics));
    ShaderChecker third;
    EXPECT_TRUE(checkPipelineCached(third, l.pipeline, l.plan, processRegistry(), dir.str()).hit)
        << "the damaged entry was not rewritten";
  }
}

// What rgraph wrote before entries were verdicts: diagnostics to replay, one
// of them of no known severity (printed as "error:" while not counted as one).
TEST(ShaderCheckCache, AnEntryWithMessagesIsAMissAndNothingIsReplayed) {
  TempDir dir;
  Loaded l = load(kPipelines + "/deferred-pbr.json");
  const fs::path entry = firstEntry(dir, l);
  ASSERT_FALSE(entry.empty());
  const std::string text = [&] {
    std::ifstream in(entry);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  const std::string check = text.substr(0, text.find(','));
  for (const std::string& crafted :
       {check + ",\"diagnostics\":[[0,7,\"crafted\",\"\",\"\",\"\",\"x.json\",1,1,\"\"]]}",
        check + ",\"clean\":true,\"diagnostics\":[[0,0,\"crafted\",\"\",\"\",\"\",\"\",0,0,\"\"]]}"}) {
    std::ofstream(entry, std::ios::trunc) << crafted;
    ShaderChecker again;
    const CachedShaderCheck r = checkPipelineCached(again, l.pipeline, l.plan, processRegistry(), dir.str());
    EXPECT_FALSE(r.hit) << crafted;
    EXPECT_TRUE(r.diagnostics.empty()) << "replayed from the cache: " << lines(r.diagnostics);
  }
}

// A FIFO at the entry's path: a miss at once (opening it for a blocking read
// would wait for a writer forever), then replaced by an entry.
TEST(ShaderCheckCache, AFifoEntryIsAMissNotAHang) {
  TempDir dir;
  Loaded l = load(kPipelines + "/deferred-pbr.json");
  const fs::path entry = firstEntry(dir, l);
  ASSERT_FALSE(entry.empty());
  fs::remove(entry);
  ASSERT_EQ(::mkfifo(entry.c_str(), 0600), 0);
  // A regression fails here instead of hanging: after 30 s a writer opens and
  // closes the FIFO, which ends a blocked open and read.
  std::atomic<bool> done{false}, rescued{false};
  std::thread rescue([&] {
    for (int i = 0; i < 300 && !done; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (done) return;
    rescued = true;
    const int fd = ::open(entry.c_str(), O_WRONLY | O_NONBLOCK);
    if (fd >= 0) ::close(fd);
  });
  ShaderChecker again;
  const CachedShaderCheck r = checkPipelineCached(again, l.pipeline, l.plan, processRegistry(), dir.str());
  done = true;
  rescue.join();
  EXPECT_FALSE(rescued) << "reading the FIFO entry blocked";
  EXPECT_FALSE(r.hit);
  EXPECT_TRUE(fs::is_regular_file(entry)) << "the FIFO was not replaced by an entry";
}

TEST(ShaderCheckCache, AChangedShaderSourceIsAMiss) {
  TempDir dir;
  const fs::path shaders = dir.path() / "shaders";
  fs::create_directories(shaders);
  std::ofstream(shaders / "cache_probe.frag") << "#version 450 core\nlayout(location = 0) out vec4 o;\n"
                                                 "void main() { o = vec4(1.0); }\n";
  PipelineConfig pipeline;
  Diagnostics diags;
  pipeline = ConfigDocument::parseText(
                 "{\"version\": 1, \"resources\": {\"out\": {\"format\": \"rgba8\"}}, \"passes\": [{\"name\": \"f\", "
                 "\"type\": \"fullscreen\", \"params\": {\"shader\": \"cache_probe.frag\"}, \"outputs\": {\"color\": "
                 "\"out\"}}], \"output\": \"out\"}",
                 "probe.json", diags)
                 .build(processRegistry(), diags);
  ASSERT_FALSE(hasErrors(diags)) << lines(diags);
  const Plan plan = compile(pipeline.graph);
  std::vector<std::string> dirs = {shaders.string()};
  for (auto& d : defaultShaderSearchDirectories()) dirs.push_back(d);
  const std::string cache = (dir.path() / "cache").string();
  ShaderChecker c(dirs);
  EXPECT_FALSE(checkPipelineCached(c, pipeline, plan, processRegistry(), cache).hit);
  EXPECT_TRUE(checkPipelineCached(c, pipeline, plan, processRegistry(), cache).hit);
  // Now a compile error: the cached "no error" must not be reused.
  std::ofstream(shaders / "cache_probe.frag", std::ios::trunc)
      << "#version 450 core\nlayout(location = 0) out vec4 o;\nvoid main() { o = vec4(1.0) }\n";
  ShaderChecker after(dirs);
  const CachedShaderCheck r = checkPipelineCached(after, pipeline, plan, processRegistry(), cache);
  EXPECT_FALSE(r.hit);
  EXPECT_TRUE(hasErrors(r.diagnostics)) << lines(r.diagnostics);
}

}  // namespace
