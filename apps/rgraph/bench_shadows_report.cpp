// `rgraph bench`, the shadows axis written out: results.json rows, the
// checks and summary lines, the figure table "shadows" and the chart
// shadows_ms_vs_error (bench_shadows.h says what the figures are).
#include <algorithm>
#include <cstdio>

#include "bench_chart.h"
#include "bench_shadows.h"

namespace rgraph::cli::bench {

using nlohmann::json;

namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string mib(uint64_t bytes) { return fmt("%.1f MiB", double(bytes) / (1024.0 * 1024.0)); }

const ShadowRow* findRow(const std::vector<ShadowRow>& rows, const std::string& method, int size, int cascades) {
  for (const auto& r : rows)
    if (r.measured() && r.method == method && (method == "none" || (r.mapSize == size && r.cascades == cascades)))
      return &r;
  return nullptr;
}

// The measured row with shadows (method != none) of the highest PSNR, and the
// cheapest row within 1 dB of it at <= half its frame time (nullptr: none).
struct Pick {
  const ShadowRow *best = nullptr, *cheapest = nullptr;
};
Pick pick(const std::vector<ShadowRow>& rows) {
  Pick p;
  for (const auto& r : rows)
    if (r.measured() && r.method != "none" && (!p.best || r.err.psnr > p.best->err.psnr)) p.best = &r;
  if (!p.best) return p;
  const double bestMs = median(p.best->frameMs);
  for (const auto& r : rows)
    if (r.measured() && r.method != "none" && r.err.psnr >= p.best->err.psnr - 1.0 &&
        median(r.frameMs) <= 0.5 * bestMs && (!p.cheapest || median(r.frameMs) < median(p.cheapest->frameMs)))
      p.cheapest = &r;
  return p;
}

}  // namespace

json shadowJson(const ShadowRow& r) {
  json j = {{"axes", {"shadows"}},
            {"shadow_axes", r.axes},
            {"method", r.method},
            {"label", r.label()},
            {"map_size", r.mapSize},
            {"cascades", r.cascades},
            {"width", r.size.width},
            {"height", r.size.height},
            {"frame_ms", r.frameMs},
            {"median_ms", median(r.frameMs)},
            {"shadow_ms", r.shadowMs},
            {"shadow_median_ms", median(r.shadowMs)},
            {"psnr_db", r.err.psnr},
            {"max_abs_error", r.err.maxAbs},
            {"share_over_1", r.err.over1},
            {"atlas_bytes", r.atlasBytes},
            {"atlas_layers", r.atlasLayers},
            {"allocated_bytes", r.allocatedBytes}};
  if (!r.skipped.empty()) j["skipped"] = r.skipped;
  if (!r.ok()) j["error"] = r.error;
  return j;
}

ShadowRow shadowFromJson(const json& j) {
  ShadowRow r;
  r.axes = j.at("shadow_axes").get<std::vector<std::string>>();
  r.method = j.at("method");
  r.mapSize = j.at("map_size");
  r.cascades = j.at("cascades");
  r.size = {j.at("width").get<uint32_t>(), j.at("height").get<uint32_t>()};
  r.frameMs = j.at("frame_ms").get<std::vector<double>>();
  r.shadowMs = j.at("shadow_ms").get<std::vector<double>>();
  r.err.psnr = j.at("psnr_db");
  r.err.maxAbs = j.at("max_abs_error");
  r.err.over1 = j.at("share_over_1");
  r.atlasBytes = j.at("atlas_bytes");
  r.atlasLayers = j.at("atlas_layers");
  r.allocatedBytes = j.at("allocated_bytes");
  r.skipped = j.value("skipped", std::string());
  r.error = j.value("error", std::string());
  return r;
}

json shadowReferenceJson(const ShadowReference& r) {
  return {{"how", r.how},
          {"casting_lights", r.lights},
          {"probed_pixels", r.pixels},
          {"shadow_rays", r.shadowRays},
          {"oracle_seconds", r.oracleSeconds},
          {"shadowed_share", r.shadowedShare},
          {"linearity_max_abs_hdr", r.linearityMaxAbs}};
}

void shadowChecks(const std::vector<ShadowRow>& rows, json& checks, std::vector<std::string>& summary) {
  const ShadowRow* none = findRow(rows, "none", 0, 0);
  const ShadowRow* shipped = findRow(rows, "pcf3", 2048, 4);  // deferred-pbr-shadows.json as shipped
  const Pick p = pick(rows);
  if (!p.best) return;
  json j = {{"best", p.best->label()},
            {"best_psnr_db", p.best->err.psnr},
            {"best_ms", median(p.best->frameMs)},
            {"cheapest_within_1db_at_half_time", p.cheapest ? json(p.cheapest->label()) : json(nullptr)}};
  char buf[512];
  std::snprintf(buf, sizeof buf, "shadows: best %s %.2f dB at %.1f ms; cheapest within 1 dB at <= half its time: %s",
                p.best->label().c_str(), p.best->err.psnr, median(p.best->frameMs),
                p.cheapest ? (p.cheapest->label() + fmt(" (%.2f dB", p.cheapest->err.psnr) +
                              fmt(", %.1f ms)", median(p.cheapest->frameMs)))
                                 .c_str()
                           : "none");
  summary.push_back(buf);
  if (p.cheapest) j["cheapest_psnr_db"] = p.cheapest->err.psnr, j["cheapest_ms"] = median(p.cheapest->frameMs);
  if (none && shipped) {
    const double cost = median(shipped->frameMs) - median(none->frameMs);
    j["cost"] = {{"none_ms", median(none->frameMs)},           {"shipped", shipped->label()},
                 {"shipped_ms", median(shipped->frameMs)},     {"shipped_shadow_map_ms", median(shipped->shadowMs)},
                 {"shipped_atlas_bytes", shipped->atlasBytes}, {"none_psnr_db", none->err.psnr},
                 {"shipped_psnr_db", shipped->err.psnr}};
    std::snprintf(buf, sizeof buf,
                  "shadows cost: %s %.1f ms (shadow maps %.1f ms) vs none %.1f ms (+%.1f ms, %.2fx); atlas %s; PSNR "
                  "%.2f vs %.2f dB without shadows",
                  shipped->label().c_str(), median(shipped->frameMs), median(shipped->shadowMs), median(none->frameMs),
                  cost, median(shipped->frameMs) / median(none->frameMs), mib(shipped->atlasBytes).c_str(),
                  shipped->err.psnr, none->err.psnr);
    summary.push_back(buf);
  }
  // Finer maps err less: hard at 512 against 2048 (the sanity of the reference).
  if (const ShadowRow* lo = findRow(rows, "hard", 512, 4), *hi = findRow(rows, "hard", 2048, 4); lo && hi) {
    j["hard_512_vs_2048"] = {
        {"psnr_512_db", lo->err.psnr}, {"psnr_2048_db", hi->err.psnr}, {"pass", hi->err.psnr > lo->err.psnr}};
  }
  checks["shadows"] = j;
}

std::string shadowTable(const std::vector<ShadowRow>& rows) {
  auto row = [](std::initializer_list<std::string> cells) {
    std::string s = "|";
    for (const auto& c : cells) s += " " + c + " |";
    return s + "\n";
  };
  std::string t = row({"method", "map", "cascades", "size", "PSNR", "pixels > 1/255", "atlas", "layers"}) +
                  row({"---", "---:", "---:", "---", "---:", "---:", "---:", "---:"});
  for (const auto& r : rows) {
    const bool none = r.method == "none";
    const std::string map = none ? "-" : std::to_string(r.mapSize), cascades = none ? "-" : std::to_string(r.cascades);
    if (!r.skipped.empty()) {
      t += row({r.method, map, cascades, sizeText(r.size), "skipped", "", "", ""});
      continue;
    }
    if (!r.ok()) {
      t += row({r.method, map, cascades, sizeText(r.size), "failed", "", "", ""});
      continue;
    }
    t += row({r.method, map, cascades, sizeText(r.size),
              r.err.psnr >= kPsnrCap ? "100 dB (cap)" : fmt("%.2f dB", r.err.psnr), fmt("%.2f%%", 100.0 * r.err.over1),
              none ? "-" : mib(r.atlasBytes), none ? "-" : std::to_string(r.atlasLayers)});
  }
  return t;
}

void drawShadowChart(const std::string& dir, const std::vector<ShadowRow>& rows, const std::string& machine) {
  using namespace chart;
  Chart c;
  c.title = "Shadows: frame time against error";
  c.notes = {machine,
             "error: PSNR of the lit image against exact visibility (ray caster); labels: map size, c = sun cascades; "
             "right is better"};
  c.xLabel = "PSNR dB against the exact-visibility image";
  c.yLabel = "frame ms (median)";
  for (const auto& r : rows) {
    if (!r.measured()) continue;
    Series& s = c.seriesNamed(r.method == "none" ? "no shadows" : r.method);
    s.points.push_back({r.err.psnr, median(r.frameMs),
                        r.method == "none" ? "" : std::to_string(r.mapSize) + " c" + std::to_string(r.cascades)});
  }
  if (!c.series.empty()) writeChart(c, dir, "shadows_ms_vs_error");
}

}  // namespace rgraph::cli::bench
