// Messages a plugin author meets (issue 16): shader errors name the shader's
// source file, not the build tree's copy of it (4); `render` shows a driver's
// compile errors in the clean form `validate` uses, the driver's whole log
// only at debug level (5); a pass type that a plugin on the search path
// provides, used without naming the plugin, says which entry to add (6).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.h"

namespace fs = std::filesystem;
using rgraph::testsupport::runCommand;

namespace {

const std::string kCli = RGRAPH_CLI;
const std::string kSource = RGRAPH_SOURCE_DIR;
const std::string kPlugins = RGRAPH_PLUGIN_OUTPUT_DIR;
const std::string kBrokenRoot = RGRAPH_BROKEN_SHADER_ROOT;
const std::string kBrokenPluginDir = kBrokenRoot + "/lib/rgraph/plugins";
const std::string kBrokenCopy = kBrokenRoot + "/share/rgraph/plugins/fixture_broken_shader/broken.frag";
// The source as shown from the source tree (where the commands below run).
const std::string kBrokenSource = "tests/plugin/fixtures/shaders/broken.frag";
const std::string kConfigs = "tests/plugin/configs/";

using Result = rgraph::testsupport::CommandResult;

// `rgraph ARGS` run in the source tree, stdout and stderr together, with no
// plugin folder from the environment and a shader-check cache of its own.
Result runRgraph(const std::string& args) {
  const std::string cache = (fs::temp_directory_path() / ("rgraph-messages-cache-" + std::to_string(getpid()))).string();
  return runCommand("cd '" + kSource + "' && env -u RGRAPH_PLUGIN_PATH RGRAPH_CACHE_DIR='" + cache + "' '" + kCli +
                    "' " + args + " 2>&1");
}

std::string tempPath(const std::string& name) {
  return (fs::temp_directory_path() / ("rgraph-messages-" + std::to_string(getpid()) + "-" + name)).string();
}

std::string brokenShader(const std::string& command) {
  return command + " " + kConfigs + "broken-shader.json --plugin-path '" + kBrokenPluginDir + "'";
}

std::string renderArgs(const std::string& png) { return " --width 32 --height 32 --out '" + png + "'"; }

}  // namespace

// ---- 4: the source, not the copy ----

TEST(PluginShaderErrors, ManifestBesideTheCopyNamesTheSource) {
  std::ifstream manifest(fs::path(kBrokenCopy).parent_path() / "rgraph-shader-sources.txt");
  ASSERT_TRUE(manifest) << "rgraph_add_plugin wrote no manifest beside " << kBrokenCopy;
  std::stringstream text;
  text << manifest.rdbuf();
  EXPECT_NE(text.str().find("broken.frag\t" + kSource + "/" + kBrokenSource + "\n"), std::string::npos) << text.str();
}

TEST(PluginShaderErrors, ValidateNamesTheSourceFile) {
  Result r = runRgraph(brokenShader("validate"));
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_TRUE(r.has(kBrokenSource + ":9: error: ")) << r.out;
  EXPECT_FALSE(r.has("share/rgraph/plugins/fixture_broken_shader")) << r.out;
}

TEST(PluginShaderErrors, RenderNamesTheSourceFile) {
  const std::string png = tempPath("broken.png");
  for (const std::string& checks : {std::string(), std::string(" --no-checks")}) {  // glslang's message, then the driver's
    Result r = runRgraph(brokenShader("render") + renderArgs(png) + checks);
    EXPECT_EQ(r.exitCode, 1) << checks << "\n" << r.out;
    EXPECT_TRUE(r.has(kBrokenSource + ":9: error: ")) << checks << "\n" << r.out;
    EXPECT_FALSE(r.has("share/rgraph/plugins/fixture_broken_shader")) << checks << "\n" << r.out;
    EXPECT_FALSE(fs::exists(png));
  }
}

// A copy of the plugin in a folder of its own, whose manifest points at
// `source` (written with `sourceText`, or left out when empty).
class CopiedPlugin : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = tempPath("copied-plugin");
    fs::remove_all(root_);
    fs::create_directories(root_);
    fs::copy(kBrokenRoot, root_, fs::copy_options::recursive);
  }
  void TearDown() override { fs::remove_all(root_); }
  std::string copy() const { return root_ + "/share/rgraph/plugins/fixture_broken_shader/broken.frag"; }
  void pointManifestAt(const std::string& source) const {
    std::ofstream(fs::path(copy()).parent_path() / "rgraph-shader-sources.txt") << "# test\nbroken.frag\t" << source << "\n";
  }
  Result validate() const {
    return runRgraph("validate " + kConfigs + "broken-shader.json --plugin-path '" + root_ + "/lib/rgraph/plugins'");
  }
  std::string root_;
};

TEST_F(CopiedPlugin, SourceEditedSinceTheCopySaysItIsACopyOfIt) {
  const std::string source = root_ + "/edited-source.frag";
  {
    std::ifstream in(copy());
    std::ofstream out(source);
    out << "// a line added since the build copied this file\n" << in.rdbuf();
  }
  pointManifestAt(source);
  Result r = validate();
  EXPECT_EQ(r.exitCode, 1) << r.out;
  // Line 9 is the copy's line: the message names the copy, and says whose copy.
  EXPECT_TRUE(r.has(copy() + ":9: error: ")) << r.out;
  EXPECT_TRUE(r.has("(" + copy() + " is a copy of " + source +
                    ", which has changed since it was copied: rebuild the plugin to copy it again)"))
      << r.out;
}

TEST_F(CopiedPlugin, SourceGoneOrNoManifestNamesTheCopy) {
  pointManifestAt(root_ + "/no-such-source.frag");
  Result r = validate();
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_TRUE(r.has(copy() + ":9: error: ")) << r.out;
  EXPECT_FALSE(r.has("is a copy of")) << r.out;

  fs::remove(fs::path(copy()).parent_path() / "rgraph-shader-sources.txt");
  r = validate();
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_TRUE(r.has(copy() + ":9: error: ")) << r.out;
}

// ---- 5: render's driver errors, short ----

TEST(PluginShaderErrors, RenderShowsTheDriverErrorShortWithoutADoubledPrefix) {
  const std::string png = tempPath("driver.png");
  // --no-checks: glslang does not run, so the driver's compiler reports it.
  Result r = runRgraph(brokenShader("render") + renderArgs(png) + " --no-checks");
  EXPECT_EQ(r.exitCode, 1) << r.out;
  const std::vector<std::string> lines = r.lines();
  ASSERT_FALSE(lines.empty()) << r.out;
  ASSERT_LE(lines.size(), 4u) << r.out;  // error, what refused it, which pass
  EXPECT_EQ(lines[0].rfind(kBrokenSource + ":9: error: ", 0), 0u) << r.out;
  for (const auto& l : lines) EXPECT_NE(l.rfind("error: ", 0), 0u) << "doubled prefix: " << l;
  EXPECT_EQ(r.out.find("error: " + kBrokenSource), std::string::npos) << r.out;
  EXPECT_FALSE(r.has("candidates")) << r.out;
  EXPECT_TRUE(r.has("(in setup of pass 'broken' of type 'fixture_broken_shader' at " + kConfigs +
                    "broken-shader.json:11:5 (/passes/1))"))
      << r.out;
}

TEST(PluginShaderErrors, RenderShowsTheDriversWholeLogAtDebugLevel) {
  const std::string png = tempPath("driver-debug.png");
  Result quiet = runRgraph(brokenShader("render") + renderArgs(png) + " --no-checks");
  Result r = runRgraph("--log-level debug " + brokenShader("render") + renderArgs(png) + " --no-checks");
  EXPECT_EQ(r.exitCode, 1) << r.out;
  const size_t log = r.out.find("broken.frag (fragment shader): the driver's compile log:");
  ASSERT_NE(log, std::string::npos) << r.out;
  // The log follows, located at the source's lines like everything else.
  EXPECT_NE(r.out.find(kBrokenSource + ":9: ", log), std::string::npos) << r.out;
  EXPECT_FALSE(quiet.has("the driver's compile log")) << quiet.out;
  EXPECT_GT(r.lines().size(), quiet.lines().size() + 1) << r.out;
}

// ---- 6: a type a plugin on the search path provides ----

TEST(PluginSuggestion, UnknownTypeNamesThePluginToAdd) {
  const std::string png = tempPath("suggest.png");
  const std::string ssao = fs::weakly_canonical(kPlugins + "/librgraph_ssao.so").string();
  for (const std::string& cmd : {std::string("validate"), "render" + renderArgs(png)}) {
    Result r = runRgraph(cmd + " " + kConfigs + "ssao-without-plugins.json");
    EXPECT_EQ(r.exitCode, 1) << cmd << "\n" << r.out;
    ASSERT_EQ(r.lines().size(), 1u) << cmd << "\n" << r.out;
    EXPECT_EQ(r.lines()[0], kConfigs + "ssao-without-plugins.json:16:31: error: /passes/1/type: unknown pass type "
                                       "'ssao'; plugin \"ssao\" (" + ssao + ") provides it: add \"plugins\": "
                                       "[\"ssao\"] at the top level of the config")
        << cmd;
    EXPECT_FALSE(fs::exists(png));
  }
}

TEST(PluginSuggestion, WithAPluginsArraySaysToAddTheEntryToIt) {
  const std::string bloom = fs::weakly_canonical(kPlugins + "/librgraph_bloom.so").string();
  Result r = runRgraph("validate " + kConfigs + "bloom-not-listed.json");
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_TRUE(r.has("bloom-not-listed.json:11:33: error: /passes/1/type: unknown pass type 'bloom_bright'; plugin "
                    "\"bloom\" (" + bloom + ") provides it: add \"bloom\" to the config's \"plugins\" array"))
      << r.out;
}

TEST(PluginSuggestion, ATypeNoPluginHasGetsNoSuggestion) {
  const std::string config = tempPath("no-such-type.json");
  std::ofstream(config) << R"({ "version": 1, "resources": { "o": { "format": "rgba8" } },
  "passes": [ { "name": "x", "type": "no_plugin_has_this", "outputs": { "color": "o" } } ], "output": "o" })";
  Result r = runRgraph("validate '" + config + "'");
  fs::remove(config);
  EXPECT_EQ(r.exitCode, 1) << r.out;
  EXPECT_TRUE(r.has("unknown pass type 'no_plugin_has_this'")) << r.out;
  EXPECT_FALSE(r.has("provides it")) << r.out;
}

// Damaged libraries on the path (cut short, empty, text, a copy of ssao cut
// short that shadows the real one) are skipped by the look-up: no crash, and
// the real ssao is named by its path, since "ssao" would find the damaged one.
TEST(PluginSuggestion, DamagedPluginsOnThePathAreSkipped) {
  const std::string dir = tempPath("damaged-path");
  fs::create_directories(dir);
  std::ifstream in(kPlugins + "/librgraph_ssao.so", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 32768u);
  std::ofstream(dir + "/librgraph_ssao.so", std::ios::binary) << bytes.substr(0, 32768);
  std::ofstream(dir + "/librgraph_empty.so", std::ios::binary) << "";
  std::ofstream(dir + "/librgraph_text.so", std::ios::binary) << "#!/bin/sh\necho not a library\n";
  const std::string ssao = fs::weakly_canonical(kPlugins + "/librgraph_ssao.so").string();
  for (const std::string& cmd : {std::string("validate"), "render" + renderArgs(tempPath("damaged.png"))}) {
    Result r = runRgraph(cmd + " " + kConfigs + "ssao-without-plugins.json --plugin-path '" + dir + "'");
    EXPECT_EQ(r.exitCode, 1) << cmd << "\n" << r.out;  // 128+N: killed by signal N
    ASSERT_EQ(r.lines().size(), 1u) << cmd << "\n" << r.out;
    EXPECT_TRUE(r.has("unknown pass type 'ssao'; plugin \"" + ssao + "\" (" + ssao + ") provides it: add \"plugins\": [\"" +
                      ssao + "\"] at the top level of the config"))
        << cmd << "\n" << r.out;
  }
  fs::remove_all(dir);
}
