// Large configs take the loader's paths for size: objects with many members
// are searched through a hash index (while parsing and when locating), and
// version names are resolved (by the compiler) whatever order the passes are
// declared in. They must give the same answers as small ones.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_registry.h"

namespace rgraph {
namespace {

std::string allDiagnostics(const Diagnostics& diags) {
  std::string out;
  for (const auto& d : diags) out += formatDiagnostic(d) + "\n";
  return out;
}

// 40 resources, one per line from line 4 (r<i> on line 4 + i), then a key
// written with an escape ("r\u0031x" is "r1x") and "r7" again with another
// format.
std::string manyResources() {
  std::string text = "{\n  \"version\": 1,\n  \"resources\": {\n";
  for (int i = 0; i < 40; ++i) text += "    \"r" + std::to_string(i) + "\": {\"format\": \"rgba8\"},\n";
  text += "    \"r\\u0031x\": {\"format\": \"rgba8\"},\n";     // line 44
  text += "    \"r7\": {\"format\": \"rgba16f\"}\n  },\n";       // line 45
  text += "  \"passes\": [{\"name\": \"d\", \"type\": \"decal\", \"outputs\": {\"color\": \"r0\"}}],\n";
  text += "  \"output\": \"r0\"\n}\n";
  return text;
}

TEST(LargeConfig, RepeatedKeyInALargeObjectIsReportedAndKeepsItsFirstPlaceAndLastValue) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText(manyResources(), "many.json", diags);
  ASSERT_TRUE(doc.ok()) << allDiagnostics(diags);
  PipelineConfig config = doc.build(test::testRegistry(), diags);
  ASSERT_EQ(diags.size(), 1u) << allDiagnostics(diags);
  EXPECT_EQ(formatDiagnostic(diags[0]),
            "many.json:45:5: error: /resources/r7: key 'r7' appears more than once in this object");

  // 41 distinct names; "r7" where it first appeared, with the last value.
  const GraphDesc& g = config.graph;
  ASSERT_EQ(g.resources.size(), 41u);
  EXPECT_EQ(g.resources[7].name, "r7");
  EXPECT_EQ(g.resources[7].texture.format, Format::rgba16f);
  EXPECT_EQ(g.resources[40].name, "r1x");

  // Positions through the index: the last "r7", the others on their lines.
  SourceLocation r7 = doc.locate("/resources/r7");
  EXPECT_EQ(r7.line, 45);
  EXPECT_EQ(r7.column, 11);
  EXPECT_EQ(doc.locateKey("/resources/r7").column, 5);
  for (int i : {0, 16, 17, 39}) {
    SourceLocation at = doc.locate("/resources/r" + std::to_string(i) + "/format");
    EXPECT_EQ(at.line, 4 + i) << i;
    EXPECT_EQ(at.column, 21 + static_cast<int>(std::to_string(i).size())) << i;
    EXPECT_EQ(at.path, "/resources/r" + std::to_string(i) + "/format");
  }
  EXPECT_EQ(doc.locate("/resources/r1x").line, 44);  // the key decoded from its escape
  EXPECT_EQ(doc.locateKey("/resources/r1x").column, 5);
  SourceLocation missing = doc.locate("/resources/r40/format");  // falls back to the object
  EXPECT_EQ(missing.path, "/resources");
  EXPECT_EQ(missing.line, 3);
}

TEST(LargeConfig, RepeatedKeysDeepInsideArraysAndEscapedKeysNameTheirPointer) {
  const std::string text =
      "{\"version\": 1,\n"
      "\"resources\": {\"a~b/c\": {\"format\": \"rgba8\",\n"
      "  \"format\": \"rgba16f\"}},\n"                                    // line 3
      "\"passes\": [{\"name\": \"x\", \"type\": \"decal\"}, {\"name\": \"y\", \"type\": \"decal\"},\n"
      "  {\"name\": \"z\", \"type\": \"decal\", \"name\": \"w\"}],\n"  // line 5
      "\"output\": \"a~b/c\"}\n";
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText(text, "dup.json", diags);
  ASSERT_TRUE(doc.ok()) << allDiagnostics(diags);
  PipelineConfig config = doc.build(test::testRegistry(), diags);
  std::vector<std::string> repeated;
  for (const auto& d : diags)
    if (d.message.find("appears more than once") != std::string::npos) repeated.push_back(formatDiagnostic(d));
  EXPECT_EQ(repeated, (std::vector<std::string>{
                          "dup.json:3:3: error: /resources/a~0b~1c/format: key 'format' appears more than once in this object",
                          "dup.json:5:34: error: /passes/2/name: key 'name' appears more than once in this object"}))
      << allDiagnostics(diags);
  ASSERT_EQ(config.graph.passes.size(), 3u);
  EXPECT_EQ(config.graph.passes[2].name, "w");  // the last value
}

// "color" (r32f), then 30 passes each loading the last version and writing
// the next ("c1".."c30"), and a geometry pass whose colour slot refuses r32f
// writing "c30" again. `reverse` declares the passes last to first.
std::string versionChain(bool reverse) {
  std::vector<std::string> passes;
  passes.push_back(R"({"name": "post", "type": "fullscreen", "inputs": {"source": "ldr"}, "outputs": {"color": "color"}})");
  std::string prev = "color";
  for (int i = 1; i <= 30; ++i) {
    const std::string cur = "c" + std::to_string(i);
    passes.push_back("{\"name\": \"p" + std::to_string(i) +
                     "\", \"type\": \"fullscreen\", \"inputs\": {\"source\": \"ldr\", \"color\": \"" + prev +
                     "\"}, \"outputs\": {\"color\": \"" + cur + "\"}}");
    prev = cur;
  }
  passes.push_back(R"({"name": "geo", "type": "geometry", "outputs": {"color": "c30", "depth": "depth"}})");
  if (reverse) std::reverse(passes.begin(), passes.end());
  std::string text =
      "{\"version\": 1, \"resources\": {\"color\": {\"format\": \"r32f\"}, \"depth\": {\"format\": \"depth24\"}, "
      "\"ldr\": {\"format\": \"rgba8\"}},\n\"passes\": [\n";
  for (size_t i = 0; i < passes.size(); ++i) text += passes[i] + (i + 1 < passes.size() ? ",\n" : "\n");
  return text + "],\n\"output\": \"c30\"}\n";
}

TEST(LargeConfig, VersionsResolveWhateverOrderThePassesAreDeclaredIn) {
  for (bool reverse : {false, true}) {
    Diagnostics diags;
    ConfigDocument doc = ConfigDocument::parseText(versionChain(reverse), "chain.json", diags);
    ASSERT_TRUE(doc.ok()) << allDiagnostics(diags);
    doc.build(test::testRegistry(), diags);
    ASSERT_EQ(diags.size(), 1u) << "reverse " << reverse << "\n" << allDiagnostics(diags);
    EXPECT_EQ(diags[0].code, DiagCode::format_not_allowed);
    EXPECT_EQ(diags[0].pass, "geo");
    EXPECT_EQ(diags[0].where.line, reverse ? 3 : 34);
    EXPECT_NE(diags[0].message.find("does not accept format r32f of 'c30' (a version of resource 'color')"),
              std::string::npos)
        << diags[0].message;
  }
}

// "a/b~c" -> "a~1b~0c" (RFC 6901).
std::string escapeToken(const std::string& key) {
  std::string out;
  for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

// Every value the JSON library reads, located by its pointer: the position
// found is that exact pointer (no fallback to a parent) and the character
// there starts a value of that type; object members' keys start with a quote.
// Over every config in tests/configs and pipelines/, and a large object.
void expectEveryValueLocated(const std::string& text, const std::string& what) {
  nlohmann::ordered_json reference;
  try {
    reference = nlohmann::ordered_json::parse(text);
  } catch (const std::exception&) {
    return;  // not JSON: nothing to locate
  }
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText(text, what, diags);
  if (!doc.ok()) {  // only nesting the library accepts and the loader bounds
    EXPECT_NE(allDiagnostics(diags).find("nested deeper than"), std::string::npos) << what << "\n"
                                                                                   << allDiagnostics(diags);
    return;
  }
  std::vector<size_t> lineStarts{0};
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n') lineStarts.push_back(i + 1);
  auto charAt = [&](const SourceLocation& at) -> char {
    if (at.line < 1 || static_cast<size_t>(at.line) > lineStarts.size() || at.column < 1) return '\0';
    size_t offset = lineStarts[at.line - 1] + static_cast<size_t>(at.column) - 1;
    return offset < text.size() ? text[offset] : '\0';
  };
  size_t checked = 0;
  auto walk = [&](auto&& self, const nlohmann::ordered_json& v, const std::string& pointer, bool member) -> void {
    SourceLocation at = doc.locate(pointer);
    EXPECT_EQ(at.path, pointer) << what;
    const char c = charAt(at);
    if (v.is_object())
      EXPECT_EQ(c, '{') << what << " " << pointer;
    else if (v.is_array())
      EXPECT_EQ(c, '[') << what << " " << pointer;
    else if (v.is_string())
      EXPECT_EQ(c, '"') << what << " " << pointer;
    else if (v.is_number())
      EXPECT_TRUE(c == '-' || (c >= '0' && c <= '9')) << what << " " << pointer << " at '" << c << "'";
    else if (v.is_boolean())
      EXPECT_EQ(c, v.get<bool>() ? 't' : 'f') << what << " " << pointer;
    else
      EXPECT_EQ(c, 'n') << what << " " << pointer;
    if (member) {
      SourceLocation key = doc.locateKey(pointer);
      EXPECT_EQ(charAt(key), '"') << what << " key " << pointer;
      EXPECT_TRUE(key.line < at.line || (key.line == at.line && key.column < at.column)) << what << " " << pointer;
    }
    ++checked;
    if (v.is_object())
      for (auto it = v.begin(); it != v.end(); ++it)
        self(self, *it, pointer + "/" + escapeToken(it.key()), true);
    else if (v.is_array())
      for (size_t i = 0; i < v.size(); ++i) self(self, v[i], pointer + "/" + std::to_string(i), false);
  };
  walk(walk, reference, "", false);
  EXPECT_GT(checked, 0u) << what;
}

TEST(LargeConfig, EveryValueOfEveryConfigIsLocatedAtItsOwnPointer) {
  size_t files = 0;
  for (const std::string dir : {test::configsDir() + "/valid", test::configsDir() + "/invalid",
                                std::string(RGRAPH_SOURCE_DIR) + "/pipelines",
                                std::string(RGRAPH_SOURCE_DIR) + "/pipelines/examples"}) {
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().extension() != ".json") continue;
      expectEveryValueLocated(test::readFile(entry.path().string()), entry.path().filename().string());
      ++files;
    }
  }
  EXPECT_GT(files, 40u);
  expectEveryValueLocated(manyResources(), "many.json");
  expectEveryValueLocated(versionChain(true), "chain.json");
}

}  // namespace
}  // namespace rgraph
