// Renderer::load(path): another pipeline file, taken atomically as reload()
// takes one (on errors the old pipeline keeps running and the diagnostics
// name the new file), after which reload() and watchedFiles() follow the new
// file. reloadJson names the text it was given, not the renderer's file.
#include <GL/glcorearb.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "rgraph/gl/format.h"
#include "rgraph/gl/objects.h"
#include "rgraph/renderer.h"
#include "test_support.h"

namespace {
using namespace rgraph;
namespace fs = std::filesystem;

constexpr Extent kSize{8, 4};

// Tone mapping of an imported mid grey; `gamma` tells the pipelines apart in the image.
std::string pipeline(const std::string& gamma) {
  return R"({
  "version": 1,
  "resources": {
    "tint":   { "format": "rgba16f", "size": "output", "imported": true },
    "output": { "format": "rgba8", "size": "output" }
  },
  "passes": [
    { "name": "tonemap", "type": "tonemap", "params": { "operator": "none", "gamma": )" +
         gamma + R"( },
      "inputs": { "hdr": "tint" }, "outputs": { "output": "output" } }
  ],
  "output": "output"
})";
}

std::string allOf(const Diagnostics& diags) {
  std::string s;
  for (const auto& d : diags) s += formatDiagnostic(d) + "\n";
  return s.empty() ? "no diagnostics" : s;
}

bool has(const std::vector<std::string>& v, const std::string& s) { return std::find(v.begin(), v.end(), s) != v.end(); }

class RendererLoad : public ::testing::Test {
 protected:
  void SetUp() override {
    testsupport::sharedGlContext();
    dir_ = fs::temp_directory_path() / ("rgraph-renderer-load-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    first_ = (dir_ / "first.json").string();
    second_ = (dir_ / "second.json").string();
    put(first_, pipeline("1.0"));
    put(second_, pipeline("2.2"));
    tint_ = gl::createTexture2D(Format::rgba16f, kSize, 1, 1);
    const float grey[4] = {0.5f, 0.5f, 0.5f, 1.0f};
    glClearTexImage(tint_.id(), 0, GL_RGBA, GL_FLOAT, grey);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  static void put(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

  std::unique_ptr<Renderer> make(const std::string& path) {
    RendererOptions options;
    options.size = kSize;
    Diagnostics diags;
    auto r = Renderer::fromFile(path, options, diags);
    EXPECT_TRUE(r) << allOf(diags);
    return r;
  }
  // The red byte of the first pixel: 128 at gamma 1.0, 186 at gamma 2.2.
  int frame(Renderer& r) {
    r.importTexture("tint", tint_.id());
    r.render();
    return r.readOutputRGBA8()[0];
  }

  fs::path dir_;
  std::string first_, second_;
  gl::Texture tint_;
};

TEST_F(RendererLoad, LoadTakesAnotherFileAndFollowsIt) {
  auto r = make(first_);
  ASSERT_TRUE(r);
  const int before = frame(*r);
  EXPECT_EQ(before, 128);
  Diagnostics diags;
  ASSERT_TRUE(r->load(second_, diags)) << allOf(diags);
  auto fresh = make(second_);
  ASSERT_TRUE(fresh);
  const int loaded = frame(*r);
  EXPECT_EQ(loaded, frame(*fresh)) << "the loaded file renders as a renderer made from it";
  EXPECT_GT(loaded, before);
  EXPECT_TRUE(has(r->watchedFiles(), second_));
  EXPECT_FALSE(has(r->watchedFiles(), first_)) << "the old file is no longer watched";

  // reload() reads the new file, not the old one.
  put(second_, pipeline("1.5"));
  put(first_, pipeline("1.0 ,"));  // broken: reading it would fail
  diags.clear();
  ASSERT_TRUE(r->reload(diags)) << allOf(diags);
  const int reloaded = frame(*r);
  EXPECT_GT(reloaded, before);
  EXPECT_LT(reloaded, loaded);
}

TEST_F(RendererLoad, ABrokenFileIsRefusedNamedAndTheOldPipelineKeepsRunning) {
  auto r = make(first_);
  ASSERT_TRUE(r);
  const int before = frame(*r);
  const std::string broken = (dir_ / "broken.json").string();
  put(broken, pipeline("1.0") + "}");
  Diagnostics diags;
  EXPECT_FALSE(r->load(broken, diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_EQ(diags.front().where.file, broken) << allOf(diags);
  EXPECT_GT(diags.front().where.line, 0);
  EXPECT_EQ(frame(*r), before) << "the last good pipeline keeps rendering";
  EXPECT_TRUE(has(r->watchedFiles(), first_)) << "still bound to its file";
  EXPECT_FALSE(has(r->watchedFiles(), broken));

  // A file that does not exist: named too; reload() still reads the first file.
  const std::string missing = (dir_ / "missing.json").string();
  diags.clear();
  EXPECT_FALSE(r->load(missing, diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_NE(diags.front().message.find("missing.json"), std::string::npos) << allOf(diags);
  put(first_, pipeline("2.2"));
  diags.clear();
  ASSERT_TRUE(r->reload(diags)) << allOf(diags);
  EXPECT_GT(frame(*r), before);
}

// A broken JSON given to reloadJson is reported in the text given ("<json>", or the name given),
// at its own line and column, not as the renderer's file.
TEST_F(RendererLoad, ReloadJsonNamesTheTextItWasGiven) {
  auto r = make(first_);
  ASSERT_TRUE(r);
  const std::string text = "{\n  \"version\": 1,\n  \"passes\": [ }\n";
  Diagnostics diags;
  EXPECT_FALSE(r->reloadJson(text, diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_EQ(diags.front().where.file, "<json>") << allOf(diags);
  EXPECT_EQ(diags.front().where.line, 3) << allOf(diags);

  diags.clear();
  EXPECT_FALSE(r->reloadJson(text, diags, "editor buffer"));
  ASSERT_FALSE(diags.empty());
  EXPECT_EQ(diags.front().where.file, "editor buffer") << allOf(diags);
  EXPECT_EQ(formatDiagnostic(diags.front()).rfind("editor buffer:3:", 0), 0u) << formatDiagnostic(diags.front());

  // Accepted text keeps the renderer bound to its file: reload() reads the file again.
  diags.clear();
  ASSERT_TRUE(r->reloadJson(pipeline("2.2"), diags, "edited")) << allOf(diags);
  EXPECT_EQ(frame(*r), 186);
  EXPECT_TRUE(has(r->watchedFiles(), first_));
  diags.clear();
  ASSERT_TRUE(r->reload(diags)) << allOf(diags);
  EXPECT_EQ(frame(*r), 128);
}

// A renderer made from text reloads its last text, under the name it was given with.
TEST_F(RendererLoad, ARendererFromTextReloadsItsLastTextUnderItsName) {
  RendererOptions options;
  options.size = kSize;
  Diagnostics diags;
  auto r = Renderer::fromJson(pipeline("1.0"), "made.json", options, diags);
  ASSERT_TRUE(r) << allOf(diags);
  ASSERT_TRUE(r->reloadJson(pipeline("2.2"), diags, "second text")) << allOf(diags);
  ASSERT_TRUE(r->reload(diags)) << allOf(diags);
  EXPECT_EQ(frame(*r), 186) << "reload() took the last accepted text";
  EXPECT_TRUE(r->watchedFiles().empty() || !has(r->watchedFiles(), "second text"));
  // load() binds it to a file from then on.
  ASSERT_TRUE(r->load(first_, diags)) << allOf(diags);
  EXPECT_EQ(frame(*r), 128);
  EXPECT_TRUE(has(r->watchedFiles(), first_));
}

}  // namespace
