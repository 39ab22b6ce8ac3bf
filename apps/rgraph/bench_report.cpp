// `rgraph bench`, results: the CSV and JSON rows, the headline checks, and
// the tables of deterministic figures that docs/performance.md quotes (a
// test regenerates them and compares, so the docs cannot drift from the code).
#include <algorithm>
#include <cstdio>
#include <sstream>
#include <functional>

#include "bench.h"
#include "bench_shadows.h"
#include "rgraph/error.h"
#include "rgraph/output_file.h"

namespace rgraph::cli::bench {

using nlohmann::json;

namespace {

std::string csvEscape(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char c : s) o += c == '"' ? std::string("\"\"") : std::string(1, c);
  return o + "\"";
}

std::string fmtMs(double ms) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f ms", ms);
  return buf;
}

std::string joined(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
  return s;
}

}  // namespace

void writeCsv(const std::string& path, const std::vector<Point>& points, const std::vector<AaRow>& aa,
              const std::vector<ShadowRow>& shadows) {
  std::ostringstream f;
  f << "axes,method,layout,threshold,lights,width,height,frames,median_ms,min_"
       "ms,max_ms,psnr_db,max_abs_error,"
       "share_over_1,gbuffer_bytes_per_pixel,gbuffer_bytes_per_pixel_adapted,"
       "allocated_bytes,naive_bytes,status,scene,aa,edge_psnr_db,edge_pixels,psnr_exact_db,max_abs_error_exact,"
       "map_size,cascades,shadow_ms,atlas_bytes\n";
  char buf[64];
  auto n = [&](double v, const char* fmt = "%.4f") {
    std::snprintf(buf, sizeof buf, fmt, v);
    return std::string(buf);
  };
  for (const auto& p : points) {
    const auto& fr = p.m.frameMs;
    const double mn = fr.empty() ? 0 : *std::min_element(fr.begin(), fr.end());
    const double mx = fr.empty() ? 0 : *std::max_element(fr.begin(), fr.end());
    f << csvEscape(joined(p.axes, ";")) << "," << p.cfg.method << "," << (p.cfg.deferred() ? p.cfg.layout : "") << ","
      << n(p.cfg.threshold, "%.8f") << "," << p.cfg.lights << "," << p.cfg.size.width << "," << p.cfg.size.height << ","
      << fr.size() << "," << n(median(fr)) << "," << n(mn) << "," << n(mx) << "," << n(p.err.psnr, "%.3f") << ","
      << p.err.maxAbs << "," << n(p.err.over1, "%.6f") << "," << p.m.gbufferBytes << "," << p.m.gbufferBytesAdapted
      << "," << p.m.allocatedBytes << "," << p.m.naiveBytes << "," << csvEscape(p.ok() ? "ok" : "error: " + p.error)
      << "," << (p.cfg.pillars ? "pillars" : "") << ",,,," << (p.hasExact ? n(p.errExact.psnr, "%.3f") + "," + std::to_string(p.errExact.maxAbs) : ",") << ",,,,\n";
  }
  // aa rows: the pipeline file in the method column, the scene's point lights
  // unknown here (empty), no G-buffer figures.
  for (const auto& r : aa) {
    const auto& fr = r.frameMs;
    const double mn = fr.empty() ? 0 : *std::min_element(fr.begin(), fr.end());
    const double mx = fr.empty() ? 0 : *std::max_element(fr.begin(), fr.end());
    f << "aa," << csvEscape(r.pipeline) << ",,,," << r.size.width << "," << r.size.height << "," << fr.size() << ","
      << n(median(fr)) << "," << n(mn) << "," << n(mx) << "," << n(r.psnr, "%.3f") << "," << r.maxAbs << ",,,,,,"
      << csvEscape(r.ok() ? "ok" : "error: " + r.error) << "," << csvEscape(r.scene) << "," << r.aa << ","
      << n(r.edgePsnr, "%.3f") << "," << r.edgePixels << ",,,,,,\n";
  }
  // shadows rows: the filter in the method column (none: shadows off), the
  // scene file in the scene column, their own last four columns.
  for (const auto& r : shadows) {
    const auto& fr = r.frameMs;
    const double mn = fr.empty() ? 0 : *std::min_element(fr.begin(), fr.end());
    const double mx = fr.empty() ? 0 : *std::max_element(fr.begin(), fr.end());
    const std::string status = !r.skipped.empty() ? "skipped: " + r.skipped : r.ok() ? "ok" : "error: " + r.error;
    f << "shadows," << r.method << ",,,," << r.size.width << "," << r.size.height << "," << fr.size() << ","
      << n(median(fr)) << "," << n(mn) << "," << n(mx) << "," << n(r.err.psnr, "%.3f") << "," << r.err.maxAbs << ","
      << n(r.err.over1, "%.6f") << ",,," << r.allocatedBytes << ",," << csvEscape(status) << ",shadows.json,,,,,,"
      << r.mapSize << "," << r.cascades << "," << n(median(r.shadowMs)) << "," << r.atlasBytes << "\n";
  }
  writeOutputFile(path, f.str());
}

json pointJson(const Point& p) {
  const auto& fr = p.m.frameMs;
  json passes = json::array();
  for (const auto& name : p.m.passOrder) passes.push_back({{"name", name}, {"ms", median(p.m.passMs.at(name))}});
  json j = {{"axes", p.axes},
            {"method", p.cfg.method},
            {"layout", p.cfg.deferred() ? json(p.cfg.layout) : json(nullptr)},
            {"threshold", p.cfg.threshold},
            {"lights", p.cfg.lights},
            {"width", p.cfg.size.width},
            {"height", p.cfg.size.height},
            {"frames", fr.size()},
            {"frame_ms", fr},
            {"median_ms", median(fr)},
            {"min_ms", fr.empty() ? 0.0 : *std::min_element(fr.begin(), fr.end())},
            {"max_ms", fr.empty() ? 0.0 : *std::max_element(fr.begin(), fr.end())},
            {"passes", passes},
            {"psnr_db", p.err.psnr},
            {"max_abs_error", p.err.maxAbs},
            {"share_over_1", p.err.over1},
            {"gbuffer_bytes_per_pixel", p.m.gbufferBytes},
            {"gbuffer_bytes_per_pixel_adapted", p.m.gbufferBytesAdapted},
            {"allocated_bytes", p.m.allocatedBytes},
            {"naive_bytes", p.m.naiveBytes},
            {"gl_errors", p.m.glErrors}};
  if (p.cfg.pillars) j["scene_variant"] = "pillars";
  if (p.hasExact) j["psnr_exact_db"] = p.errExact.psnr, j["max_abs_error_exact"] = p.errExact.maxAbs;
  if (!p.ok()) j["error"] = p.error;
  return j;
}

Config defaultPointFromJson(const json& results) {
  const json& d = results.at("default_point");
  Config def;
  def.method = d.at("method");
  def.layout = d.at("layout");
  def.threshold = d.at("threshold");
  def.lights = d.at("lights");
  def.size = {d.at("width").get<uint32_t>(), d.at("height").get<uint32_t>()};
  return def;
}

Point pointFromJson(const json& pj, const Config& def) {
  Point p;
  p.cfg.method = pj.at("method");
  p.cfg.layout = pj.at("layout").is_null() ? def.layout : pj.at("layout").get<std::string>();
  p.cfg.threshold = pj.at("threshold");
  p.cfg.lights = pj.at("lights");
  p.cfg.size = {pj.at("width").get<uint32_t>(), pj.at("height").get<uint32_t>()};
  p.axes = pj.at("axes").get<std::vector<std::string>>();
  p.cfg.pillars = pj.value("scene_variant", std::string()) == "pillars";
  p.m.frameMs = pj.at("frame_ms").get<std::vector<double>>();
  p.m.gbufferBytes = pj.at("gbuffer_bytes_per_pixel");
  p.m.gbufferBytesAdapted = pj.value("gbuffer_bytes_per_pixel_adapted", 0u);
  p.m.allocatedBytes = pj.value("allocated_bytes", uint64_t{0});
  p.m.naiveBytes = pj.value("naive_bytes", uint64_t{0});
  p.err.psnr = pj.at("psnr_db");
  p.err.maxAbs = pj.at("max_abs_error");
  p.err.over1 = pj.at("share_over_1");
  if (pj.contains("psnr_exact_db")) {
    p.hasExact = true;
    p.errExact.psnr = pj.at("psnr_exact_db");
    p.errExact.maxAbs = pj.at("max_abs_error_exact");
  }
  if (pj.contains("error")) p.error = pj.at("error");
  return p;
}

json shippedJson(const ShippedResult& r) {
  json j = {{"name", r.method.name},         {"file", r.method.file},       {"fp32_position", r.method.fp32Position},
            {"max_abs_error", r.err.maxAbs}, {"share_over_2", r.err.over2}, {"psnr_db", r.err.psnr}};
  if (!r.error.empty()) j["error"] = r.error;
  return j;
}

ShippedResult shippedFromJson(const json& j) {
  // The names point into kShippedMethods (static strings) where they match.
  ShippedResult r{{"", ""}, {}, {}};
  const std::string name = j.at("name"), file = j.at("file");
  const bool fp32 = j.value("fp32_position", false);
  for (const auto& m : kShippedMethods)
    if (name == m.name && file == m.file && fp32 == m.fp32Position) r.method = m;
  if (!*r.method.name) throw RuntimeError("unknown shipped pipeline '" + name + "' (" + file + ")");
  r.err.maxAbs = j.at("max_abs_error");
  r.err.over2 = j.at("share_over_2");
  r.err.psnr = j.at("psnr_db");
  if (j.contains("error")) r.error = j.at("error");
  return r;
}

// ---------------------------------------------------------------- headline checks

namespace {

const Point* findPoint(const std::vector<Point>& points, const Config& c) {
  for (const auto& p : points)
    if (p.ok() && p.cfg.key() == c.key()) return &p;
  return nullptr;
}

bool onAxis(const Point& p, const char* axis) { return std::count(p.axes.begin(), p.axes.end(), axis) > 0; }

// At 1,024 lights: each method against the exact loop (threshold 0) at the
// same N, in time and in PSNR against its image; passes when a method at
// >= 35 dB runs >= 10x faster than the exact loop (issue 14's must-show).
void exactReferenceCheck(const std::vector<Point>& points, const Config& def, json& checks,
                         std::vector<std::string>& summary) {
  Config at = def;
  at.lights = 1024;
  const Point* exact = findPoint(points, exactConfig(at, def));
  if (!exact || exact->m.frameMs.empty()) return;
  const double exactMs = median(exact->m.frameMs);
  json methods = json::object();
  std::string line = "1,024 lights " + sizeText(at.size) + ": exact loop (no cut-off) " + fmtMs(exactMs) + ";";
  bool pass = false;
  for (const auto& m : kMethods) {
    Config c = at;
    c.method = m;
    const Point* p = findPoint(points, c);
    if (!p || !p->hasExact || p->m.frameMs.empty()) continue;
    const double ms = median(p->m.frameMs), speedup = exactMs / ms;
    methods[m] = {{"ms", ms}, {"psnr_exact_db", p->errExact.psnr}, {"speedup", speedup}};
    pass = pass || (p->errExact.psnr >= 35.0 && speedup >= 10.0);
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s %s %.1fx faster at %.1f dB", methods.size() > 1 ? "," : "", m.c_str(), speedup,
                  p->errExact.psnr);
    line += buf;
  }
  checks["exact_reference_1024"] = {{"lights", 1024}, {"exact_ms", exactMs}, {"methods", methods}, {"pass", pass}};
  summary.push_back(line + (pass ? " (>= 35 dB at >= 10x: yes)" : " (>= 35 dB at >= 10x: NO)"));
}

// Cost flat in lights at constant overlap: each culling method's median at
// 1,024 lights over its median at 64, same run (the target: <= 1.2).
void flatCostCheck(const std::vector<Point>& points, const Config& def, json& checks,
                   std::vector<std::string>& summary) {
  std::string line = "median at 1,024 / at 64 lights " + sizeText(def.size) + ":";
  json j = json::object();
  for (const char* m : {"light_volumes", "tiled", "clustered"}) {
    Config c = def;
    c.method = m;
    c.lights = 64;
    const Point* lo = findPoint(points, c);
    c.lights = 1024;
    const Point* hi = findPoint(points, c);
    if (!lo || !hi || lo->m.frameMs.empty() || hi->m.frameMs.empty()) continue;
    const double ratio = median(hi->m.frameMs) / median(lo->m.frameMs);
    j[m] = {
        {"ms_64", median(lo->m.frameMs)}, {"ms_1024", median(hi->m.frameMs)}, {"ratio", ratio}, {"pass", ratio <= 1.2}};
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s %s %.1f / %.1f ms = %.2fx%s", j.size() > 1 ? "," : "", m, median(hi->m.frameMs),
                  median(lo->m.frameMs), ratio, ratio <= 1.2 ? " (<= 1.2: yes)" : " (<= 1.2: NO)");
    line += buf;
  }
  if (j.empty()) return;
  checks["flat_cost_64_to_1024"] = j;
  summary.push_back(line);
}

// Tiles against clusters where depth is discontinuous: tiled's median over
// clustered's at each light count of the pillars axis, and the same on the
// field at those counts (the chart tiles_vs_clusters draws them).
void pillarsCheck(const std::vector<Point>& points, const Config& def, json& checks,
                  std::vector<std::string>& summary) {
  json rows = json::array();
  std::string line = "tiled / clustered median, " + sizeText(def.size) + ", pillars (field):";
  for (const auto& p : points) {
    if (!p.ok() || p.cfg.method != "tiled" || !onAxis(p, "pillars") || p.m.frameMs.empty()) continue;
    Config c = p.cfg;
    c.method = "clustered";
    const Point* clustered = findPoint(points, c);
    c.pillars = false;
    const Point* fieldClustered = findPoint(points, c);
    c.method = "tiled";
    const Point* fieldTiled = findPoint(points, c);
    if (!clustered || clustered->m.frameMs.empty()) continue;
    json r = {{"lights", p.cfg.lights},
              {"tiled_ms", median(p.m.frameMs)},
              {"clustered_ms", median(clustered->m.frameMs)},
              {"tiled_psnr_db", p.err.psnr},
              {"clustered_psnr_db", clustered->err.psnr},
              {"ratio", median(p.m.frameMs) / median(clustered->m.frameMs)}};
    char buf[96];
    std::snprintf(buf, sizeof buf, " %d: %.2fx", p.cfg.lights, r["ratio"].get<double>());
    line += buf;
    if (fieldTiled && fieldClustered && !fieldTiled->m.frameMs.empty() && !fieldClustered->m.frameMs.empty()) {
      r["field_tiled_ms"] = median(fieldTiled->m.frameMs);
      r["field_clustered_ms"] = median(fieldClustered->m.frameMs);
      r["field_ratio"] = median(fieldTiled->m.frameMs) / median(fieldClustered->m.frameMs);
      std::snprintf(buf, sizeof buf, " (%.2fx)", r["field_ratio"].get<double>());
      line += buf;
    }
    rows.push_back(r);
  }
  if (rows.empty()) return;
  checks["tiles_vs_clusters_pillars"] = rows;
  summary.push_back(line);
}

}  // namespace

json headlineChecks(const std::vector<Point>& points, const Config& def, std::vector<std::string>& summary) {
  json checks = json::object();
  exactReferenceCheck(points, def, checks, summary);
  flatCostCheck(points, def, checks, summary);
  pillarsCheck(points, def, checks, summary);
  char line[512];
  const bool timed = std::any_of(points.begin(), points.end(), [](const Point& p) { return !p.m.frameMs.empty(); });
  {
    // Light volumes or tiled against the fullscreen loop at 1,024 lights.
    Config c = def;
    c.lights = 1024;
    c.method = "fullscreen";
    const Point* full = findPoint(points, c);
    c.method = "light_volumes";
    const Point* vol = findPoint(points, c);
    c.method = "tiled";
    const Point* tiled = findPoint(points, c);
    if (timed && full && (vol || tiled)) {
      const Point* best = vol && (!tiled || median(vol->m.frameMs) <= median(tiled->m.frameMs)) ? vol : tiled;
      const double speedup = median(full->m.frameMs) / median(best->m.frameMs);
      json j = {{"lights", 1024},
                {"fullscreen_ms", median(full->m.frameMs)},
                {"fullscreen_psnr_db", full->err.psnr},
                {"best_method", best->cfg.method},
                {"best_ms", median(best->m.frameMs)},
                {"best_psnr_db", best->err.psnr},
                {"speedup", speedup},
                {"pass", speedup >= 5.0 && best->err.psnr >= full->err.psnr - 0.5}};
      if (vol) j["light_volumes_ms"] = median(vol->m.frameMs), j["light_volumes_psnr_db"] = vol->err.psnr;
      if (tiled) j["tiled_ms"] = median(tiled->m.frameMs), j["tiled_psnr_db"] = tiled->err.psnr;
      checks["culling_vs_fullscreen_1024"] = j;
      std::snprintf(line, sizeof line,
                    "1,024 lights %s: fullscreen loop %.1f ms (PSNR %.1f dB), light "
                    "volumes %.1f ms (%.1f dB), "
                    "tiled %.1f ms (%.1f dB): %s %.1fx faster",
                    sizeText(c.size).c_str(), median(full->m.frameMs), full->err.psnr,
                    vol ? median(vol->m.frameMs) : 0.0, vol ? vol->err.psnr : 0.0,
                    tiled ? median(tiled->m.frameMs) : 0.0, tiled ? tiled->err.psnr : 0.0, best->cfg.method.c_str(),
                    speedup);
      summary.push_back(line);
    }
  }
  {
    // Compact layout: bytes per pixel and error where the layout is the only difference.
    Config c = def;
    c.method = "fullscreen";
    c.threshold = 0.0;
    c.layout = "compact";
    const Point* compact = findPoint(points, c);
    c.layout = "pbr";
    const Point* pbr = findPoint(points, c);
    if (compact) {
      json j = {{"bytes_per_pixel", compact->m.gbufferBytes},
                {"bytes_per_pixel_adapted", compact->m.gbufferBytesAdapted},
                {"psnr_db", compact->err.psnr},
                {"max_abs_error", compact->err.maxAbs},
                {"pass", compact->m.gbufferBytes <= 16 && compact->err.psnr >= 50.0}};
      if (pbr) j["pbr_bytes_per_pixel"] = pbr->m.gbufferBytes, j["pbr_psnr_db"] = pbr->err.psnr;
      checks["compact_layout"] = j;
      std::snprintf(line, sizeof line,
                    "compact layout: %u bytes/pixel with depth (pbr %u), PSNR "
                    "%.1f dB, max error %d/255 "
                    "(fullscreen loop, no cut-off, %d lights)",
                    compact->m.gbufferBytes, pbr ? pbr->m.gbufferBytes : 0u, compact->err.psnr, compact->err.maxAbs,
                    c.lights);
      summary.push_back(line);
    }
  }
  {
    Config c = def;
    c.method = "forward_lit";
    const Point* fwd = findPoint(points, c);
    c.method = "light_volumes";
    const Point* vol = findPoint(points, c);
    if (timed && fwd && vol) {
      const double speedup = median(fwd->m.frameMs) / median(vol->m.frameMs);
      checks["light_volumes_vs_forward"] = {{"lights", def.lights},
                                            {"forward_ms", median(fwd->m.frameMs)},
                                            {"light_volumes_ms", median(vol->m.frameMs)},
                                            {"speedup", speedup}};
      std::snprintf(line, sizeof line,
                    "%d lights %s: forward_lit %.1f ms, light volumes %.1f ms: "
                    "%.1fx faster",
                    def.lights, sizeText(def.size).c_str(), median(fwd->m.frameMs), median(vol->m.frameMs), speedup);
      summary.push_back(line);
    }
  }
  return checks;
}

// ---------------------------------------------------------------- figure tables

namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}
std::string psnrText(double db) { return db >= kPsnrCap ? "100 dB (cap)" : fmt("%.1f dB", db); }
std::string errText(int e) { return std::to_string(e) + "/255"; }
std::string shareText(double s) { return fmt("%.3f%%", 100.0 * s); }
std::string mbText(uint64_t bytes) { return fmt("%.1f", double(bytes) / (1024.0 * 1024.0)); }
std::string layoutText(const Config& c) { return c.deferred() ? c.layout : std::string("-"); }
std::string countText(int n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(static_cast<size_t>(i), ",");
  return s;
}

std::string row(const std::vector<std::string>& cells) {
  std::string s = "|";
  for (const auto& c : cells) s += " " + c + " |";
  return s + "\n";
}

// Light count (the counts of points on `axis`) x method at the default
// layout, cut-off and size; `cell` gives a point's cell ("-" where none).
std::string lightsGrid(const std::vector<Point>& points, const Config& def, const char* axis,
                       const std::function<std::string(const Point*)>& cell) {
  std::vector<int> counts;
  for (const auto& p : points)
    if (onAxis(p, axis) && !std::count(counts.begin(), counts.end(), p.cfg.lights)) counts.push_back(p.cfg.lights);
  std::sort(counts.begin(), counts.end());
  std::vector<std::string> head = {"lights"}, rule = {"---:"};
  for (const auto& m : kMethods) head.push_back(methodTitle(m)), rule.push_back("---:");
  std::string t = row(head) + row(rule);
  for (int n : counts) {
    std::vector<std::string> cells = {countText(n)};
    for (const auto& m : kMethods) {
      Config c = def;
      c.method = m;
      c.lights = n;
      cells.push_back(cell(findPoint(points, c)));
    }
    t += row(cells);
  }
  return t;
}

// Against the reference (forward_lit, no cut-off).
std::string lightsTable(const std::vector<Point>& points, const Config& def) {
  return lightsGrid(points, def, "lights", [](const Point* p) {
    return p ? psnrText(p->err.psnr) + ", " + errText(p->err.maxAbs) : std::string("-");
  });
}

// Against the exact loop at the same N (lights_exact) instead of forward_lit.
std::string lightsExactTable(const std::vector<Point>& points, const Config& def) {
  return lightsGrid(points, def, "lights_exact", [](const Point* p) {
    return p && p->hasExact ? psnrText(p->errExact.psnr) + ", " + errText(p->errExact.maxAbs) : std::string("-");
  });
}

// One row per layout: bytes, and the error with and without the cut-off.
std::string layoutsTable(const std::vector<Point>& points, const Config& def) {
  std::string t =
      row({"layout", "bytes/pixel (with depth)", "after adapting to the scene", "PSNR, no cut-off",
           "max error, no cut-off", "PSNR, " + methodTitle(def.method) + " at " + thresholdText(def.threshold),
           "texture MB allocated / naive"}) +
      row({"---", "---:", "---:", "---:", "---:", "---:", "---:"});
  for (const auto& layout : kLayouts) {
    Config exact = def;
    exact.layout = layout;
    exact.method = "fullscreen";
    exact.threshold = 0.0;
    Config cut = def;
    cut.layout = layout;
    const Point* e = findPoint(points, exact);
    const Point* c = findPoint(points, cut);
    if (!e && !c) continue;
    const Point* any = e ? e : c;
    t += row({layout, std::to_string(any->m.gbufferBytes), std::to_string(any->m.gbufferBytesAdapted),
              e ? psnrText(e->err.psnr) : "-", e ? errText(e->err.maxAbs) : "-", c ? psnrText(c->err.psnr) : "-",
              c ? mbText(c->m.allocatedBytes) + " / " + mbText(c->m.naiveBytes) : "-"});
  }
  return t;
}

// Cut-off x culling method at the default layout, light count and size.
std::string thresholdsTable(const std::vector<Point>& points, const Config& def) {
  std::vector<double> cuts;
  std::vector<std::string> methods;
  for (const auto& p : points) {
    if (!onAxis(p, "threshold")) continue;
    if (!std::count(cuts.begin(), cuts.end(), p.cfg.threshold)) cuts.push_back(p.cfg.threshold);
    if (!std::count(methods.begin(), methods.end(), p.cfg.method)) methods.push_back(p.cfg.method);
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<std::string> head = {"cut-off"}, rule = {"---"};
  for (const auto& m : methods) head.push_back(methodTitle(m)), rule.push_back("---:");
  std::string t = row(head) + row(rule);
  for (double cut : cuts) {
    std::vector<std::string> cells = {thresholdText(cut)};
    for (const auto& m : methods) {
      Config c = def;
      c.method = m;
      c.threshold = cut;
      const Point* p = findPoint(points, c);
      cells.push_back(p ? psnrText(p->err.psnr) + ", " + errText(p->err.maxAbs) : "-");
    }
    t += row(cells);
  }
  return t;
}

// Every point: the full record of deterministic figures.
std::string pointsTable(const std::vector<Point>& points) {
  std::string t = row({"method", "layout", "cut-off", "lights", "size", "PSNR", "max error", "pixels off > 1/255",
                       "bytes/pixel", "adapted", "allocated / naive bytes"}) +
                  row({"---", "---", "---", "---:", "---", "---:", "---:", "---:", "---:", "---:", "---:"});
  std::vector<const Point*> sorted;
  for (const auto& p : points) sorted.push_back(&p);
  std::stable_sort(sorted.begin(), sorted.end(), [](const Point* a, const Point* b) {
    if (a->cfg.size.width != b->cfg.size.width) return a->cfg.size.width < b->cfg.size.width;
    if (a->cfg.lights != b->cfg.lights) return a->cfg.lights < b->cfg.lights;
    return a->cfg.key() < b->cfg.key();
  });
  for (const Point* p : sorted) {
    if (!p->ok()) {
      t += row({p->cfg.method, layoutText(p->cfg), thresholdText(p->cfg.threshold),
                countText(p->cfg.lights) + (p->cfg.pillars ? " pillars" : ""), sizeText(p->cfg.size), "failed", "", "",
                "", "", ""});
      continue;
    }
    const double ratio = p->m.naiveBytes ? double(p->m.allocatedBytes) / double(p->m.naiveBytes) : 0.0;
    t += row({p->cfg.method, layoutText(p->cfg), thresholdText(p->cfg.threshold),
              countText(p->cfg.lights) + (p->cfg.pillars ? " pillars" : ""), sizeText(p->cfg.size), psnrText(p->err.psnr), errText(p->err.maxAbs), shareText(p->err.over1),
              std::to_string(p->m.gbufferBytes), std::to_string(p->m.gbufferBytesAdapted), fmt("%.2f", ratio)});
  }
  return t;
}

// The aa axis: two decimals, the methods differ by tenths of a dB on some scenes.
std::string aaTable(const std::vector<AaRow>& rows) {
  auto db = [](double v) { return v >= kPsnrCap ? std::string("100 dB (cap)") : fmt("%.2f dB", v); };
  std::string t = row({"scene", "aa", "pipeline", "size", "frames", "PSNR", "edge PSNR", "edge pixels"}) +
                  row({"---", "---", "---", "---", "---:", "---:", "---:", "---:"});
  for (const auto& r : rows) {
    if (!r.ok()) {
      t += row({r.scene, r.aa, r.pipeline, sizeText(r.size), "", "failed", "", ""});
      continue;
    }
    t += row({r.scene, r.aa, r.pipeline, sizeText(r.size), std::to_string(r.frames), db(r.psnr), db(r.edgePsnr),
              std::to_string(r.edgePixels)});
  }
  return t;
}

// The shipped pipelines against forward.json.
std::string shippedTable(const std::vector<ShippedResult>& shipped) {
  std::string t =
      row({"against forward.json", "max diff", "pixels > 2/255", "PSNR"}) + row({"---", "---:", "---:", "---:"});
  for (const auto& r : shipped) {
    if (!r.error.empty()) {
      t += row({r.method.name, "failed", "", ""});
      continue;
    }
    t += row({r.method.name, errText(r.err.maxAbs), shareText(r.err.over2), psnrText(r.err.psnr)});
  }
  return t;
}

}  // namespace

std::map<std::string, std::string> figureTables(const std::vector<Point>& points, const Config& def,
                                                const std::vector<ShippedResult>& shipped,
                                                const std::vector<AaRow>& aa) {
  std::map<std::string, std::string> tables;
  if (!points.empty())
    tables = {{"lights", lightsTable(points, def)},
              {"layouts", layoutsTable(points, def)},
              {"lights_exact", lightsExactTable(points, def)},
              {"thresholds", thresholdsTable(points, def)},
              {"points", pointsTable(points)}};
  if (!shipped.empty()) tables["shipped"] = shippedTable(shipped);
  if (!aa.empty()) tables["aa"] = aaTable(aa);
  return tables;
}

}  // namespace rgraph::cli::bench
