// rgraph view's parameter editor without a window: edits keep the file's key
// order, mistakes are refused with a message, saving round-trips, and an
// edit applied through Renderer::reloadJson changes the image.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "rgraph/error.h"
#include "rgraph/renderer.h"
#include "test_support.h"
#include "view_panels.h"
#include "view_test_util.h"

namespace {
using namespace rgraph;
using Json = nlohmann::ordered_json;
namespace fs = std::filesystem;

const std::string& kDefault = viewtest::kDefaultPipeline;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A private copy of a shipped pipeline (tests write files).
std::string tempCopy(const std::string& from, const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rgraph-view-panels-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path to = dir / name;
  fs::copy_file(from, to, fs::copy_options::overwrite_existing);
  return to.string();
}

size_t tonemapIndex(const Json& doc) {
  for (size_t i = 0; i < doc["passes"].size(); ++i)
    if (doc["passes"][i]["name"] == "tonemap") return i;
  ADD_FAILURE() << "no tonemap pass";
  return 0;
}

TEST(ViewParamEditor, AnEditChangesOnlyThatValueAndKeepsKeyOrder) {
  view::ParamEditor editor(kDefault);
  std::string error;
  const auto text = editor.withParam("tonemap", "gamma", "2.2", error);
  ASSERT_TRUE(text) << error;

  Json expected = Json::parse(slurp(kDefault));
  expected["passes"][tonemapIndex(expected)]["params"]["gamma"] = 2.2;
  EXPECT_EQ(*text, expected.dump(2) + "\n");
  // The top-level keys come back in the file's order, not sorted.
  std::vector<std::string> keys;
  const Json edited = Json::parse(*text);
  for (const auto& item : edited.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"version", "description", "resources", "passes", "output"}));
  EXPECT_EQ(editor.text(), slurp(kDefault)) << "withParam gives new text; the editor keeps its own until accept()";
}

TEST(ViewParamEditor, AParameterNotInTheFileIsAddedUnderParams) {
  view::ParamEditor editor(kDefault);
  std::string error;
  const auto text = editor.withParam("tonemap", "exposure", "2.0", error);
  ASSERT_TRUE(text) << error;
  const Json doc = Json::parse(*text);
  std::vector<std::string> keys;
  for (const auto& item : doc["passes"][tonemapIndex(doc)]["params"].items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"operator", "gamma", "exposure"}));
  EXPECT_EQ(doc["passes"][tonemapIndex(doc)]["params"]["exposure"], 2.0);
}

TEST(ViewParamEditor, UnknownPassUnknownParameterAndBadJsonAreRefusedWithAMessage) {
  view::ParamEditor editor(kDefault);
  std::string error;
  EXPECT_FALSE(editor.withParam("tonemapp", "gamma", "2.2", error));
  EXPECT_NE(error.find("no pass named 'tonemapp'"), std::string::npos) << error;
  EXPECT_NE(error.find("default.json"), std::string::npos) << error;
  EXPECT_NE(error.find("tonemap"), std::string::npos) << "lists the passes: " << error;

  error.clear();
  EXPECT_FALSE(editor.withParam("tonemap", "gama", "2.2", error));
  EXPECT_NE(error.find("no parameter 'gama'"), std::string::npos) << error;
  EXPECT_NE(error.find("gamma"), std::string::npos) << "lists the parameters: " << error;

  error.clear();
  EXPECT_FALSE(editor.withParam("tonemap", "gamma", "2.2.2", error));
  EXPECT_NE(error.find("not JSON"), std::string::npos) << error;

  EXPECT_THROW(view::ParamEditor("/no/such/pipeline.json"), RuntimeError);
  const std::string broken = tempCopy(kDefault, "broken.json");
  std::ofstream(broken) << "{ \"version\": 1, ";
  try {
    view::ParamEditor bad(broken);
    ADD_FAILURE() << "a file that is not JSON was taken";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.json"), std::string::npos) << e.what();
  }
}

// The editor opens what the renderer may refuse (the viewer keeps running
// on the last good pipeline): odd members are skipped, never thrown on.
TEST(ViewParamEditor, APipelineWithWrongMemberTypesIsRefusedWithAMessageNotAnException) {
  const std::string path = tempCopy(kDefault, "odd.json");
  std::ofstream(path) << R"({ "version": 1, "passes": [ { "name": 5, "type": [] }, 7,
    { "name": "t", "type": "tonemap", "params": 3 } ] })";
  view::ParamEditor editor(path);
  std::string error;
  EXPECT_FALSE(editor.withParam("5", "gamma", "1", error));
  EXPECT_NE(error.find("no pass named '5'"), std::string::npos) << error;
  const auto text = editor.withParam("t", "gamma", "2.0", error);
  ASSERT_TRUE(text) << error;
  EXPECT_EQ(nlohmann::ordered_json::parse(*text)["passes"][2]["params"]["gamma"], 2.0)
      << "params replaced by an object";
}

// A script's value goes through the loader's parser and nesting bound: 100,000 levels used to overflow
// the stack copying the document (ParamEditor::edited), 1e999 to end the viewer with a bare
// [json.exception.out_of_range.406].
TEST(ViewParamEditor, ValuesAreParsedWithTheLimitsAndMessagesOfPipelineFiles) {
  view::ParamEditor editor(kDefault);
  std::string error;
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  EXPECT_FALSE(editor.withParam("tonemap", "gamma", deep, error));
  EXPECT_NE(error.find("nested deeper than"), std::string::npos) << error.substr(0, 300);
  EXPECT_LT(error.size(), 400u) << "the value is not repeated whole";
  // The bound counts the levels above the value: what fits a file's bound with them is taken.
  error.clear();
  EXPECT_TRUE(editor.withParam("tonemap", "gamma", std::string(200, '[') + std::string(200, ']'), error)) << error;
  EXPECT_FALSE(editor.withParam("tonemap", "gamma", std::string(300, '[') + std::string(300, ']'), error));

  error.clear();
  EXPECT_FALSE(editor.withParam("tonemap", "gamma", "1e999", error));
  EXPECT_NE(error.find("number overflow"), std::string::npos) << error;
  EXPECT_NE(error.find("param tonemap gamma"), std::string::npos) << error;
  // Invalid UTF-8 in a string would make the document's dump() throw later: refused here.
  error.clear();
  EXPECT_FALSE(editor.withParam("tonemap", "operator", "\"\xff\"", error));
  EXPECT_NE(error.find("not JSON"), std::string::npos) << error;

  // A file nested too deep is refused with the file's located message, as the renderer refuses it.
  const std::string path = tempCopy(kDefault, "deep.json");
  std::ofstream(path) << "{ \"version\": 1, \"x\": " << deep << " }";
  try {
    view::ParamEditor bad(path);
    ADD_FAILURE() << "a file nested 100,000 deep was taken";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("deep.json:1:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nested deeper than"), std::string::npos) << e.what();
  }
}

// The line and column of `needle`'s first character in `text` (1-based).
std::pair<int, int> lineColumnOf(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  const size_t lineStart = text.rfind('\n', at) + 1;  // npos + 1 == 0 on the first line
  return {int(std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n')) + 1, int(at - lineStart) + 1};
}

// Diagnostics about the editor's text are pointed at the same JSON path in the file the user has open,
// not at the re-serialised text (p.json:122:18 for a 33-line file).
TEST(ViewParamEditor, DiagnosticsPointIntoThePipelineFileItself) {
  view::ParamEditor editor(kDefault);
  const std::string file = slurp(kDefault);
  const size_t pass = tonemapIndex(Json::parse(file));
  Diagnostic d;
  d.code = DiagCode::param_range;
  d.message = "9 is above the maximum";
  d.where = {kDefault, 122, 18, "/passes/" + std::to_string(pass) + "/params/gamma"};
  Diagnostic added = d;  // a parameter the file does not write: its params object
  added.where.path = "/passes/" + std::to_string(pass) + "/params/exposure";
  Diagnostic shader;  // another file's diagnostic is left alone
  shader.where = {"shaders/tonemap.frag", 7, 0, ""};
  const Diagnostics moved = editor.inFile({d, added, shader});
  ASSERT_EQ(moved.size(), 3u);
  const auto [line, column] = lineColumnOf(file, "\"gamma\": 1.0");
  EXPECT_EQ(moved[0].where.line, line) << formatDiagnostic(moved[0]);
  EXPECT_EQ(moved[0].where.column, column + 9) << "at the value: " << formatDiagnostic(moved[0]);
  EXPECT_EQ(moved[0].where.path, d.where.path);
  const auto [paramsLine, paramsColumn] = lineColumnOf(file, "{ \"operator\": \"none\"");
  EXPECT_EQ(moved[1].where.line, paramsLine) << formatDiagnostic(moved[1]);
  EXPECT_EQ(moved[1].where.column, paramsColumn) << formatDiagnostic(moved[1]);
  EXPECT_EQ(moved[2].where.line, 7);
}

TEST(ViewParamEditor, SaveWritesTheAcceptedTextAndSaveAsLeavesTheFileAlone) {
  const std::string path = tempCopy(kDefault, "save.json");
  view::ParamEditor editor(path);
  std::string error;
  const auto text = editor.withParam("tonemap", "operator", "\"reinhard\"", error);
  ASSERT_TRUE(text) << error;
  editor.accept(*text);
  EXPECT_TRUE(editor.modified());

  const std::string other = path + ".as.json";
  editor.save(other);
  EXPECT_EQ(slurp(other), *text);
  EXPECT_EQ(slurp(path), slurp(kDefault)) << "save as leaves the pipeline file alone";

  EXPECT_TRUE(editor.modified()) << "saved elsewhere: the pipeline file still differs";
  editor.save();
  EXPECT_FALSE(editor.modified());
  EXPECT_EQ(slurp(path), *text);
  view::ParamEditor reread(path);
  EXPECT_EQ(reread.text(), *text);
  EXPECT_EQ(Json::parse(reread.text())["passes"][tonemapIndex(Json::parse(*text))]["params"]["operator"], "reinhard");
  EXPECT_THROW(editor.save("/no/such/dir/x.json"), RuntimeError);
  // A failed write says why (the OS's reason); the file is written through a temporary (OutputFile tests).
  try {
    editor.save("/dev/full");
    ADD_FAILURE() << "saving to /dev/full did not throw";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
  }
}

class ViewParamEditorGl : public ::testing::Test {
 protected:
  void SetUp() override { testsupport::sharedGlContext(); }
};

double meanByte(const std::vector<uint8_t>& rgba) {
  double sum = 0.0;
  for (size_t i = 0; i < rgba.size(); i += 4) sum += rgba[i] + rgba[i + 1] + rgba[i + 2];
  return sum / double(rgba.size() / 4 * 3);
}

TEST_F(ViewParamEditorGl, AnEditAppliedWithReloadJsonChangesTheImageAndABadOneIsRefused) {
  auto renderer = viewtest::defaultRenderer({96, 64});
  Diagnostics diags;
  ASSERT_TRUE(renderer);
  renderer->render();
  const std::vector<uint8_t> before = renderer->readOutputRGBA8();

  view::ParamEditor editor(kDefault);
  std::string error;
  auto text = editor.withParam("tonemap", "gamma", "2.2", error);
  ASSERT_TRUE(text) << error;
  ASSERT_TRUE(renderer->reloadJson(*text, diags)) << (diags.empty() ? "" : formatDiagnostic(diags.front()));
  editor.accept(*text);
  renderer->render();
  EXPECT_GT(meanByte(renderer->readOutputRGBA8()), meanByte(before) + 4.0) << "gamma 2.2 brightens the image";

  // A value the declaration refuses: the renderer says where, the editor keeps its text.
  const std::string accepted = editor.text();
  auto bad = editor.withParam("tonemap", "gamma", "9.0", error);
  ASSERT_TRUE(bad) << "range checks are the renderer's: " << error;
  diags.clear();
  EXPECT_FALSE(renderer->reloadJson(*bad, diags));
  ASSERT_FALSE(diags.empty());
  EXPECT_NE(formatDiagnostic(diags.front()).find("gamma"), std::string::npos) << formatDiagnostic(diags.front());
  editor.reject(formatDiagnostic(diags.front()));
  EXPECT_EQ(editor.text(), accepted);
}

}  // namespace
