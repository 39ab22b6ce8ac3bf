// Garbage in, diagnostics out: nothing here may crash, hang or throw.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "test_registry.h"

namespace rgraph {
namespace {

// Parses and builds; returns the diagnostics. Fails the test on an exception.
Diagnostics run(const std::string& text, bool* ok = nullptr) {
  Diagnostics diags;
  try {
    ConfigDocument doc = ConfigDocument::parseText(text, "g.json", diags);
    if (ok) *ok = doc.ok();
    PipelineConfig cfg = doc.build(test::testRegistry(), diags);
    (void)cfg;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "exception: " << e.what();
  }
  return diags;
}

int lineCount(const std::string& text) {
  int n = 1;
  for (char c : text) n += c == '\n';
  return n;
}

void expectLocatedSyntaxError(const std::string& text, int line, int column) {
  bool ok = true;
  Diagnostics diags = run(text, &ok);
  EXPECT_FALSE(ok);
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, DiagCode::json_syntax);
  EXPECT_EQ(diags[0].where.line, line) << formatDiagnostic(diags[0]);
  EXPECT_EQ(diags[0].where.column, column) << formatDiagnostic(diags[0]);
}

TEST(Robustness, EmptyAndBlank) {
  expectLocatedSyntaxError("", 1, 1);
  expectLocatedSyntaxError("   \n  ", 2, 3);  // at the end of input
  expectLocatedSyntaxError("\n\n\n", 4, 1);
}

TEST(Robustness, BinaryBytes) {
  std::string bytes;
  for (int i = 0; i < 256; ++i) bytes += static_cast<char>(i);
  bool ok = true;
  Diagnostics diags = run(bytes, &ok);
  EXPECT_FALSE(ok);
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, DiagCode::json_syntax);
  EXPECT_EQ(diags[0].where.line, 1);  // the NUL at offset 0
  EXPECT_EQ(diags[0].where.column, 1);

  expectLocatedSyntaxError(std::string("{\"a\": \"x\0y\"}", 12), 1, 9);  // control character in a string
  expectLocatedSyntaxError("{\"a\": \"\xFF\"}", 1, 8);                   // invalid UTF-8
  expectLocatedSyntaxError(std::string("{\"a\": 1}\0", 9), 1, 9);        // NUL after the value
}

TEST(Robustness, DeepNesting) {
  // Unclosed: refused at the bracket that opens level 257, before any parse.
  expectLocatedSyntaxError(std::string(10000, '['), 1, 257);
  // A syntax error before the bracket that is too deep is still the one reported.
  expectLocatedSyntaxError("[1 2, " + std::string(10000, '['), 1, 4);
  // A deep value followed by another member: building the document would copy
  // the deep value recursively (this overflowed the stack).
  {
    bool ok = true;
    Diagnostics diags = run("{\"notes\": " + std::string(100000, '[') + std::string(100000, ']') + ", \"passes\": []}", &ok);
    EXPECT_FALSE(ok);
    ASSERT_EQ(diags.size(), 1u);
    EXPECT_EQ(diags[0].where.column, 266);  // '{' is level 1; the 256th '[' after column 10 opens level 257
    EXPECT_NE(diags[0].message.find("nested deeper than 256"), std::string::npos);
  }
  // Closed: valid JSON, but deeper than the loader supports.
  std::string deep = std::string(10000, '[') + std::string(10000, ']');
  bool ok = true;
  Diagnostics diags = run(deep, &ok);
  EXPECT_FALSE(ok);
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, DiagCode::json_syntax);
  EXPECT_EQ(diags[0].where.column, 257);  // the bracket that opens level 257
  EXPECT_NE(diags[0].message.find("nested deeper than 256"), std::string::npos);
  // Exactly at the limit is fine (and is not a pipeline).
  diags = run(std::string(256, '[') + std::string(256, ']'), &ok);
  EXPECT_TRUE(ok);
  ASSERT_FALSE(diags.empty());
  EXPECT_EQ(diags[0].code, DiagCode::config_schema);
  // Very deep objects inside a pipeline.
  std::string objects = "{\"version\": 1, \"description\": ";
  for (int i = 0; i < 100000; ++i) objects += "{\"a\":";
  objects += "1";
  objects += std::string(100000, '}') + "}";
  diags = run(objects, &ok);
  EXPECT_FALSE(ok);
  ASSERT_EQ(diags.size(), 1u);
  EXPECT_EQ(diags[0].code, DiagCode::json_syntax);
}

TEST(Robustness, HugeNumbers) {
  expectLocatedSyntaxError("{\"version\": 1e999}", 1, 13);
  expectLocatedSyntaxError("{\"version\":\n  -1e400}", 2, 3);

  Diagnostics diags = run(R"({"version": 18446744073709551616, "resources": {
    "a": {"format": "rgba8", "samples": 99999999999999999999, "mips": 1e300, "size": [1e30, -5]},
    "b": {"type": "buffer", "buffer_bytes": 18446744073709551615}},
    "passes": [{"name": "t", "type": "tweak", "outputs": {"color": "a"},
                "params": {"count": 9223372036854775808, "gain": 1e308, "rect": [1e308, -1e308, 0, 0]}}],
    "output": "a"})");
  std::vector<std::string> paths;
  for (const auto& d : diags) paths.push_back(d.where.path);
  EXPECT_EQ(paths, (std::vector<std::string>{"/version", "/resources/a/samples", "/resources/a/mips",
                                             "/resources/a/size/0", "/resources/a/size/1", "/resources/b/buffer_bytes",
                                             "/passes/0/params/count", "/passes/0/params/gain",
                                             // rect has no range, but its components are floats for the pass
                                             "/passes/0/params/rect/0", "/passes/0/params/rect/1"}));
  for (const auto& d : diags) EXPECT_TRUE(d.where.known());
  EXPECT_EQ(diags.back().code, DiagCode::param_range);
}

TEST(Robustness, WrongShapesEverywhere) {
  // Every key present with a value of the wrong type.
  Diagnostics diags =
      run(R"({"version": [], "description": 1, "plugins": "x", "resources": {"r": 5, "s": {"format": "rgba8",
    "size": null, "samples": "4", "mips": true, "clear": {}, "type": 3}}, "passes": [1, {"name": 2, "type": [],
    "inputs": [], "outputs": "o", "params": 4, "enabled": 1, "side_effect": "yes", "description": false}],
    "output": 7})");
  EXPECT_GE(diags.size(), 15u);
  for (const auto& d : diags) {
    EXPECT_TRUE(d.where.known()) << formatDiagnostic(d);
    EXPECT_EQ(d.code, DiagCode::config_schema) << formatDiagnostic(d);
  }
  // Top-level scalars.
  for (const char* text : {"1", "\"str\"", "null", "true", "[]"}) {
    diags = run(text);
    ASSERT_EQ(diags.size(), 1u) << text;
    EXPECT_EQ(diags[0].where.line, 1);
    EXPECT_EQ(diags[0].where.column, 1);
  }
}

// Random edits of the valid configs: whatever comes out, the loader only
// returns diagnostics, each inside the text.
TEST(Robustness, MutatedConfigs) {
  std::vector<std::string> seeds;
  for (const char* name : {"deferred.json", "compute.json", "minimal.json", "history.json"})
    seeds.push_back(test::readFile(test::configsDir() + "/valid/" + name));
  const std::string alphabet = "{}[]:,\"\\ \n0123456789.-+eEtrufalsn\x01\xC3\xA9/~";
  std::mt19937 rng(12345);
  for (int iteration = 0; iteration < 10000; ++iteration) {
    std::string text = seeds[iteration % seeds.size()];
    int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !text.empty(); ++e) {
      size_t at = rng() % text.size();
      switch (rng() % 4) {
        case 0:
          text.erase(at, 1 + rng() % 8);
          break;
        case 1:
          text.insert(at, 1, alphabet[rng() % alphabet.size()]);
          break;
        case 2:
          text[at] = alphabet[rng() % alphabet.size()];
          break;
        case 3:
          text.resize(at);
          break;
      }
    }
    Diagnostics diags = run(text);
    int lines = lineCount(text);
    for (const auto& d : diags) {
      ASSERT_GE(d.where.line, 1) << "iteration " << iteration << ": " << formatDiagnostic(d);
      ASSERT_LE(d.where.line, lines) << "iteration " << iteration << ": " << formatDiagnostic(d);
      ASSERT_GE(d.where.column, 1) << "iteration " << iteration << ": " << formatDiagnostic(d);
    }
  }
}

}  // namespace
}  // namespace rgraph
