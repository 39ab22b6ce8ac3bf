// rgraph's own folders (rgraph/own_files.h): an install's found relative to
// the library, a build tree's named by its marker. This program links rgraph
// statically, so its own code file is the program in <build>/bin, beside the
// marker CMake writes there (librgraph.so's case: tests/plugin/plugin_loader_test.cpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "rgraph/own_files.h"
#include "rgraph/shader_check.h"

using namespace rgraph;
namespace fs = std::filesystem;

namespace {

std::string real(const fs::path& p) { return fs::weakly_canonical(p).string(); }

struct Scratch {
  fs::path base = fs::temp_directory_path() / ("rgraph-own-files-" + std::to_string(::getpid()));
  Scratch() { fs::remove_all(base); }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(base, ec);
  }
};

TEST(OwnFiles, ABuildTreeProgramReadsItsSourceTree) {
  const OwnFiles& own = ownFiles();
  EXPECT_TRUE(own.buildTree) << own.codeFile;
  EXPECT_EQ(own.codeFile, real(fs::read_symlink("/proc/self/exe")));
  EXPECT_EQ(real(own.shaders), real(std::string(RGRAPH_SOURCE_DIR) + "/shaders"));
  EXPECT_EQ(real(own.pipelines), real(std::string(RGRAPH_SOURCE_DIR) + "/pipelines"));
  // The built-in shaders are searched, after $RGRAPH_SHADER_DIR's folders.
  const std::vector<std::string> dirs = defaultShaderSearchDirectories();
  EXPECT_NE(std::find(dirs.begin(), dirs.end(), own.shaders), dirs.end());
  EXPECT_FALSE(findShaderFile("fullscreen.vert", dirs).empty());
}

TEST(OwnFiles, AnInstallIsFoundRelativeToTheLibrary) {
  // <prefix>/<libdir>/librgraph.so, as `cmake --install` lays it out (the file
  // itself need not exist: only where it is counts).
  Scratch s;
  const fs::path prefix = s.base / "anywhere" / "prefix";
  fs::create_directories(prefix / RGRAPH_INSTALL_LIBDIR);
  const OwnFiles own = ownFilesBeside((prefix / RGRAPH_INSTALL_LIBDIR / "librgraph.so").string());
  EXPECT_FALSE(own.buildTree);
  const fs::path share = prefix / RGRAPH_INSTALL_DATADIR / "rgraph";
  EXPECT_EQ(real(own.shaders), real(share / "shaders"));
  EXPECT_EQ(real(own.pipelines), real(share / "pipelines"));
  EXPECT_EQ(real(own.plugins), real(prefix / RGRAPH_INSTALL_LIBDIR / "rgraph" / "plugins"));
}

TEST(OwnFiles, AMarkerNamesTheBuildTreesFolders) {
  Scratch s;
  const fs::path lib = s.base / "build" / "lib";
  fs::create_directories(lib);
  std::ofstream(lib / kBuildTreeMarker) << "# a comment=not a key\r\nshaders=/src/tree/shaders\r\n"
                                        << "unknown=ignored\nno equals sign\npipelines=/src/tree/./pipelines\n";
  const OwnFiles own = ownFilesBeside((lib / "librgraph.so").string());
  EXPECT_TRUE(own.buildTree);
  EXPECT_EQ(own.shaders, "/src/tree/shaders");
  EXPECT_EQ(own.pipelines, "/src/tree/pipelines");
  EXPECT_EQ(own.plugins, (lib / "rgraph" / "plugins").lexically_normal().string());
}

}  // namespace
