// The plugin loader: finding plugins, the ABI check, refusals with one-line
// messages, all-or-nothing registration, origins.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "rgraph/own_files.h"
#include "rgraph/plugin.h"
#include "rgraph/registry.h"

namespace fs = std::filesystem;
using namespace rgraph;

namespace {

const std::string kFixtures = RGRAPH_PLUGIN_FIXTURE_DIR;
const std::string kPlugins = RGRAPH_PLUGIN_OUTPUT_DIR;

std::string fixture(const std::string& name) { return kFixtures + "/librgraph_fixture_" + name + ".so"; }
std::string canonical(const std::string& p) { return fs::weakly_canonical(p).string(); }

// A scratch folder per test, removed afterwards.
class TempDir {
 public:
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "rgraph-plugin-test-XXXXXX").string();
    path_ = mkdtemp(tmpl.data()) ? tmpl : std::string();
  }
  ~TempDir() {
    std::error_code ec;
    if (!path_.empty()) fs::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Unsets RGRAPH_PLUGIN_PATH for a test and restores it.
class PluginPathEnv {
 public:
  PluginPathEnv() {
    if (const char* v = getenv("RGRAPH_PLUGIN_PATH")) saved_ = v, had_ = true;
    unsetenv("RGRAPH_PLUGIN_PATH");
  }
  ~PluginPathEnv() {
    if (had_)
      setenv("RGRAPH_PLUGIN_PATH", saved_.c_str(), 1);
    else
      unsetenv("RGRAPH_PLUGIN_PATH");
  }

 private:
  std::string saved_;
  bool had_ = false;
};

class PluginLoaderTest : public ::testing::Test {
 protected:
  PluginPathEnv env;
};

void expectOneLine(const std::string& error) {
  EXPECT_FALSE(error.empty());
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

}  // namespace

TEST_F(PluginLoaderTest, LoadsBloomWithItsOrigin) {
  PassRegistry registry;
  PluginLoader loader(registry);
  std::string error;
  const LoadedPlugin* p = loader.load("bloom", {}, error);
  ASSERT_NE(p, nullptr) << error;
  EXPECT_TRUE(error.empty());
  EXPECT_EQ(p->name, "bloom");
  EXPECT_EQ(p->path, canonical(kPlugins + "/librgraph_bloom.so"));
  EXPECT_EQ(p->passTypes, (std::vector<std::string>{"bloom_bright", "bloom_blur", "bloom_composite"}));
  for (const auto& t : p->passTypes) {
    const PassTypeDesc* desc = registry.find(t);
    ASSERT_NE(desc, nullptr) << t;
    EXPECT_EQ(desc->origin, p->path);
    EXPECT_TRUE(desc->create);
  }
}

TEST_F(PluginLoaderTest, LoadsSsaoWithItsOrigin) {
  PassRegistry registry;
  PluginLoader loader(registry);
  std::string error;
  const LoadedPlugin* p = loader.load("ssao", {}, error);
  ASSERT_NE(p, nullptr) << error;
  EXPECT_EQ(p->path, canonical(kPlugins + "/librgraph_ssao.so"));
  for (const char* t : {"ssao", "ssao_blur", "ssao_upsample"}) {
    const PassTypeDesc* desc = registry.find(t);
    ASSERT_NE(desc, nullptr) << t;
    EXPECT_EQ(desc->origin, p->path);
  }
  // The lighting pass's G-buffer layouts, compact included.
  const ParamDecl* layout = registry.find("ssao")->findParam("layout");
  ASSERT_NE(layout, nullptr);
  EXPECT_NE(std::find(layout->choices.begin(), layout->choices.end(), "compact"), layout->choices.end());
}

TEST_F(PluginLoaderTest, PluginShadersResolveToTheirFolder) {
  // Built into <build>/share/rgraph/plugins/<name>/ beside <build>/lib/rgraph/plugins.
  PassRegistry registry;
  PluginLoader loader(registry);
  std::string error;
  ASSERT_NE(loader.load("bloom", {}, error), nullptr) << error;
  ASSERT_NE(loader.load("ssao", {}, error), nullptr) << error;
  for (const char* t : {"bloom_bright", "bloom_blur", "bloom_composite", "ssao", "ssao_blur", "ssao_upsample"}) {
    const PassTypeDesc* desc = registry.find(t);
    ASSERT_NE(desc, nullptr);
    const std::vector<std::string> files = desc->shaderFiles();
    ASSERT_EQ(files.size(), 2u) << t;
    EXPECT_EQ(files[0], "fullscreen.vert");
    const fs::path frag = files[1];
    EXPECT_TRUE(frag.is_absolute()) << frag;
    EXPECT_TRUE(fs::is_regular_file(frag)) << frag;
    EXPECT_NE(frag.string().find("/share/rgraph/plugins/"), std::string::npos) << frag;
  }
}

TEST_F(PluginLoaderTest, LoadingTwiceIsANoOp) {
  PassRegistry registry;
  PluginLoader loader(registry);
  std::string error;
  const LoadedPlugin* a = loader.load("bloom", {}, error);
  ASSERT_NE(a, nullptr) << error;
  const LoadedPlugin* b = loader.load(kPlugins + "/librgraph_bloom.so", {}, error);
  EXPECT_EQ(a, b) << error;
  EXPECT_EQ(loader.loaded().size(), 1u);
}

TEST_F(PluginLoaderTest, MissingPluginNamesItAndTheFoldersSearched) {
  PassRegistry registry;
  PluginLoader loader(registry);
  loader.addSearchDirectory("/nonexistent/plugin/dir");
  std::string error;
  EXPECT_EQ(loader.load("no_such_plugin", {}, error), nullptr);
  expectOneLine(error);
  EXPECT_NE(error.find("plugin 'no_such_plugin'"), std::string::npos) << error;
  EXPECT_NE(error.find("not found"), std::string::npos) << error;
  EXPECT_NE(error.find("librgraph_no_such_plugin.so"), std::string::npos) << error;
  EXPECT_NE(error.find("/nonexistent/plugin/dir"), std::string::npos) << error;
  EXPECT_NE(error.find(canonical(kPlugins)), std::string::npos) << error;
  EXPECT_TRUE(loader.loaded().empty());
}

TEST_F(PluginLoaderTest, MissingPathIsRelativeToTheBaseFolder) {
  PassRegistry registry;
  PluginLoader loader(registry);
  std::string error;
  EXPECT_EQ(loader.load("./sub/libnothing.so", "/some/config/dir", error), nullptr);
  expectOneLine(error);
  EXPECT_NE(error.find("plugin './sub/libnothing.so': file not found: /some/config/dir/sub/libnothing.so"),
            std::string::npos)
      << error;
}

TEST_F(PluginLoaderTest, WrongAbiIsRefusedBeforeRegistering) {
  // The fixtures' register functions abort: reaching one fails this test.
  // wrong_abi: a version from the future; abi_previous: built against ABI 7,
  // before SceneFeatures's light-marker facts (8).
  static_assert(RGRAPH_PLUGIN_ABI_VERSION == 8u, "abi_previous stands for the version before this one");
  const std::pair<const char*, const char*> cases[] = {{"wrong_abi", "999"}, {"abi_previous", "7"}};
  for (const auto& [name, found] : cases) {
    SCOPED_TRACE(name);
    PassRegistry registry;
    PluginLoader loader(registry);
    std::string error;
    EXPECT_EQ(loader.loadFile(fixture(name), error), nullptr);
    expectOneLine(error);
    EXPECT_NE(error.find(canonical(fixture(name))), std::string::npos) << error;
    EXPECT_NE(error.find("ABI version mismatch: expected " + std::to_string(RGRAPH_PLUGIN_ABI_VERSION) + ", found " +
                         found),
              std::string::npos)
        << error;
    EXPECT_TRUE(registry.all().empty());
  }
}

TEST_F(PluginLoaderTest, LibraryWithoutEntryPointIsRefused) {
  PassRegistry registry;
  PluginLoader loader(registry);
  std::string error;
  EXPECT_EQ(loader.loadFile(fixture("no_entry"), error), nullptr);
  expectOneLine(error);
  EXPECT_NE(error.find("not an rgraph plugin: no entry point 'rgraph_plugin_abi_version'"), std::string::npos)
      << error;

  EXPECT_EQ(loader.loadFile(fixture("abi_only"), error), nullptr);
  expectOneLine(error);
  EXPECT_NE(error.find("no entry point 'rgraph_plugin_register'"), std::string::npos) << error;
  EXPECT_TRUE(registry.all().empty());
}

TEST_F(PluginLoaderTest, LibraryThatFailsToLoadGivesDlerror) {
  PassRegistry registry;
  PluginLoader loader(registry);
  std::string error;
  EXPECT_EQ(loader.loadFile(fixture("unresolved"), error), nullptr);
  expectOneLine(error);
  EXPECT_NE(error.find("cannot load the library"), std::string::npos) << error;
  EXPECT_NE(error.find("rgraph_fixture_symbol_nobody_defines"), std::string::npos) << error;

  TempDir dir;
  const std::string garbage = dir.path() + "/librgraph_garbage.so";
  std::ofstream(garbage) << "not an ELF file\n";
  loader.addSearchDirectory(dir.path());
  EXPECT_EQ(loader.load("garbage", {}, error), nullptr);
  expectOneLine(error);
  // Refused before dlopen sees it (plugin_file_check.h).
  EXPECT_NE(error.find("plugin 'garbage' (" + canonical(garbage) + "): not a loadable plugin: not an ELF shared library"),
            std::string::npos)
      << error;
}

TEST_F(PluginLoaderTest, DuplicateOfABuiltinRefusesTheWholePlugin) {
  PassRegistry registry = PassRegistry::builtins();  // a copy: built-ins only
  ASSERT_NE(registry.find("tonemap"), nullptr);
  PluginLoader loader(registry);
  std::string error;
  EXPECT_EQ(loader.loadFile(fixture("dup_builtin"), error), nullptr);
  expectOneLine(error);
  EXPECT_NE(error.find("registration failed: pass type 'tonemap' is already registered (from built-in)"),
            std::string::npos)
      << error;
  EXPECT_EQ(registry.find("fixture_dup_first"), nullptr) << "all or nothing";
  EXPECT_EQ(registry.find("tonemap")->origin, "built-in");
}

TEST_F(PluginLoaderTest, DuplicateWithinAPluginIsRefused) {
  PassRegistry registry;
  PluginLoader loader(registry);
  std::string error;
  EXPECT_EQ(loader.loadFile(fixture("dup_self"), error), nullptr);
  expectOneLine(error);
  EXPECT_NE(error.find("pass type 'fixture_twice' is already registered"), std::string::npos) << error;
  EXPECT_EQ(registry.find("fixture_twice"), nullptr);
}

TEST_F(PluginLoaderTest, DuplicateAcrossPluginsNamesTheFirst) {
  TempDir dir;
  const std::string copy = dir.path() + "/librgraph_fixture_good_copy.so";
  fs::copy_file(fixture("good"), copy);
  PassRegistry registry;
  PluginLoader loader(registry);
  std::string error;
  ASSERT_NE(loader.loadFile(fixture("good"), error), nullptr) << error;
  EXPECT_EQ(loader.loadFile(copy, error), nullptr);
  expectOneLine(error);
  EXPECT_NE(error.find("pass type 'fixture_noop' is already registered (from " + canonical(fixture("good")) + ")"),
            std::string::npos)
      << error;
  EXPECT_EQ(registry.find("fixture_noop")->origin, canonical(fixture("good")));
}

TEST_F(PluginLoaderTest, BadDeclarationAndThrowingRegistrationAreRefused) {
  PassRegistry registry;
  PluginLoader loader(registry);
  std::string error;
  EXPECT_EQ(loader.loadFile(fixture("bad_decl"), error), nullptr);
  expectOneLine(error);
  EXPECT_NE(error.find("default of parameter 'gain' is out of its range"), std::string::npos) << error;

  EXPECT_EQ(loader.loadFile(fixture("throws"), error), nullptr);
  expectOneLine(error);
  EXPECT_NE(error.find("registration failed: registration threw: fixture exploded"), std::string::npos) << error;
  EXPECT_TRUE(registry.all().empty());
}

TEST_F(PluginLoaderTest, SearchOrderPluginPathThenEnvironment) {
  TempDir a, b, c;
  fs::copy_file(fixture("good"), a.path() + "/librgraph_fixture_good.so");
  fs::copy_file(fixture("good"), b.path() + "/librgraph_fixture_good.so");
  fs::copy_file(fixture("good"), c.path() + "/fixture_plain.so");
  PassRegistry registry;

  setenv("RGRAPH_PLUGIN_PATH", ("/nonexistent:" + b.path()).c_str(), 1);
  {
    PluginLoader loader(registry);
    EXPECT_EQ(loader.find("fixture_good"), canonical(b.path() + "/librgraph_fixture_good.so"));
    loader.addSearchDirectory(a.path());  // --plugin-path comes first
    EXPECT_EQ(loader.find("fixture_good"), canonical(a.path() + "/librgraph_fixture_good.so"));
    const auto dirs = loader.searchDirectories();
    ASSERT_GE(dirs.size(), 3u);
    EXPECT_EQ(dirs[0], canonical(a.path()));
    EXPECT_EQ(dirs[1], "/nonexistent");
    EXPECT_EQ(dirs[2], canonical(b.path()));
    // rgraph's own plugin folder comes last: found from where this program
    // and librgraph.so are (<build>/bin, <build>/lib), not baked in.
    EXPECT_EQ(dirs.back(), canonical(kPlugins));
  }
  {
    // <name>.so, and a name that is a file name.
    PluginLoader loader(registry);
    loader.addSearchDirectory(c.path());
    EXPECT_EQ(loader.find("fixture_plain"), canonical(c.path() + "/fixture_plain.so"));
    EXPECT_EQ(loader.find("fixture_plain.so"), canonical(c.path() + "/fixture_plain.so"));
    // A path with '/' is relative to the base folder, never searched.
    EXPECT_EQ(loader.find("./fixture_plain.so", c.path()), canonical(c.path() + "/fixture_plain.so"));
    EXPECT_EQ(loader.find("./fixture_plain.so", a.path()), "");
  }
}

TEST_F(PluginLoaderTest, GoodFixtureRegistersThroughTheMacro) {
  PassRegistry registry;
  PluginLoader loader(registry);
  loader.addSearchDirectory(kFixtures);
  std::string error;
  const LoadedPlugin* p = loader.load("fixture_good", {}, error);
  ASSERT_NE(p, nullptr) << error;
  EXPECT_EQ(p->name, "fixture_good");
  ASSERT_NE(registry.find("fixture_noop"), nullptr);
  EXPECT_EQ(registry.find("fixture_noop")->origin, canonical(fixture("good")));
  EXPECT_TRUE(registry.find("fixture_noop")->create() != nullptr);
}

// "unknown pass type": which plugin on the path has it. Every fixture is
// probed (wrong ABI, no entry point, a registration that throws, an
// unresolved symbol, a duplicate: each skipped without a crash); only the
// good one provides fixture_noop, and nothing reaches the registry.
TEST_F(PluginLoaderTest, FindProviderProbesThePathWithoutRegistering) {
  PassRegistry registry;
  PluginLoader loader(registry);
  loader.addSearchDirectory(kFixtures);
  const std::optional<PluginLoader::Provider> p = loader.findProvider("fixture_noop");
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->name, "fixture_good");
  EXPECT_EQ(p->path, canonical(fixture("good")));
  EXPECT_FALSE(loader.findProvider("fixture_twice").has_value());  // dup_self's registration is refused
  EXPECT_FALSE(loader.findProvider("no_plugin_has_this").has_value());
  EXPECT_TRUE(registry.all().empty());
  EXPECT_TRUE(loader.loaded().empty());
  // Loading it afterwards registers its types as usual; a loaded plugin is
  // not offered again.
  std::string error;
  ASSERT_NE(loader.load("fixture_good", {}, error), nullptr) << error;
  EXPECT_NE(registry.find("fixture_noop"), nullptr);
  EXPECT_FALSE(loader.findProvider("fixture_noop").has_value());
}

// A file that another of the same name shadows earlier on the path is named
// by its path: the name would load the other one.
TEST_F(PluginLoaderTest, FindProviderNamesAShadowedPluginByItsPath) {
  TempDir first;
  std::ofstream(first.path() + "/librgraph_fixture_good.so") << "not a library";
  PassRegistry registry;
  PluginLoader loader(registry);
  loader.addSearchDirectory(first.path());
  loader.addSearchDirectory(kFixtures);
  const std::optional<PluginLoader::Provider> p = loader.findProvider("fixture_noop");
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->name, canonical(fixture("good")));
  EXPECT_EQ(p->path, canonical(fixture("good")));
}

// librgraph.so of a build tree reads the source tree's shaders and pipelines
// (the marker CMake writes beside it) and its plugins from <build>/lib/rgraph/plugins.
TEST(OwnFiles, ABuildTreesLibraryReadsItsSourceTree) {
  const OwnFiles& own = ownFiles();
  EXPECT_TRUE(own.buildTree) << own.codeFile;
  EXPECT_EQ(own.codeFile, canonical(kPlugins + "/../../librgraph.so"));
  EXPECT_EQ(canonical(own.shaders), canonical(std::string(RGRAPH_SOURCE_DIR) + "/shaders"));
  EXPECT_EQ(canonical(own.pipelines), canonical(std::string(RGRAPH_SOURCE_DIR) + "/pipelines"));
  EXPECT_EQ(own.plugins, canonical(kPlugins));
}
