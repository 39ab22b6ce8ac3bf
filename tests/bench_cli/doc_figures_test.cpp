// The figures docs/performance.md quotes are the code's: `rgraph bench --quick
// --figures-only` (every point rendered once, untimed: errors and bytes are
// deterministic on one renderer) must reproduce the committed run
// (docs/images/bench/results.json, whose charts the page shows), and every
// `<!-- bench-figures:NAME -->` block of the page must equal the table of the
// same name bench writes into figures.md. On a mismatch the expected block is
// printed; scripts/update-bench-figures.py regenerates the run and the blocks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <unistd.h>

#include "support/run_command.h"

namespace {
namespace fs = std::filesystem;
using nlohmann::json;

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

int runCli(const std::string& args, std::string& out) {
  const rgraph::testsupport::CommandResult r =
      rgraph::testsupport::runCommand(std::string(RGRAPH_CLI) + " " + args + " 2>&1");
  out += r.out;
  return r.exitCode;
}

// name -> block text between <!-- bench-figures:NAME --> and <!-- /bench-figures:NAME -->.
std::map<std::string, std::string> blocks(const std::string& text) {
  std::map<std::string, std::string> out;
  const std::string open = "<!-- bench-figures:", close = "<!-- /bench-figures:";
  for (size_t at = text.find(open); at != std::string::npos; at = text.find(open, at + 1)) {
    const size_t nameEnd = text.find(" -->", at);
    if (nameEnd == std::string::npos) break;
    const std::string name = text.substr(at + open.size(), nameEnd - at - open.size());
    const size_t body = text.find('\n', nameEnd) + 1;
    const size_t end = text.find(close + name + " -->", body);
    out[name] = end == std::string::npos ? std::string("<unterminated>") : text.substr(body, end - body);
  }
  return out;
}

std::string pointKey(const json& p) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "%s|%s|%.8f|%d|%dx%d|%s", p.at("method").get<std::string>().c_str(),
                p.at("layout").is_null() ? "-" : p.at("layout").get<std::string>().c_str(),
                p.at("threshold").get<double>(), p.at("lights").get<int>(), p.at("width").get<int>(),
                p.at("height").get<int>(), p.value("scene_variant", std::string()).c_str());
  return buf;
}

// One bench run for both checks (ctest runs each test in its own process).
struct FreshRun {
  fs::path dir;
  std::string out;
  int exit = -1;
  FreshRun() {
    dir = fs::temp_directory_path() / ("rgraph-doc-figures-" + std::to_string(getpid()));
    fs::remove_all(dir);
    exit = runCli("bench --quick --figures-only --out " + dir.string(), out);
  }
  ~FreshRun() { fs::remove_all(dir); }
};

const fs::path kSource = RGRAPH_SOURCE_DIR;

// The committed run and a fresh untimed one agree point by point: PSNR to
// 0.005 dB (it prints to 0.001; renders are deterministic, the margin only
// absorbs the summation order of the squared errors), maximum error and bytes
// exactly, the share of pixels off to a millionth.
void expectCommittedRunMatches(const FreshRun& run) {
  const json fresh = json::parse(slurp(run.dir / "results.json"));
  const json committed = json::parse(slurp(kSource / "docs/images/bench/results.json"));
  std::map<std::string, json> byKey;
  for (const json& p : fresh.at("points")) byKey[pointKey(p)] = p;
  ASSERT_EQ(committed.at("points").size(), byKey.size()) << "the sweep changed: regenerate the committed run";
  for (const json& c : committed.at("points")) {
    const std::string key = pointKey(c);
    SCOPED_TRACE(key);
    ASSERT_TRUE(byKey.count(key)) << "point no longer swept";
    const json& f = byKey.at(key);
    EXPECT_NEAR(c.at("psnr_db").get<double>(), f.at("psnr_db").get<double>(), 0.005);
    EXPECT_NEAR(c.at("share_over_1").get<double>(), f.at("share_over_1").get<double>(), 1e-6);
    for (const char* exact : {"max_abs_error", "gbuffer_bytes_per_pixel", "gbuffer_bytes_per_pixel_adapted",
                              "allocated_bytes", "naive_bytes"})
      EXPECT_EQ(c.at(exact), f.at(exact)) << exact;
  }
}

// The aa axis's rows (the still methods, TAA after a fixed number of frames,
// the orbit's mean): the same figures, in the same order.
void expectCommittedAaMatches(const FreshRun& run) {
  const json fresh = json::parse(slurp(run.dir / "results.json")).at("aa");
  const json committed = json::parse(slurp(kSource / "docs/images/bench/results.json")).value("aa", json::array());
  ASSERT_EQ(committed.size(), fresh.size()) << "the aa axis changed: regenerate the committed run";
  for (size_t i = 0; i < fresh.size(); ++i) {
    SCOPED_TRACE(fresh[i].at("scene").get<std::string>() + " " + fresh[i].at("aa").get<std::string>());
    EXPECT_EQ(committed[i].at("scene"), fresh[i].at("scene"));
    EXPECT_EQ(committed[i].at("aa"), fresh[i].at("aa"));
    EXPECT_FALSE(fresh[i].contains("error")) << fresh[i].dump();
    EXPECT_NEAR(committed[i].at("psnr_db").get<double>(), fresh[i].at("psnr_db").get<double>(), 0.005);
    EXPECT_NEAR(committed[i].at("edge_psnr_db").get<double>(), fresh[i].at("edge_psnr_db").get<double>(), 0.005);
    EXPECT_EQ(committed[i].at("edge_pixels"), fresh[i].at("edge_pixels"));
    EXPECT_EQ(committed[i].at("frames"), fresh[i].at("frames"));
  }
}

// Every figures block the page quotes is what bench generates now, and the
// page quotes every table bench generates.
// The shipped pipelines against forward.json, in the same order.
void expectCommittedShippedMatches(const FreshRun& run) {
  const json fresh = json::parse(slurp(run.dir / "results.json")).at("shipped");
  const json committed = json::parse(slurp(kSource / "docs/images/bench/results.json")).at("shipped");
  ASSERT_EQ(committed.size(), fresh.size());
  for (size_t i = 0; i < fresh.size(); ++i) {
    SCOPED_TRACE(fresh[i].at("name").get<std::string>());
    EXPECT_EQ(committed[i].at("file"), fresh[i].at("file"));
    EXPECT_EQ(committed[i].at("max_abs_error"), fresh[i].at("max_abs_error"));
    EXPECT_NEAR(committed[i].at("psnr_db").get<double>(), fresh[i].at("psnr_db").get<double>(), 0.005);
    EXPECT_NEAR(committed[i].at("share_over_2").get<double>(), fresh[i].at("share_over_2").get<double>(), 1e-6);
  }
}

void expectPageQuotesTheTables(const FreshRun& run) {
  const auto generated = blocks(slurp(run.dir / "figures.md"));
  const auto page = blocks(slurp(kSource / "docs/performance.md"));
  ASSERT_GE(generated.size(), 4u) << slurp(run.dir / "figures.md");
  for (const auto& [name, table] : generated) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(page.count(name)) << "docs/performance.md lacks the block <!-- bench-figures:" << name << " -->";
    EXPECT_EQ(page.at(name), table) << "docs/performance.md's block '" << name << "' is stale; expected:\n" << table;
  }
  for (const auto& [name, table] : page) EXPECT_TRUE(generated.count(name)) << "bench no longer generates " << name;
}

TEST(DocFigures, CommittedRunAndPerformancePageMatchTheCode) {
  const FreshRun run;
  ASSERT_EQ(run.exit, 0) << run.out;
  {
    SCOPED_TRACE("docs/images/bench/results.json against a fresh run");
    expectCommittedRunMatches(run);
    expectCommittedShippedMatches(run);
    expectCommittedAaMatches(run);
  }
  {
    SCOPED_TRACE("docs/performance.md's generated tables against a fresh run");
    expectPageQuotesTheTables(run);
  }
}

}  // namespace
