// What a live-reloading tool (rgraph view) relies on: a renderer made from a
// file stays bound to it after reloadJson, a shader override that comes back
// is picked up, and a size whose textures exceed the memory budget is refused
// before anything is allocated, the last good size kept.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "rgraph/error.h"
#include "rgraph/gl/objects.h"
#include "rgraph/renderer.h"
#include "test_support.h"

namespace {
using namespace rgraph;
namespace fs = std::filesystem;

const std::string kDefault = std::string(RGRAPH_SOURCE_DIR) + "/pipelines/default.json";
const std::string kTonemap = std::string(RGRAPH_SOURCE_DIR) + "/shaders/tonemap.frag";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Replaces a file in one step, as editors do.
void put(const fs::path& path, const std::string& text) {
  std::ofstream(path.string() + ".tmp", std::ios::binary) << text;
  fs::rename(path.string() + ".tmp", path);
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

class RendererFileBinding : public ::testing::Test {
 protected:
  void SetUp() override {
    testsupport::sharedGlContext();
    dir_ = fs::temp_directory_path() / ("rgraph-file-binding-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::unique_ptr<Renderer> make(const std::string& path, RendererOptions options = {}) {
    options.size = {48, 32};
    Diagnostics diags;
    auto r = Renderer::fromFile(path, options, diags);
    EXPECT_TRUE(r) << (diags.empty() ? std::string("no diagnostics") : formatDiagnostic(diags.front()));
    if (r) r->setScene(scene_);
    return r;
  }
  std::vector<uint8_t> frame(Renderer& r) {
    r.render();
    return r.readOutputRGBA8();
  }
  fs::path dir_;
  std::shared_ptr<RenderScene> scene_ = RenderScene::load("learnopengl:overview");
};

// reloadJson used to forget the file: later edits of it were not watched and reload() re-read the old text.
TEST_F(RendererFileBinding, AfterReloadJsonTheFileIsStillWatchedAndReloadReadsIt) {
  const fs::path p = dir_ / "p.json";
  fs::copy_file(kDefault, p);
  auto r = make(p.string());
  ASSERT_TRUE(r);
  frame(*r);
  const std::string text = slurp(p.string());
  Diagnostics diags;
  ASSERT_TRUE(r->reloadJson(replaced(text, "\"gamma\": 1.0", "\"gamma\": 2.2"), diags));
  const std::vector<uint8_t> edited = frame(*r);
  const auto watched = r->watchedFiles();
  EXPECT_NE(std::find(watched.begin(), watched.end(), p.string()), watched.end()) << "the file is still watched";

  put(p, replaced(text, "\"gamma\": 1.0", "\"gamma\": 1.5"));
  diags.clear();
  ASSERT_TRUE(r->reload(diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  auto fresh = make(p.string());
  ASSERT_TRUE(fresh);
  EXPECT_TRUE(frame(*r) == frame(*fresh)) << "reload() read the file's new text, replacing the in-memory edit";
  EXPECT_FALSE(frame(*r) == edited);

  // A broken file is refused and named, as before any reloadJson.
  put(p, text + "}");
  diags.clear();
  EXPECT_FALSE(r->reload(diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_EQ(diags.front().where.file, p.string());
}

// reloadJson takes text from an editor: the file's nesting bound applies (no stack overflow), the last good
// pipeline keeps rendering.
TEST_F(RendererFileBinding, ReloadJsonRefusesTextNestedDeeperThanAFileMayBe) {
  auto r = make(kDefault);
  ASSERT_TRUE(r);
  const std::vector<uint8_t> good = frame(*r);
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  Diagnostics diags;
  EXPECT_FALSE(r->reloadJson(replaced(slurp(kDefault), "\"gamma\": 1.0", "\"gamma\": " + deep), diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_NE(diags.front().message.find("nested deeper than"), std::string::npos) << diags.front().message;
  EXPECT_EQ(diags.front().where.file, "<json>") << "the text given is named, not the file the renderer came from";
  EXPECT_TRUE(frame(*r) == good);
}

// An override deleted (the built-in shader takes over), then created again: the override is used again.
TEST_F(RendererFileBinding, AShaderOverrideThatComesBackIsPickedUpAtTheNextReload) {
  const fs::path override = dir_ / "tonemap.frag";
  const std::string red = replaced(slurp(kTonemap), "outColor = vec4(c, 1.0);", "outColor = vec4(1.0, 0.0, 0.0, 1.0);");
  put(override, red);
  RendererOptions options;
  options.shaderDirectories = {dir_.string()};
  auto r = make(kDefault, options);
  ASSERT_TRUE(r);
  const std::vector<uint8_t> overridden = frame(*r);
  EXPECT_EQ(overridden[0], 255);
  EXPECT_EQ(overridden[1], 0);

  fs::remove(override);
  Diagnostics diags;
  ASSERT_TRUE(r->reload(diags));
  const std::vector<uint8_t> builtIn = frame(*r);
  EXPECT_FALSE(builtIn == overridden) << "the built-in tonemap.frag took over";
  const auto watched = r->watchedFiles();
  EXPECT_NE(std::find(watched.begin(), watched.end(), override.string()), watched.end())
      << "the override's path is still watched after it was deleted";

  put(override, red);
  diags.clear();
  ASSERT_TRUE(r->reload(diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  EXPECT_TRUE(frame(*r) == overridden) << "the recreated override is compiled again";
  fs::remove(override);  // the folder stays in the process's shader search path: leave it empty
}

// A budget smaller than the plan at a new size: refused with both figures before any texture is made,
// the last good size and frame kept, and the next frame is drawn at that size instead of retrying.
TEST_F(RendererFileBinding, ASizeOverTheMemoryBudgetIsRefusedOnceAndTheLastGoodSizeIsKept) {
  RendererOptions options;
  options.maxMemoryBytes = 4u << 20;
  auto r = make(kDefault, options);
  ASSERT_TRUE(r);
  const std::vector<uint8_t> good = frame(*r);
  const uint64_t builds = r->builds();

  r->setSize({1024, 1024});
  const int64_t textures = gl::createdObjects(gl::ObjectKind::texture);
  std::string message = "(no error)";
  try {
    r->render();
  } catch (const RuntimeError& e) {
    message = e.what();
  }
  std::smatch need;  // the plan's bytes (Plan::allocatedBytes of the pipeline as adapted to the scene)
  ASSERT_TRUE(std::regex_search(message, need, std::regex("needs ([0-9]+) bytes"))) << message;
  EXPECT_GT(std::stoull(need[1].str()), options.maxMemoryBytes) << message;
  EXPECT_NE(message.find(std::to_string(options.maxMemoryBytes) + " bytes"), std::string::npos) << message;
  EXPECT_NE(message.find("RendererOptions::maxMemoryBytes"), std::string::npos) << message;
  EXPECT_NE(message.find("1024x1024"), std::string::npos) << message;
  EXPECT_EQ(gl::createdObjects(gl::ObjectKind::texture) - textures, 0) << "refused before allocating";

  EXPECT_EQ(r->size(), (Extent{48, 32})) << "size() is the last good size again";
  EXPECT_EQ(r->outputExtent(), (Extent{48, 32}));
  EXPECT_TRUE(frame(*r) == good) << "the next frame is the last good one, not a retry";
  EXPECT_LE(r->builds(), builds + 1);
}

}  // namespace
