// `rgraph passes` as text answers on its own what a config may bind and set:
// every slot under the side of the config it is bound on ("inputs" or
// "outputs") with its access and accepted formats, every parameter with its
// type, default and range or choices (an int's range in integers), and the
// rules the type's checks enforce; names never run into the next column
// (constant_material once printed as "constant_materialbool"). Checked against
// `rgraph passes --json`, which reads the same declarations.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.h"

namespace {

std::string run(const std::string& args, int* exitCode, bool withStderr = false) {
  auto r = rgraph::testsupport::runCommand(std::string(RGRAPH_CLI) + " " + args +
                                           (withStderr ? " 2>&1" : " 2>/dev/null"));
  *exitCode = r.exitCode;
  return r.out;
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// The words of a line, split at runs of two or more spaces (the columns).
std::vector<std::string> columns(const std::string& line) {
  std::vector<std::string> out;
  size_t i = line.find_first_not_of(' ');
  while (i != std::string::npos) {
    size_t end = line.find("  ", i);
    out.push_back(line.substr(i, end == std::string::npos ? std::string::npos : end - i));
    i = end == std::string::npos ? end : line.find_first_not_of(' ', end);
  }
  return out;
}

std::string joined(const nlohmann::json& list, const std::string& sep, bool quote) {
  std::string out;
  for (const auto& v : list) out += (out.empty() ? "" : sep) + (quote ? v.dump() : v.get<std::string>());
  return out;
}

// One type's text block: its lines up to the next blank line.
std::map<std::string, std::vector<std::string>> blocks(const std::string& text) {
  std::map<std::string, std::vector<std::string>> out;
  std::string current;
  for (const auto& l : lines(text)) {
    if (l.empty()) {
      current.clear();
      continue;
    }
    if (current.empty()) current = l.substr(0, l.find("  ("));
    out[current].push_back(l);
  }
  return out;
}

// The line of slot or param `name` in a block's section ("inputs:", "outputs:", "params:").
const std::string* entry(const std::vector<std::string>& block, const std::string& section, const std::string& name) {
  bool in = false;
  for (const auto& l : block) {
    if (l.rfind("  ", 0) == 0 && l.rfind("   ", 0) != 0) in = l == "  " + section;
    if (in && l.rfind("    " + name + "  ", 0) == 0) return &l;
  }
  return nullptr;
}

TEST(CliPassesText, EverySlotParamAndRuleOfTheJsonIsInTheText) {
  int rc = -1;
  const nlohmann::json types = nlohmann::json::parse(run("passes --json", &rc));
  ASSERT_EQ(rc, 0);
  const std::string text = run("passes", &rc);
  ASSERT_EQ(rc, 0);
  const auto byType = blocks(text);
  ASSERT_EQ(byType.size(), types.size()) << text;
  size_t longest = 0, intRanges = 0, choices = 0, rules = 0;
  for (const auto& t : types) {
    const std::string name = t.at("type");
    SCOPED_TRACE(name);
    ASSERT_TRUE(byType.count(name)) << text;
    const auto& block = byType.at(name);
    EXPECT_EQ(block[0], name + "  (" + t.at("origin").get<std::string>() + ")");
    EXPECT_EQ(block[1], "  " + t.at("description").get<std::string>());
    for (const auto& s : t.at("slots")) {
      const std::string slot = s.at("name");
      const bool writes = s.at("binds_in") == "outputs";
      const std::string* line = entry(block, writes ? "outputs:" : "inputs:", slot);
      ASSERT_NE(line, nullptr) << slot << " not under " << s.at("binds_in") << "\n" << text;
      const auto cols = columns(*line);
      ASSERT_EQ(cols.size(), 4u) << *line;
      EXPECT_EQ(cols[0], slot);
      EXPECT_EQ(cols[1], s.at("required").get<bool>() ? "required" : "optional");
      EXPECT_EQ(cols[2], s.at("access"));
      const std::string formats =
          s.at("formats").empty() ? "any format" : "formats " + joined(s.at("formats"), ", ", false);
      EXPECT_EQ(cols[3], formats + (s.at("multisampled").get<bool>() ? "; multisampled too" : ""));
      longest = std::max(longest, slot.size());
    }
    for (const auto& p : t.at("params")) {
      const std::string param = p.at("name");
      const std::string* line = entry(block, "params:", param);
      ASSERT_NE(line, nullptr) << param << "\n" << text;
      const auto cols = columns(*line);
      ASSERT_GE(cols.size(), 3u) << *line;
      EXPECT_EQ(cols[0], param);
      EXPECT_EQ(cols[1], p.at("type"));
      EXPECT_EQ(cols[2], "= " + p.at("default").dump());
      std::string accepts;
      if (p.contains("choices")) {
        accepts = "one of " + joined(p.at("choices"), ", ", true);
        ++choices;
      } else if (p.contains("min") && p.contains("max")) {
        accepts = p.at("min").dump() + " to " + p.at("max").dump();
        if (p.at("type") == "vec3" || p.at("type") == "vec4") accepts = "each " + accepts;
      }
      if (p.at("type") == "int" && p.contains("min")) {
        // Integers print as integers: "1 to 8", not "1.0 to 8.0".
        EXPECT_TRUE(p.at("min").is_number_integer()) << p;
        EXPECT_EQ(accepts.find('.'), std::string::npos) << *line;
        ++intRanges;
      }
      if (!accepts.empty()) {
        ASSERT_EQ(cols.size(), 4u) << *line;
        EXPECT_EQ(cols[3], accepts);
      }
      longest = std::max(longest, param.size());
    }
    for (const auto& r : t.at("rules")) {
      EXPECT_NE(std::find(block.begin(), block.end(), "    " + r.get<std::string>()), block.end()) << r;
      ++rules;
    }
  }
  // The cases the issue names, so that none of them is vacuous.
  EXPECT_GT(longest, 14u);
  EXPECT_GT(intRanges, 0u);
  EXPECT_GT(choices, 0u);
  EXPECT_GT(rules, 0u);
  EXPECT_EQ(text.find("constant_materialbool"), std::string::npos);
}

TEST(CliPassesText, ColumnsLineUpWithinAType) {
  int rc = -1;
  const std::string text = run("passes", &rc);
  ASSERT_EQ(rc, 0);
  for (const auto& [type, block] : blocks(text)) {
    SCOPED_TRACE(type);
    // Slot lines: name, required, access, formats start at the same columns;
    // param lines: name, type, default.
    std::map<std::string, std::set<size_t>> starts;
    std::string section;
    for (const auto& l : block) {
      if (l.rfind("  ", 0) == 0 && l.rfind("   ", 0) != 0) section = l;
      if (l.rfind("    ", 0) != 0 || l.rfind("     ", 0) == 0 || section == "  rules:") continue;
      const bool param = section == "  params:";
      size_t at = 4;
      for (int c = 0; c < (param ? 3 : 4); ++c) {
        starts[(param ? "param" : "slot") + std::to_string(c)].insert(at);
        const size_t end = l.find("  ", at);
        if (end == std::string::npos) break;
        at = l.find_first_not_of(' ', end);
      }
    }
    for (const auto& [col, at] : starts) EXPECT_EQ(at.size(), 1u) << col << "\n" << text;
  }
}

// The must-show of issue 16: one type, with its slots' formats, its enum
// values and its same-size rule.
TEST(CliPassesText, OneTypeShowsFormatsChoicesAndRules) {
  int rc = -1;
  const std::string text = run("passes tonemap", &rc);
  ASSERT_EQ(rc, 0);
  const auto block = blocks(text);
  ASSERT_EQ(block.size(), 1u) << text;
  const auto& t = block.at("tonemap");
  const std::string* hdr = entry(t, "inputs:", "hdr");
  ASSERT_NE(hdr, nullptr) << text;
  EXPECT_EQ(columns(*hdr), (std::vector<std::string>{"hdr", "required", "sampled", "formats rgba16f, rgba32f, r11g11b10f"}));
  const std::string* output = entry(t, "outputs:", "output");
  ASSERT_NE(output, nullptr) << text;
  EXPECT_EQ(columns(*output)[3], "formats rgba8, srgb8_alpha8");
  const std::string* op = entry(t, "params:", "operator");
  ASSERT_NE(op, nullptr) << text;
  EXPECT_EQ(columns(*op), (std::vector<std::string>{"operator", "enum", "= \"aces\"", "one of \"reinhard\", \"aces\", \"none\""}));
  EXPECT_NE(std::find(t.begin(), t.end(), "    hdr and output must have the same size"), t.end()) << text;
}

TEST(CliPassesText, AnIntRangeIsPrintedInIntegers) {
  int rc = -1;
  const std::string text = run("passes clustered_deferred", &rc);
  ASSERT_EQ(rc, 0);
  const auto typeBlocks = blocks(text);  // entry() points into it: keep it alive
  const std::string* slices = entry(typeBlocks.at("clustered_deferred"), "params:", "slices");
  ASSERT_NE(slices, nullptr) << text;
  EXPECT_EQ(columns(*slices)[3], "1 to 256") << *slices;
}

TEST(CliPassesText, UnknownTypeIsOneLineWithASuggestionAndExit1) {
  int rc = -1;
  const std::string out = run("passes tonemapp", &rc, true);
  EXPECT_EQ(rc, 1);
  EXPECT_EQ(out,
            "error: unknown pass type 'tonemapp' (did you mean 'tonemap'?); `rgraph passes` lists every type, "
            "`rgraph passes --plugin NAME` a plugin's\n");
  const std::string far = run("passes no_such_type_at_all", &rc, true);
  EXPECT_EQ(rc, 1);
  EXPECT_EQ(far.rfind("error: unknown pass type 'no_such_type_at_all'; ", 0), 0u) << far;
}

TEST(CliPassesText, SeveralTypesInTheOrderGiven) {
  int rc = -1;
  const std::string text = run("passes tonemap blit", &rc);
  ASSERT_EQ(rc, 0);
  const size_t tonemap = text.find("tonemap  (built-in)"), blit = text.find("blit  (built-in)");
  ASSERT_NE(tonemap, std::string::npos);
  ASSERT_NE(blit, std::string::npos);
  EXPECT_LT(tonemap, blit);
  EXPECT_EQ(blocks(text).size(), 2u);
}

}  // namespace
