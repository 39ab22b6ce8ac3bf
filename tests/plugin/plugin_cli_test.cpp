// The rgraph command line with plugins: configs naming plugins, --plugin-path,
// RGRAPH_PLUGIN_PATH, `rgraph passes --plugin`, and one-line refusals with
// exit code 1.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kCli = RGRAPH_CLI;
const std::string kSource = RGRAPH_SOURCE_DIR;
const std::string kConfigs = std::string(RGRAPH_SOURCE_DIR) + "/tests/plugin/configs";
const std::string kFixtures = RGRAPH_PLUGIN_FIXTURE_DIR;
const std::string kPlugins = RGRAPH_PLUGIN_OUTPUT_DIR;

using Result = rgraph::testsupport::CommandResult;

// Runs `rgraph ARGS` through the shell (RGRAPH_PLUGIN_PATH unset unless `env` sets it).
Result runRgraph(const std::string& args, const std::string& env = "env -u RGRAPH_PLUGIN_PATH") {
  const std::string cmd = env + " '" + kCli + "' " + args + " 2>&1";
  return rgraph::testsupport::runCommand(cmd);
}

std::string canonical(const std::string& p) { return fs::weakly_canonical(p).string(); }

std::string tempPng(const std::string& name) {
  return (fs::temp_directory_path() / ("rgraph-plugin-cli-" + std::to_string(getpid()) + "-" + name)).string();
}

}  // namespace

TEST(PluginCli, RenderWithMissingPluginIsOneLineAndExit1) {
  const std::string png = tempPng("missing.png");
  Result r = runRgraph("render " + kConfigs + "/missing-plugin.json --width 32 --height 32 --out " + png);
  EXPECT_EQ(r.exitCode, 1) << r.out;
  ASSERT_EQ(r.lines().size(), 1u) << r.out;
  // The plugin's name in the config is on line 3, column 15.
  EXPECT_NE(r.out.find("missing-plugin.json:3:15: error: /plugins/0: plugin 'no_such_plugin': not found"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(png));
}

TEST(PluginCli, ValidateWithMissingPluginIsAPluginErrorDiagnostic) {
  Result r = runRgraph("validate --json " + kConfigs + "/missing-plugin.json");
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_NE(r.out.find("\"code\": \"plugin_error\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"line\": 3"), std::string::npos) << r.out;
}

TEST(PluginCli, RenderWithWrongAbiPluginIsOneLineAndExit1) {
  const std::string png = tempPng("abi.png");
  Result r = runRgraph("render " + kConfigs + "/wrong-abi-plugin.json --plugin-path " + kFixtures +
                    " --width 32 --height 32 --out " + png);
  EXPECT_EQ(r.exitCode, 1) << r.out;
  ASSERT_EQ(r.lines().size(), 1u) << r.out;
  // The expected version is the current ABI's (plugin_loader_test checks the number).
  EXPECT_NE(r.out.find("plugin 'fixture_wrong_abi' (" + canonical(kFixtures + "/librgraph_fixture_wrong_abi.so") +
                       "): ABI version mismatch: expected "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(", found 999 (rebuild the plugin against this rgraph)"), std::string::npos) << r.out;
}

TEST(PluginCli, PluginPathFromTheEnvironment) {
  Result r = runRgraph("validate " + kConfigs + "/wrong-abi-plugin.json", "env RGRAPH_PLUGIN_PATH=" + kFixtures);
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_NE(r.out.find("ABI version mismatch"), std::string::npos) << r.out;
}

TEST(PluginCli, PassesListsPluginTypesWithTheirOrigin) {
  Result r = runRgraph("passes --plugin bloom --plugin ssao");
  EXPECT_EQ(r.exitCode, 0) << r.out;
  const std::string bloom = canonical(kPlugins + "/librgraph_bloom.so");
  const std::string ssao = canonical(kPlugins + "/librgraph_ssao.so");
  for (const char* t : {"bloom_bright", "bloom_blur", "bloom_composite"})
    EXPECT_NE(r.out.find(std::string(t) + "  (" + bloom + ")"), std::string::npos) << t << "\n" << r.out;
  for (const char* t : {"ssao", "ssao_blur"})
    EXPECT_NE(r.out.find(std::string(t) + "  (" + ssao + ")"), std::string::npos) << t;
  // Only the named plugins' types (issue 16: the built-in ones were mixed in).
  EXPECT_EQ(r.out.find("(built-in)"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("tonemap"), std::string::npos) << r.out;

  Result json = runRgraph("passes --json --plugin bloom");
  EXPECT_EQ(json.exitCode, 0);
  EXPECT_NE(json.out.find("\"origin\": \"" + bloom + "\""), std::string::npos) << json.out;
  EXPECT_EQ(json.out.find("\"origin\": \"built-in\""), std::string::npos) << json.out;
}

// Exactly the types the plugin registers, in the order it registers them.
TEST(PluginCli, PassesWithOnePluginListsExactlyItsTypes) {
  Result r = runRgraph("passes --plugin bloom");
  EXPECT_EQ(r.exitCode, 0) << r.out;
  std::vector<std::string> headers;
  for (const auto& l : r.lines())
    if (!l.empty() && l[0] != ' ') headers.push_back(l.substr(0, l.find("  (")));
  EXPECT_EQ(headers, (std::vector<std::string>{"bloom_bright", "bloom_blur", "bloom_composite"})) << r.out;
}

// A type named with --plugin may be one of the plugin's or a built-in one.
TEST(PluginCli, PassesTypeFindsAPluginType) {
  Result r = runRgraph("passes bloom_composite tonemap --plugin bloom");
  EXPECT_EQ(r.exitCode, 0) << r.out;
  EXPECT_EQ(r.out.rfind("bloom_composite  (", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("\ntonemap  (built-in)\n"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("bloom_blur"), std::string::npos) << r.out;
  Result without = runRgraph("passes bloom_composite");
  EXPECT_EQ(without.exitCode, 1) << without.out;
  EXPECT_NE(without.out.find("unknown pass type 'bloom_composite'"), std::string::npos) << without.out;
}

TEST(PluginCli, PassesWithoutPluginsListsNoPluginTypes) {
  Result r = runRgraph("passes");
  EXPECT_EQ(r.exitCode, 0) << r.out;
  EXPECT_EQ(r.out.find("bloom_bright"), std::string::npos);
}

TEST(PluginCli, PassesWithMissingPluginIsOneLineAndExit1) {
  Result r = runRgraph("passes --plugin no_such_plugin");
  EXPECT_EQ(r.exitCode, 1) << r.out;
  ASSERT_EQ(r.lines().size(), 1u) << r.out;
  EXPECT_EQ(r.out.rfind("error: plugin 'no_such_plugin': not found", 0), 0u) << r.out;
}

TEST(PluginCli, ShippedSsaoBloomPipelineValidatesAndRenders) {
  const std::string pipeline = kSource + "/pipelines/deferred-ssao-bloom.json";
  Result v = runRgraph("validate " + pipeline);
  EXPECT_EQ(v.exitCode, 0) << v.out;
  const std::string png = tempPng("ssao-bloom.png");
  Result r = runRgraph("render " + pipeline + " --width 96 --height 64 --out " + png);
  EXPECT_EQ(r.exitCode, 0) << r.out;
  EXPECT_TRUE(fs::exists(png)) << r.out;
  std::error_code ec;
  fs::remove(png, ec);
}

namespace {

// Resources that share a physical texture in a `rgraph plan --json` must
// have disjoint lifetimes (first..last pass order, inclusive): the rule that
// keeps aliasing honest. Returns how many textures are shared.
size_t expectSharersDisjoint(const nlohmann::json& plan, const std::string& what) {
  std::map<int, std::vector<std::pair<int, int>>> byPhysical;
  std::map<int, std::vector<std::string>> names;
  for (const auto& r : plan["resources"]) {
    if (!r["physical"].is_number()) continue;  // imported
    const int ph = r["physical"].get<int>();
    byPhysical[ph].push_back({r["first_order"].get<int>(), r["last_order"].get<int>()});
    names[ph].push_back(r["name"].get<std::string>());
  }
  size_t shared = 0;
  for (const auto& [ph, spans] : byPhysical) {
    shared += spans.size() > 1;
    for (size_t i = 0; i < spans.size(); ++i)
      for (size_t j = i + 1; j < spans.size(); ++j)
        EXPECT_TRUE(spans[i].second < spans[j].first || spans[j].second < spans[i].first)
            << what << ": " << names[ph][i] << " (passes " << spans[i].first << ".." << spans[i].second << ") and "
            << names[ph][j] << " (passes " << spans[j].first << ".." << spans[j].second << ") share physical #" << ph;
  }
  return shared;
}

nlohmann::json planAt1080p(const std::string& pipeline) {
  Result r = runRgraph("plan --json --width 1920 --height 1080 " + kSource + "/pipelines/" + pipeline);
  EXPECT_EQ(r.exitCode, 0) << r.out;
  return r.exitCode == 0 ? nlohmann::json::parse(r.out) : nlohmann::json();
}

}  // namespace

// Issue 15: at 1920x1080 the pipeline allocates at most 45% of what it took
// before (the pbr G-buffer, full-size bloom: 160,704,000 naive bytes, of
// which aliasing left 94,348,800 allocated). It is smaller rather than
// shared: the compact G-buffer (14 bytes per pixel with depth, against 36),
// bloom's three textures at half size, the bloom added into the HDR target.
// Per pixel of the output: rg16f normal 4, rgba8 albedo 4, rg8 material 2,
// depth32f 4, r8 visibility 1, rgba16f HDR 8; per half-size pixel: two r8
// SSAO targets, three rgba16f bloom targets (26); and blur_b's mip levels
// 1..4 below its level 0 (480x270 down to 60x33, rgba16f: 172,020 texels;
// the chain's five levels lie at the origin of mip levels 0..4).
// As shipped it also declares the G-buffer's optional targets, r11g11b10f
// emissive 4 and rgba8 reflectance 4 bytes a pixel, which scene adaptation
// removes for a scene with no emissive, unlit or KHR_materials_specular
// material (what the 45% is about). Nothing is left to alias:
// the resources of one format and size (ao_raw, ao_half; bright, blur_a,
// blur_b) are each live at one pass together, so every resource has a
// texture of its own and the plan's own allocated/naive ratio is 100%.
TEST(PluginCli, SsaoBloomPipelineAllocatesAtMost45PercentOfItsFormerNaiveAt1080p) {
  const nlohmann::json plan = planAt1080p("deferred-ssao-bloom.json");
  ASSERT_FALSE(plan.is_null());
  const uint64_t full = 1920ull * 1080, half = 960ull * 540;
  const uint64_t allocated = plan["memory"]["allocated_bytes"].get<uint64_t>();
  const uint64_t chainLevels = 480ull * 270 + 240 * 135 + 120 * 67 + 60 * 33;
  const uint64_t optional = 8 * full;
  EXPECT_EQ(allocated, 23 * full + optional + 26 * half + 8 * chainLevels);
  EXPECT_EQ(allocated, 79136160u);
  EXPECT_LE(double(allocated - optional), 0.45 * 160704000.0);
  EXPECT_EQ(plan["memory"]["naive_bytes"].get<uint64_t>(), allocated) << "nothing aliases";
  // At the lighting pass the G-buffer (normal 4, albedo 4, material 2, depth
  // 4 bytes a pixel), the visibility (1) and the HDR target (8) are live: an
  // allocator that aliased across formats and sizes would still need 78%.
  EXPECT_EQ(plan["memory"]["peak_live_bytes"].get<uint64_t>(), 23 * full + optional);
  EXPECT_EQ(plan["physical"].size(), 13u);
  EXPECT_EQ(expectSharersDisjoint(plan, "deferred-ssao-bloom.json"), 0u);
}

// The same rule where textures are shared: the shipped post chain aliases
// five transients onto two textures.
TEST(PluginCli, PlansShareTexturesOnlyBetweenDisjointLifetimes) {
  const nlohmann::json plan = planAt1080p("examples/post-chain.json");
  ASSERT_FALSE(plan.is_null());
  EXPECT_EQ(expectSharersDisjoint(plan, "examples/post-chain.json"), 2u);
}

// ---- damaged plugin files: refused before dlopen (which would die of SIGBUS
// reading a segment cut short), exit code 1, never a signal ----

namespace {

// Damaged copies of the shipped plugins, one folder per case, each holding
// librgraph_<plugin>.so: cut at 4, 32 and 64 KiB, an empty file, a text file.
struct DamagedPlugin {
  std::string dir, plugin, file, problem;
  std::string location() const {  // "plugins": ["ssao", "bloom"] on line 4 of deferred-ssao-bloom.json
    return plugin == "ssao" ? "deferred-ssao-bloom.json:4:15: error: /plugins/0: "
                            : "deferred-ssao-bloom.json:4:23: error: /plugins/1: ";
  }
};

class DamagedPluginCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = (fs::temp_directory_path() / ("rgraph-damaged-plugins-" + std::to_string(getpid()))).string();
    cases_.clear();
    auto add = [](const std::string& name, const std::string& plugin, const std::string& bytes, const std::string& problem) {
      const std::string dir = root_ + "/" + name;
      fs::create_directories(dir);
      const std::string file = dir + "/librgraph_" + plugin + ".so";
      std::ofstream(file, std::ios::binary) << bytes;
      cases_.push_back({dir, plugin, canonical(file), problem});
    };
    for (const std::string plugin : {"bloom", "ssao"}) {
      std::ifstream in(kPlugins + "/librgraph_" + plugin + ".so", std::ios::binary);
      const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      for (size_t cut : {4096u, 32768u, 65536u}) {
        ASSERT_GT(bytes.size(), cut) << plugin;
        add(plugin + "-cut-" + std::to_string(cut), plugin, bytes.substr(0, cut), "(PT_LOAD) ends at byte ");
      }
    }
    add("empty", "bloom", "", "not a loadable plugin: the file is empty (0 bytes)");
    add("text", "bloom", "#!/bin/sh\necho not a library\n",
        "not a loadable plugin: not an ELF shared library: it starts with \"#!/bin/sh\\necho n...\"");
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  // What every refusal says: the location (when from a config), the file, the problem.
  static void expectRefused(const Result& r, const DamagedPlugin& c, bool fromConfig) {
    EXPECT_EQ(r.exitCode, 1) << c.file << "\n" << r.out;  // 128+N through the shell: killed by signal N
    ASSERT_EQ(r.lines().size(), 1u) << r.out;
    EXPECT_NE(r.out.find("(" + c.file + "): not a loadable plugin: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(c.problem), std::string::npos) << r.out;
    if (c.dir.find("-cut-") != std::string::npos) {
      const std::string cut = c.dir.substr(c.dir.rfind('-') + 1);
      EXPECT_NE(r.out.find("but the file has " + cut + " bytes (truncated?)"), std::string::npos) << r.out;
    }
    if (fromConfig) {
      EXPECT_NE(r.out.find(c.location()), std::string::npos) << r.out;
    }
  }
  static inline std::string root_;
  static inline std::vector<DamagedPlugin> cases_;
};

const std::string kSsaoBloom = kSource + "/pipelines/deferred-ssao-bloom.json";

}  // namespace

TEST_F(DamagedPluginCli, ValidateRefusesEachWithTheConfigLocationAndTheFile) {
  ASSERT_EQ(cases_.size(), 8u);
  for (const auto& c : cases_) expectRefused(runRgraph("validate " + kSsaoBloom + " --plugin-path " + c.dir), c, true);
}

TEST_F(DamagedPluginCli, PassesWithPluginRefusesEachNamingTheFile) {
  for (const auto& c : cases_) expectRefused(runRgraph("passes --plugin " + c.file), c, false);
}

TEST_F(DamagedPluginCli, RenderRefusesEachAndWritesNoImage) {
  const std::string png = tempPng("damaged.png");
  for (const auto& c : cases_) {
    expectRefused(runRgraph("render " + kSsaoBloom + " --plugin-path " + c.dir + " --width 32 --height 32 --out " + png), c, true);
    EXPECT_FALSE(fs::exists(png)) << c.file;
  }
}

// The C library stops at a NUL: the name would be looked up as "bloom" and
// reported as not found. It is refused by name, at its place in the config.
TEST(PluginCli, PluginNameWithANulByteIsRefusedAtItsConfigLocation) {
  for (const std::string& cmd : {std::string("validate"), "render --width 32 --height 32 --out " + tempPng("nul.png")}) {
    Result r = runRgraph(cmd + " " + kConfigs + "/nul-plugin-name.json");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    ASSERT_EQ(r.lines().size(), 1u) << r.out;
    EXPECT_NE(r.out.find("nul-plugin-name.json:3:15: error: /plugins/0: plugin 'bloom\\u0000': the name contains a NUL "
                         "byte (character 6); a plugin name or path cannot contain one"),
              std::string::npos)
        << r.out;
  }
}
