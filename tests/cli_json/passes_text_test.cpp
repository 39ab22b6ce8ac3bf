// `rgraph passes` as text: every slot and parameter line has its name, its
// access or type, and the rest in columns that line up, whatever the length
// of the longest name (constant_material once ran into its type: "constant_materialbool").
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "support/run_command.h"

namespace {

std::string run(const std::string& args, int* exitCode) {
  auto r = rgraph::testsupport::runCommand(std::string(RGRAPH_CLI) + " " + args + " 2>/dev/null");
  *exitCode = r.exitCode;
  return r.out;
}

TEST(CliPassesText, NamesTypesAndAccessesStandInAlignedColumns) {
  int rc = -1;
  const nlohmann::json types = nlohmann::json::parse(run("passes --json", &rc));
  ASSERT_EQ(rc, 0);
  const std::string text = run("passes", &rc);
  ASSERT_EQ(rc, 0);

  // Every "    slot  NAME  ACCESS ..." / "    param NAME  TYPE  = ..." line.
  std::set<size_t> secondColumn, thirdColumn;
  size_t lines = 0, longest = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    const bool slot = line.rfind("    slot  ", 0) == 0, param = line.rfind("    param ", 0) == 0;
    if (!slot && !param) continue;
    ++lines;
    const size_t nameAt = 10;
    const size_t nameEnd = line.find(' ', nameAt);
    ASSERT_NE(nameEnd, std::string::npos) << line;
    const size_t kindAt = line.find_first_not_of(' ', nameEnd);
    ASSERT_NE(kindAt, std::string::npos) << line;
    EXPECT_GE(kindAt - nameEnd, 2u) << "name and type/access must be apart: " << line;
    const size_t kindEnd = line.find(' ', kindAt);
    ASSERT_NE(kindEnd, std::string::npos) << line;
    const size_t restAt = line.find_first_not_of(' ', kindEnd);
    ASSERT_NE(restAt, std::string::npos) << line;
    EXPECT_GE(restAt - kindEnd, 2u) << line;
    secondColumn.insert(kindAt);
    thirdColumn.insert(restAt);
    longest = std::max(longest, nameEnd - nameAt);
  }
  EXPECT_EQ(secondColumn.size(), 1u) << text;
  EXPECT_EQ(thirdColumn.size(), 1u) << text;

  // Every slot and parameter of the JSON listing appears, its name followed by
  // spaces and its type (or access) as a separate word.
  size_t expected = 0;
  for (const auto& t : types) {
    for (const auto& s : t.at("slots")) {
      ++expected;
      const std::string name = s.at("name"), access = s.at("access");
      EXPECT_NE(text.find("slot  " + name + " "), std::string::npos) << name;
      EXPECT_EQ(text.find(name + access), std::string::npos) << name << " glued to " << access;
    }
    for (const auto& p : t.at("params")) {
      ++expected;
      const std::string name = p.at("name"), type = p.at("type");
      EXPECT_NE(text.find("param " + name + " "), std::string::npos) << name;
      EXPECT_EQ(text.find(name + type), std::string::npos) << name << " glued to " << type;
    }
  }
  EXPECT_EQ(lines, expected);
  // The regression itself: a name longer than the old fixed 14 columns.
  EXPECT_GT(longest, 14u);
  EXPECT_NE(text.find("constant_material "), std::string::npos);
}

}  // namespace
