// `rgraph bench --smoke --only shadows`: the shadows axis end to end on its
// tiny plan (shadows off, hard at 512 and 2048, pcf 3x3 at 2048; 160x90, one
// frame each) against the exact-visibility image, its CSV columns, JSON,
// figure table and chart. No timing is asserted beyond being measured.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/run_command.h"

namespace {
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

size_t cells(const std::string& line) {  // shadows rows quote no commas
  size_t n = 1;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    if (c == ',' && !quoted) ++n;
  }
  return n;
}

}  // namespace

TEST(BenchShadows, SmokeRowsAgainstExactVisibility) {
  const fs::path dir = fs::temp_directory_path() / ("rgraph-bench-shadows-" + std::to_string(getpid()));
  fs::remove_all(dir);
  const auto r = rgraph::testsupport::runCommand(std::string(RGRAPH_CLI) + " bench --smoke --only shadows --out " +
                                                 dir.string() + " 2>&1");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(slurp(dir / "results.json"));
  EXPECT_TRUE(j.at("points").empty());

  // The reference: the ray caster's visibility for every casting light of
  // scenes/shadows.json (a sun, two spots, three shadowed point lights), and
  // the same sum with every visibility 1 is the pipeline with shadows off (up
  // to the rgba16f target's rounding).
  const nlohmann::json& ref = j.at("shadow_reference");
  EXPECT_NE(ref.at("how").get<std::string>().find("ray caster"), std::string::npos) << ref.dump();
  EXPECT_EQ(ref.at("casting_lights").size(), 6u) << ref.dump();
  EXPECT_EQ(ref.at("shadow_rays").get<size_t>(), 6 * ref.at("probed_pixels").get<size_t>());
  EXPECT_GT(ref.at("probed_pixels").get<size_t>(), 160u * 90u / 2);
  EXPECT_GT(ref.at("shadowed_share").get<double>(), 0.05) << "the scene has shadows to find";
  EXPECT_GE(ref.at("linearity_max_abs_hdr").get<double>(), 0.0);
  EXPECT_LT(ref.at("linearity_max_abs_hdr").get<double>(), 0.01);

  std::map<std::string, nlohmann::json> rows;  // label -> row
  for (const auto& row : j.at("shadows")) {
    EXPECT_FALSE(row.contains("error")) << row.dump();
    EXPECT_FALSE(row.contains("skipped")) << row.dump();
    EXPECT_EQ(row.at("width"), 160);
    EXPECT_EQ(row.at("frame_ms").size(), 1u);
    EXPECT_GT(row.at("median_ms").get<double>(), 0.0);
    rows[row.at("label")] = row;
  }
  ASSERT_EQ(rows.size(), 4u) << j.at("shadows").dump();
  for (const char* label : {"none", "hard 512 c4", "hard 2048 c4", "pcf3 2048 c4"})
    ASSERT_TRUE(rows.count(label)) << label;
  const double none = rows["none"].at("psnr_db"), hard512 = rows["hard 512 c4"].at("psnr_db"),
               hard2048 = rows["hard 2048 c4"].at("psnr_db"), pcf = rows["pcf3 2048 c4"].at("psnr_db");
  // No method is its own reference (that would read 100 dB, the cap), every
  // method is closer to exact visibility than no shadows at all, and a finer
  // map errs less.
  for (double db : {hard512, hard2048, pcf}) {
    EXPECT_LT(db, 60.0);
    EXPECT_GT(db, none + 3.0);
  }
  EXPECT_GT(hard2048, hard512 + 0.5);
  EXPECT_GT(rows["hard 2048 c4"].at("share_over_1").get<double>(), 0.0);
  // The atlas: 4 sun cascades, 2 spot maps, 3 x 6 cube faces, depth32f.
  EXPECT_EQ(rows["none"].at("atlas_bytes"), 0);
  EXPECT_EQ(rows["hard 2048 c4"].at("atlas_layers"), 24);
  EXPECT_EQ(rows["hard 2048 c4"].at("atlas_bytes").get<uint64_t>(), 24ull * 2048 * 2048 * 4);
  EXPECT_EQ(rows["hard 512 c4"].at("atlas_bytes").get<uint64_t>(), 24ull * 512 * 512 * 4);
  EXPECT_GT(rows["hard 2048 c4"].at("shadow_median_ms").get<double>(), 0.0);
  EXPECT_EQ(j.at("checks").at("shadows").at("hard_512_vs_2048").at("pass"), true);

  // CSV: the four rows, as many cells as the header, ok.
  std::istringstream csv(slurp(dir / "results.csv"));
  std::string header, line;
  std::getline(csv, header);
  EXPECT_NE(header.find("map_size,cascades,shadow_ms,atlas_bytes"), std::string::npos) << header;
  int shadowRows = 0;
  while (std::getline(csv, line))
    if (line.rfind("shadows,", 0) == 0) {
      ++shadowRows;
      EXPECT_EQ(cells(line), cells(header)) << line;
      EXPECT_NE(line.find(",ok,shadows.json,"), std::string::npos) << line;
    }
  EXPECT_EQ(shadowRows, 4);

  // The figure table and the chart.
  const std::string figures = slurp(dir / "figures.md");
  EXPECT_NE(figures.find("<!-- bench-figures:shadows -->"), std::string::npos) << figures;
  EXPECT_NE(figures.find("| hard | 512 | 4 | 160x90 |"), std::string::npos) << figures;
  for (const char* ext : {".svg", ".png"})
    EXPECT_GT(fs::file_size(dir / (std::string("shadows_ms_vs_error") + ext)), 1000u) << ext;
  fs::remove_all(dir);
}
