// ConfigDocument::locate / locateKey: positions of values and keys by JSON
// pointer. Columns are 1-based byte counts; every expectation below was
// counted by hand on the text it reads.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "test_registry.h"

namespace rgraph {
namespace {

// Line 2: `  "a": {"b": [10, {"c": "x\"y"}, [true, null]]},`
//          1234567890123456789012345678901234567890123456789
//                   1         2         3         4
const std::string kText =
    "{\n"
    "  \"a\": {\"b\": [10, {\"c\": \"x\\\"y\"}, [true, null]]},\n"
    "  \"t~/k\": 1,\n"
    "  \"uni\": [\"h\xC3\xA9llo\", 5],\n"
    "  \"esc\\u0041\": \"v\",\n"
    "\t\"tabbed\": 7,\n"
    "  \"empty\": {}, \"list\": [[], {}], \"last\": -1.5e3\n"
    "}\n";

struct Expect {
  std::string pointer;
  int line, column;
  std::string path;  // the pointer actually located
};

const std::vector<Expect> kValues = {
    {"", 1, 1, ""},
    {"/a", 2, 8, "/a"},
    {"/a/b", 2, 14, "/a/b"},
    {"/a/b/0", 2, 15, "/a/b/0"},
    {"/a/b/1", 2, 19, "/a/b/1"},
    {"/a/b/1/c", 2, 25, "/a/b/1/c"},
    {"/a/b/2", 2, 34, "/a/b/2"},
    {"/a/b/2/0", 2, 35, "/a/b/2/0"},
    {"/a/b/2/1", 2, 41, "/a/b/2/1"},
    {"/t~0~1k", 3, 11, "/t~0~1k"},
    {"/uni", 4, 10, "/uni"},
    {"/uni/0", 4, 11, "/uni/0"},
    {"/uni/1", 4, 21, "/uni/1"},    // after a 2-byte character: columns count bytes
    {"/escA", 5, 16, "/escA"},      // the key "esc\u0041" decodes to "escA"
    {"/tabbed", 6, 12, "/tabbed"},  // a tab counts as one column
    {"/empty", 7, 12, "/empty"},
    {"/list", 7, 24, "/list"},
    {"/list/0", 7, 25, "/list/0"},
    {"/list/1", 7, 29, "/list/1"},
    {"/last", 7, 42, "/last"},
    // Fallback to the closest existing parent.
    {"/a/b/1/zzz", 2, 19, "/a/b/1"},
    {"/a/b/7/x/y", 2, 14, "/a/b"},
    {"/nope", 1, 1, ""},
    {"/empty/x", 7, 12, "/empty"},
    {"/uni/0/deeper", 4, 11, "/uni/0"},
};

const std::vector<Expect> kKeys = {
    {"/a", 2, 3, "/a"},
    {"/a/b", 2, 9, "/a/b"},
    {"/a/b/1/c", 2, 20, "/a/b/1/c"},
    {"/t~0~1k", 3, 3, "/t~0~1k"},
    {"/escA", 5, 3, "/escA"},
    {"/tabbed", 6, 2, "/tabbed"},
    {"/list", 7, 16, "/list"},
    {"/last", 7, 34, "/last"},
    // Not an object member: the value's location.
    {"/a/b/0", 2, 15, "/a/b/0"},
    {"/a/zzz", 2, 8, "/a"},
};

void checkAll(const ConfigDocument& doc, const std::string& what) {
  for (const auto& e : kValues) {
    SourceLocation at = doc.locate(e.pointer);
    EXPECT_EQ(at.line, e.line) << what << " value " << e.pointer;
    EXPECT_EQ(at.column, e.column) << what << " value " << e.pointer;
    EXPECT_EQ(at.path, e.path) << what << " value " << e.pointer;
    EXPECT_EQ(at.file, "loc.json");
  }
  for (const auto& e : kKeys) {
    SourceLocation at = doc.locateKey(e.pointer);
    EXPECT_EQ(at.line, e.line) << what << " key " << e.pointer;
    EXPECT_EQ(at.column, e.column) << what << " key " << e.pointer;
    EXPECT_EQ(at.path, e.path) << what << " key " << e.pointer;
  }
}

TEST(Locate, ValuesKeysAndFallbacks) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText(kText, "loc.json", diags);
  ASSERT_TRUE(doc.ok()) << (diags.empty() ? "" : formatDiagnostic(diags[0]));
  ASSERT_TRUE(diags.empty());
  checkAll(doc, "LF");
}

TEST(Locate, CrlfLineEndingsGiveTheSamePositions) {
  std::string crlf;
  for (char c : kText) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText(crlf, "loc.json", diags);
  ASSERT_TRUE(doc.ok());
  checkAll(doc, "CRLF");
}

TEST(Locate, ByteOrderMarkCountsAsBytes) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText("\xEF\xBB\xBF{\"a\": 1}", "bom.json", diags);
  ASSERT_TRUE(doc.ok());
  EXPECT_EQ(doc.locate("").column, 4);
  EXPECT_EQ(doc.locate("/a").column, 10);
}

TEST(Locate, NestedPointersInAPipeline) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseFile(test::configsDir() + "/valid/deferred.json", diags);
  ASSERT_TRUE(doc.ok());
  SourceLocation tint1 = doc.locate("/passes/5/params/tint/1");
  EXPECT_EQ(tint1.line, 57);
  EXPECT_EQ(tint1.column, 21);
  // The string before it holds escaped quotes and a \u escape.
  SourceLocation label = doc.locate("/passes/5/params/label");
  EXPECT_EQ(label.line, 55);
  EXPECT_EQ(label.column, 18);
  SourceLocation mode = doc.locateKey("/passes/5/params/mode");
  EXPECT_EQ(mode.line, 56);
  EXPECT_EQ(mode.column, 9);
  SourceLocation missingParam = doc.locate("/passes/5/params/nothing");
  EXPECT_EQ(missingParam.path, "/passes/5/params");
  EXPECT_EQ(missingParam.line, 51);
  EXPECT_EQ(missingParam.column, 17);
}

TEST(Locate, DuplicateKeysLocateTheLastValue) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText("{\"a\": 1,\n \"a\": [2]}", "dup.json", diags);
  ASSERT_TRUE(doc.ok());
  EXPECT_EQ(doc.locate("/a").line, 2);
  EXPECT_EQ(doc.locate("/a").column, 7);
  EXPECT_EQ(doc.locate("/a/0").column, 8);
}

TEST(Locate, FailedDocumentHasNoPositions) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseText("{\"a\": }", "bad.json", diags);
  EXPECT_FALSE(doc.ok());
  SourceLocation at = doc.locate("/a");
  EXPECT_FALSE(at.known());
  EXPECT_EQ(at.file, "bad.json");
  EXPECT_TRUE(doc.plugins().empty());
  EXPECT_FALSE(doc.pluginLocation(0).known());
}

}  // namespace
}  // namespace rgraph
