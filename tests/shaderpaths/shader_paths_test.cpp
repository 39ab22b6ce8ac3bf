// Shader files named relative to the shader folders are read only from inside
// them: `..` and symbolic links that lead out of every folder are refused (and
// say where they lead), includes too; absolute paths (from code, never from a
// config) are used as is; folders added for the process come first
// (--shader-path) or last (a plugin's own).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "rgraph/shader_check.h"

using namespace rgraph;
namespace fs = std::filesystem;

namespace {

const std::string kTestShaders = std::string(RGRAPH_TEST_DATA_DIR) + "/shadercheck/shaders";

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string thrown(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

// root/ (the shader folder) and outside/ beside it, in a fresh temporary folder.
struct Folders {
  fs::path base, root, outside;
  Folders() {
    base = fs::temp_directory_path() / ("rgraph-shader-paths-" + std::to_string(::getpid()));
    fs::remove_all(base);
    root = base / "root";
    outside = base / "outside";
    fs::create_directories(root);
    fs::create_directories(outside);
    write(root / "ok.frag", "#version 450 core\nvoid main() {}\n");
    write(outside / "secret.frag", "#version 450 core\nvoid main() {}\n");
    write(outside / "common.glsl", "float f() { return 1.0; }\n");
  }
  ~Folders() {
    std::error_code ec;
    fs::remove_all(base, ec);
  }
  static void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }
  std::vector<std::string> dirs() const { return {root.string()}; }
};

TEST(ShaderPaths, DotDotThatLeavesTheFoldersIsRefused) {
  const std::vector<std::string> dirs = {kTestShaders};
  // tests/shadercheck/shader_check_test.cpp exists, one level above the folder.
  EXPECT_EQ(findShaderFile("../shader_check_test.cpp", dirs), "");
  const std::string what = thrown([&] { resolveShaderFile("../shader_check_test.cpp", dirs); });
  EXPECT_TRUE(contains(what, "shader file '../shader_check_test.cpp' resolves to ")) << what;
  EXPECT_TRUE(contains(what, "shader_check_test.cpp, outside the shader folders (" + kTestShaders + ")")) << what;
  EXPECT_TRUE(contains(thrown([&] { loadShaderSource("../../../../../../../../etc/passwd", {}, dirs); }),
                       "resolves to /etc/passwd, outside the shader folders"));
  // `..` that stays inside is fine.
  EXPECT_NE(findShaderFile("../shaders/four_outputs.frag", dirs), "");
  // A file that is not there anywhere is still "not found".
  EXPECT_TRUE(contains(thrown([&] { resolveShaderFile("../no-such.frag", dirs); }), "not found"));
}

// An absolute name comes from code (a plugin's or an application's pass type;
// a config cannot name one): used as is, inside the folders or not, as
// docs/writing-a-pass.md says. A missing one is named, not searched for.
TEST(ShaderPaths, AbsolutePathsAreUsedAsIs) {
  Folders f;
  EXPECT_EQ(findShaderFile((f.root / "ok.frag").string(), f.dirs()), (f.root / "ok.frag").string());
  const std::string elsewhere = (f.outside / "secret.frag").string();
  EXPECT_EQ(findShaderFile(elsewhere, f.dirs()), elsewhere);
  EXPECT_EQ(resolveShaderFile(elsewhere, f.dirs()), elsewhere);
  const std::string missing = (f.outside / "missing.frag").string();
  EXPECT_EQ(findShaderFile(missing, f.dirs()), "");
  EXPECT_EQ(thrown([&] { resolveShaderFile(missing, f.dirs()); }),
            "shader file '" + missing + "' not found (an absolute path: used as is, not searched for)");
}

// A file named by its absolute path includes files beside it (its folder acts as a shader folder for
// its includes); rgraph's own include/*.glsl are still found in the search path.
TEST(ShaderPaths, AnAbsolutelyNamedFileIncludesFilesBesideIt) {
  Folders f;
  Folders::write(f.outside / "main.frag", "#version 450 core\n#include \"common.glsl\"\nvoid main() {}\n");
  const ShaderSource src = loadShaderSource((f.outside / "main.frag").string(), {}, f.dirs());
  ASSERT_EQ(src.resolvedFiles.size(), 2u);
  EXPECT_EQ(src.resolvedFiles[1], (f.outside / "common.glsl").string());
  // A relative name is still confined: the same include from inside the folder leads out and is refused.
  Folders::write(f.root / "inside.frag", "#version 450 core\n#include \"../outside/common.glsl\"\nvoid main() {}\n");
  EXPECT_TRUE(contains(thrown([&] { loadShaderSource("inside.frag", {}, f.dirs()); }), "outside the shader folders"));
}

TEST(ShaderPaths, SymbolicLinksThatLeadOutAreRefused) {
  Folders f;
  fs::create_symlink(f.outside / "secret.frag", f.root / "link.frag");
  fs::create_symlink(f.root / "ok.frag", f.root / "inner.frag");
  EXPECT_EQ(findShaderFile("link.frag", f.dirs()), "");
  const std::string what = thrown([&] { resolveShaderFile("link.frag", f.dirs()); });
  EXPECT_TRUE(contains(what, "resolves to " + fs::weakly_canonical(f.outside / "secret.frag").string() +
                                 ", outside the shader folders"))
      << what;
  // A link that stays inside is followed.
  EXPECT_NE(findShaderFile("inner.frag", f.dirs()), "");
  // A linked folder leads out the same way.
  fs::create_directory_symlink(f.outside, f.root / "elsewhere");
  EXPECT_EQ(findShaderFile("elsewhere/secret.frag", f.dirs()), "");
}

TEST(ShaderPaths, IncludesThatLeadOutAreRefusedAtTheirLine) {
  Folders f;
  Folders::write(f.root / "inc.frag", "#version 450 core\n\n#include \"../outside/common.glsl\"\nvoid main() {}\n");
  try {
    loadShaderSource("inc.frag", {}, f.dirs());
    ADD_FAILURE() << "an include outside the folders was read";
  } catch (const ShaderSourceError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_TRUE(contains(e.message(), "outside the shader folders")) << e.message();
  }
}

TEST(ShaderPaths, ProcessFoldersComeFirstOrLast) {
  // Folders that do not exist, so that other tests' lookups stay as they are.
  const std::string first = "/shader/path/for/test";
  addShaderSearchDirectory(first);
  addPluginShaderDirectory("/plugin/shaders/for/test");
  const std::vector<std::string> dirs = defaultShaderSearchDirectories();
  ASSERT_GE(dirs.size(), 2u);
  EXPECT_EQ(dirs.front(), first);
  EXPECT_EQ(dirs.back(), "/plugin/shaders/for/test");
}

}  // namespace
