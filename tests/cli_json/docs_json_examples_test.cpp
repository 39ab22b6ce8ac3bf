// Every JSON example in README.md, docs/*.md and examples/*/README.md is
// checked against the real program (issue 16: the docs used pass types and
// slots that do not exist). A ```json block is a whole pipeline that
// `rgraph validate` (graph, pass checks, shader checks) accepts, unless the
// line before its fence says otherwise:
//
//   <!-- doc-check: invalid -->        a whole pipeline validate refuses; the
//                                      next ```text block is exactly what it
//                                      prints (its file name is the one used)
//   <!-- doc-check: resources -->      entries of "resources" (or the
//                                      "resources" member itself): added to a
//                                      small valid pipeline, which must
//                                      still validate
//   <!-- doc-check: pass FILE -->      a pass object: it replaces the pass of
//                                      that name in FILE (from the source
//                                      tree), which must still validate
//   <!-- doc-check: excerpt FILE -->   members of a pipeline ("..." lines
//                                      left out): each is in FILE with the
//                                      values shown (a pass: the one of that
//                                      name; members not shown may differ)
//   <!-- doc-check: syntax (WHY) -->   JSON only (it names files of the
//                                      reader's own); WHY is required
//
// Any other marker, or a block that is not JSON, fails.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const fs::path kSource = RGRAPH_SOURCE_DIR;

struct Example {
  std::string file;  // relative to the source tree
  int line = 0;      // of the opening fence
  std::string marker;
  std::string text;
  std::string expected;  // invalid: the ```text block that follows
};

std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<Example> examples() {
  std::vector<fs::path> files = {kSource / "README.md"};
  for (const auto& dir : {kSource / "docs", kSource / "examples"})
    for (const auto& e : fs::recursive_directory_iterator(dir))
      if (e.path().extension() == ".md") files.push_back(e.path());
  std::vector<Example> out;
  const std::regex markerRe(R"(^<!-- doc-check: (.*) -->$)");
  for (const auto& f : files) {
    std::vector<std::string> lines;
    std::istringstream in(read(f));
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    Example* open = nullptr;
    for (size_t i = 0; i < lines.size(); ++i) {
      const std::string& l = lines[i];
      if (open) {
        if (l == "```") {
          open = nullptr;
          continue;
        }
        open->text += l + "\n";
        continue;
      }
      if (l == "```text" && !out.empty() && out.back().marker == "invalid" && out.back().expected.empty() &&
          out.back().file == fs::relative(f, kSource).string()) {
        for (size_t j = i + 1; j < lines.size() && lines[j] != "```"; ++j) out.back().expected += lines[j] + "\n";
        continue;
      }
      if (l != "```json") continue;
      Example e;
      e.file = fs::relative(f, kSource).string();
      e.line = static_cast<int>(i + 1);
      std::smatch m;
      if (i > 0 && std::regex_match(lines[i - 1], m, markerRe)) e.marker = m[1];
      out.push_back(e);
      open = &out.back();
    }
  }
  return out;
}

std::string where(const Example& e) { return e.file + ":" + std::to_string(e.line); }

// A block that lists members ("key": value, ...) rather than one value is
// read as an object; "..." lines are left out.
json parseMembers(const std::string& text) {
  std::string kept;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) {
    const size_t at = l.find_first_not_of(" \t");
    if (at != std::string::npos && l.substr(at) != "...") kept += l + "\n";
  }
  const size_t first = kept.find_first_not_of(" \t\n");
  return json::parse(first != std::string::npos && kept[first] == '{' ? kept : "{" + kept + "}");
}

// Every member `part` has is in `whole` with the same value (objects may
// leave members out: an excerpt drops descriptions).
bool contained(const json& part, const json& whole) {
  if (!part.is_object() || !whole.is_object()) return part == whole;
  for (const auto& [k, v] : part.items())
    if (!whole.contains(k) || !contained(v, whole.at(k))) return false;
  return true;
}

struct Validation {
  int exit = -1;
  std::string out;
};

// Runs `rgraph validate` on the document written as NAME in a fresh folder.
Validation validate(const std::string& text, const std::string& name = "example.json") {
  static int n = 0;
  const fs::path dir = fs::temp_directory_path() / ("rgraph-docs-" + std::to_string(::getpid()) + "-" + std::to_string(n++));
  fs::create_directories(dir);
  const fs::path file = dir / name;
  std::ofstream(file, std::ios::binary) << text;
  auto r = rgraph::testsupport::runCommand("cd '" + dir.string() + "' && " + std::string(RGRAPH_CLI) + " validate " +
                                           name + " 2>&1");
  fs::remove_all(dir);
  return {r.exitCode, r.out};
}

// A small pipeline that validates, for fragments to be added to.
json basePipeline() {
  return json::parse(R"({"version": 1, "resources": {"doc_output": {"format": "rgba8"}},
    "passes": [{"name": "doc_fill", "type": "clear", "outputs": {"color": "doc_output"}}],
    "output": "doc_output"})");
}

void checkWhole(const Example& e) {
  ASSERT_NO_THROW((void)json::parse(e.text)) << "not JSON";
  const Validation v = validate(e.text);
  EXPECT_EQ(v.exit, 0) << v.out;
}

void checkInvalid(const Example& e) {
  ASSERT_FALSE(e.expected.empty()) << "an invalid example needs the ```text block of what validate prints after it";
  const std::string name = e.expected.substr(0, e.expected.find(':'));
  ASSERT_NE(name.find(".json"), std::string::npos) << "the expected output starts with the file name: " << e.expected;
  const Validation v = validate(e.text, name);
  EXPECT_EQ(v.exit, 1) << v.out;
  EXPECT_EQ(v.out, e.expected);
}

void checkResources(const Example& e) {
  json members = parseMembers(e.text);
  if (members.contains("resources")) members = members.at("resources");
  json p = basePipeline();
  ASSERT_GT(members.size(), 0u);
  for (const auto& [k, v] : members.items()) p["resources"][k] = v;
  const Validation v = validate(p.dump(2));
  EXPECT_EQ(v.exit, 0) << v.out << "\n" << p.dump(2);
}

void checkPass(const Example& e, const std::string& file) {
  const json pass = json::parse(e.text);
  json p = json::parse(read(kSource / file));
  bool replaced = false;
  for (auto& q : p.at("passes"))
    if (q.at("name") == pass.at("name")) {
      q = pass;
      replaced = true;
    }
  ASSERT_TRUE(replaced) << file << " has no pass " << pass.at("name");
  const Validation v = validate(p.dump(2));
  EXPECT_EQ(v.exit, 0) << v.out;
}

void checkExcerpt(const Example& e, const std::string& file) {
  const json part = parseMembers(e.text);
  const json whole = json::parse(read(kSource / file));
  ASSERT_GT(part.size(), 0u);
  for (const auto& [k, v] : part.items()) {
    ASSERT_TRUE(whole.contains(k)) << file << " has no \"" << k << "\"";
    if (k != "passes") {
      EXPECT_TRUE(contained(v, whole.at(k))) << "\"" << k << "\" differs from " << file << ": " << v.dump();
      continue;
    }
    for (const auto& pass : v) {
      bool found = false;
      for (const auto& q : whole.at("passes")) found = found || contained(pass, q);
      EXPECT_TRUE(found) << "pass " << pass.value("name", "?") << " is not in " << file << " as shown";
    }
  }
}

TEST(DocsJsonExamples, EveryExampleIsCheckedAgainstTheProgram) {
  const auto all = examples();
  size_t whole = 0, invalid = 0;
  for (const auto& e : all) {
    SCOPED_TRACE(where(e) + (e.marker.empty() ? "" : " (" + e.marker + ")"));
    const std::string kind = e.marker.substr(0, e.marker.find(' '));
    const std::string arg = e.marker.find(' ') == std::string::npos ? "" : e.marker.substr(e.marker.find(' ') + 1);
    if (e.marker.empty()) {
      checkWhole(e);
      ++whole;
    } else if (kind == "invalid") {
      checkInvalid(e);
      ++invalid;
    } else if (kind == "resources") {
      checkResources(e);
    } else if (kind == "pass") {
      checkPass(e, arg);
    } else if (kind == "excerpt") {
      checkExcerpt(e, arg);
    } else if (kind == "syntax") {
      EXPECT_FALSE(arg.empty()) << "say why it is only parsed";
      EXPECT_NO_THROW((void)parseMembers(e.text));
    } else {
      ADD_FAILURE() << "unknown marker '" << e.marker << "'";
    }
  }
  // The scan itself: it finds the examples the docs hold.
  EXPECT_GE(all.size(), 10u);
  EXPECT_GE(whole, 3u);
  EXPECT_GE(invalid, 1u);
}

// The checks fail on what issue 16 found: a type without those slots, a type
// that does not exist.
TEST(DocsJsonExamples, TheChecksRefuseWrongExamples) {
  Example badSlots{"x.md", 1, "", R"({"version": 1, "resources": {"hdr": {"format": "rgba16f"}},
    "passes": [{"name": "lighting", "type": "fullscreen", "inputs": {"albedo": "hdr"}, "outputs": {"color": "hdr2"}}],
    "output": "hdr"})", ""};
  EXPECT_NE(validate(badSlots.text).exit, 0);
  Example noType{"x.md", 1, "", R"({"version": 1, "resources": {"out": {"format": "rgba8"}},
    "passes": [{"name": "ui", "type": "blend", "outputs": {"color": "out"}}], "output": "out"})", ""};
  const Validation v = validate(noType.text);
  EXPECT_EQ(v.exit, 1);
  EXPECT_NE(v.out.find("unknown pass type 'blend'"), std::string::npos) << v.out;
  // An excerpt that is not in its file.
  EXPECT_NONFATAL_FAILURE(
      checkExcerpt({"x.md", 1, "", "\"resources\": {\"hdr\": {\"format\": \"rgba8\"}}\n", ""}, "pipelines/default.json"),
      "differs from");
  EXPECT_NONFATAL_FAILURE(checkExcerpt({"x.md", 1, "", "\"passes\": [{\"name\": \"tonemap\", \"type\": \"present\"}]\n", ""},
                                       "pipelines/default.json"),
                          "is not in");
}

}  // namespace

namespace {

// Issue 16: the parameter type names differed between writing-a-pass.md
// (number, integer, enumeration), pipeline-format.md and `rgraph passes`
// (float, int, enum). The docs use the names the program prints.
TEST(DocsParamTypes, TheDocsUseTheNamesRgraphPassesPrints) {
  const std::string format = read(kSource / "docs/pipeline-format.md");
  const size_t table = format.find("| declared type |");
  ASSERT_NE(table, std::string::npos);
  std::set<std::string> tableTypes;
  std::istringstream rows(format.substr(table, format.find("\n\n", table) - table));
  for (std::string row; std::getline(rows, row);)
    if (row.rfind("| `", 0) == 0) tableTypes.insert(row.substr(3, row.find('`', 3) - 3));
  EXPECT_EQ(tableTypes, (std::set<std::string>{"bool", "int", "float", "string", "shader", "enum", "vec3", "vec4"}));

  auto r = rgraph::testsupport::runCommand(std::string(RGRAPH_CLI) + " passes --json 2>/dev/null");
  ASSERT_EQ(r.exitCode, 0);
  std::set<std::string> printed;
  for (const auto& t : json::parse(r.out))
    for (const auto& p : t.at("params")) printed.insert(p.at("type").get<std::string>());
  for (const auto& t : printed) EXPECT_TRUE(tableTypes.count(t)) << "rgraph passes prints '" << t << "'";
  EXPECT_GE(printed.size(), 5u);

  const std::string pass = read(kSource / "docs/writing-a-pass.md");
  const size_t at = pass.find("Types, by the\nname `rgraph passes`");
  ASSERT_NE(at, std::string::npos);
  const std::string sentence = pass.substr(at, pass.find("The\nloader", at) - at);
  for (const auto& t : tableTypes) EXPECT_NE(sentence.find("`" + t + "`"), std::string::npos) << t << "\n" << sentence;
  // The enumerators appear only as what a type name stands for: "(`number`".
  for (const char* e : {"number", "integer", "enumeration"})
    for (size_t i = pass.find(std::string("`") + e + "`"); i != std::string::npos;
         i = pass.find(std::string("`") + e + "`", i + 1))
      EXPECT_EQ(pass[i - 1], '(') << "writing-a-pass.md names a parameter type '" << e << "': "
                                  << pass.substr(i > 40 ? i - 40 : 0, 80);
}

}  // namespace
