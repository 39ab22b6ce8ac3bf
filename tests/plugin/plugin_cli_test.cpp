// The rgraph command line with plugins: configs naming plugins, --plugin-path,
// RGRAPH_PLUGIN_PATH, `rgraph passes --plugin`, and one-line refusals with
// exit code 1.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace fs = std::filesystem;

namespace {

const std::string kCli = RGRAPH_CLI;
const std::string kSource = RGRAPH_SOURCE_DIR;
const std::string kConfigs = std::string(RGRAPH_SOURCE_DIR) + "/tests/plugin/configs";
const std::string kFixtures = RGRAPH_PLUGIN_FIXTURE_DIR;
const std::string kPlugins = RGRAPH_PLUGIN_OUTPUT_DIR;

struct Result {
  int exit = -1;
  std::string out;  // stdout + stderr
  std::vector<std::string> lines() const {
    std::vector<std::string> v;
    std::istringstream s(out);
    for (std::string l; std::getline(s, l);)
      if (!l.empty()) v.push_back(l);
    return v;
  }
};

// Runs `rgraph ARGS` through the shell (RGRAPH_PLUGIN_PATH unset unless `env` sets it).
Result rgraph(const std::string& args, const std::string& env = "env -u RGRAPH_PLUGIN_PATH") {
  const std::string cmd = env + " '" + kCli + "' " + args + " 2>&1";
  Result r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  int status = pclose(p);
  r.exit = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::string canonical(const std::string& p) { return fs::weakly_canonical(p).string(); }

std::string tempPng(const std::string& name) {
  return (fs::temp_directory_path() / ("rgraph-plugin-cli-" + std::to_string(getpid()) + "-" + name)).string();
}

}  // namespace

TEST(PluginCli, RenderWithMissingPluginIsOneLineAndExit1) {
  const std::string png = tempPng("missing.png");
  Result r = rgraph("render " + kConfigs + "/missing-plugin.json --width 32 --height 32 --out " + png);
  EXPECT_EQ(r.exit, 1) << r.out;
  ASSERT_EQ(r.lines().size(), 1u) << r.out;
  // The plugin's name in the config is on line 3, column 15.
  EXPECT_NE(r.out.find("missing-plugin.json:3:15: error: /plugins/0: plugin 'no_such_plugin': not found"),
            std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(png));
}

TEST(PluginCli, ValidateWithMissingPluginIsAPluginErrorDiagnostic) {
  Result r = rgraph("validate --json " + kConfigs + "/missing-plugin.json");
  EXPECT_EQ(r.exit, 1) << r.out;
  EXPECT_NE(r.out.find("\"code\": \"plugin_error\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"line\": 3"), std::string::npos) << r.out;
}

TEST(PluginCli, RenderWithWrongAbiPluginIsOneLineAndExit1) {
  const std::string png = tempPng("abi.png");
  Result r = rgraph("render " + kConfigs + "/wrong-abi-plugin.json --plugin-path " + kFixtures +
                    " --width 32 --height 32 --out " + png);
  EXPECT_EQ(r.exit, 1) << r.out;
  ASSERT_EQ(r.lines().size(), 1u) << r.out;
  EXPECT_NE(r.out.find("plugin 'fixture_wrong_abi' (" + canonical(kFixtures + "/librgraph_fixture_wrong_abi.so") +
                       "): ABI version mismatch: expected 1, found 999"),
            std::string::npos)
      << r.out;
}

TEST(PluginCli, PluginPathFromTheEnvironment) {
  Result r = rgraph("validate " + kConfigs + "/wrong-abi-plugin.json", "env RGRAPH_PLUGIN_PATH=" + kFixtures);
  EXPECT_EQ(r.exit, 1) << r.out;
  EXPECT_NE(r.out.find("ABI version mismatch"), std::string::npos) << r.out;
}

TEST(PluginCli, PassesListsPluginTypesWithTheirOrigin) {
  Result r = rgraph("passes --plugin bloom --plugin ssao");
  EXPECT_EQ(r.exit, 0) << r.out;
  const std::string bloom = canonical(kPlugins + "/librgraph_bloom.so");
  const std::string ssao = canonical(kPlugins + "/librgraph_ssao.so");
  for (const char* t : {"bloom_bright", "bloom_blur", "bloom_composite"})
    EXPECT_NE(r.out.find(std::string(t) + "  (" + bloom + ")"), std::string::npos) << t << "\n" << r.out;
  for (const char* t : {"ssao", "ssao_blur"})
    EXPECT_NE(r.out.find(std::string(t) + "  (" + ssao + ")"), std::string::npos) << t;
  EXPECT_NE(r.out.find("tonemap  (built-in)"), std::string::npos);

  Result json = rgraph("passes --json --plugin bloom");
  EXPECT_EQ(json.exit, 0);
  EXPECT_NE(json.out.find("\"origin\": \"" + bloom + "\""), std::string::npos) << json.out;
}

TEST(PluginCli, PassesWithoutPluginsListsNoPluginTypes) {
  Result r = rgraph("passes");
  EXPECT_EQ(r.exit, 0) << r.out;
  EXPECT_EQ(r.out.find("bloom_bright"), std::string::npos);
}

TEST(PluginCli, PassesWithMissingPluginIsOneLineAndExit1) {
  Result r = rgraph("passes --plugin no_such_plugin");
  EXPECT_EQ(r.exit, 1) << r.out;
  ASSERT_EQ(r.lines().size(), 1u) << r.out;
  EXPECT_EQ(r.out.rfind("error: plugin 'no_such_plugin': not found", 0), 0u) << r.out;
}

TEST(PluginCli, ShippedSsaoBloomPipelineValidatesAndRenders) {
  const std::string pipeline = kSource + "/pipelines/deferred-ssao-bloom.json";
  Result v = rgraph("validate " + pipeline);
  EXPECT_EQ(v.exit, 0) << v.out;
  const std::string png = tempPng("ssao-bloom.png");
  Result r = rgraph("render " + pipeline + " --width 96 --height 64 --out " + png);
  EXPECT_EQ(r.exit, 0) << r.out;
  EXPECT_TRUE(fs::exists(png)) << r.out;
  std::error_code ec;
  fs::remove(png, ec);
}

TEST(PluginCli, SsaoBloomPipelineAliasesToAtMost60PercentAt1080p) {
  Result r = rgraph("plan --json --width 1920 --height 1080 " + kSource + "/pipelines/deferred-ssao-bloom.json");
  ASSERT_EQ(r.exit, 0) << r.out;
  const auto plan = nlohmann::json::parse(r.out);
  const double naive = plan["memory"]["naive_bytes"].get<double>();
  const double allocated = plan["memory"]["allocated_bytes"].get<double>();
  EXPECT_GT(naive, 0.0);
  EXPECT_LE(allocated, 0.6 * naive) << "allocated " << allocated << " of naive " << naive;
  // Bloom's intermediates reuse G-buffer targets (dead after lighting).
  bool sharesWithGBuffer = false;
  for (const auto& ph : plan["physical"]) {
    const auto& names = ph["resources"];
    const bool g = std::find(names.begin(), names.end(), "gPosition") != names.end();
    const bool b = std::find(names.begin(), names.end(), "bright") != names.end();
    sharesWithGBuffer |= g && b;
  }
  EXPECT_TRUE(sharesWithGBuffer) << r.out;
}
