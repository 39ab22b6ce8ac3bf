// `rgraph bench`, the charts: frame time against light count, frame time
// against error (with the Pareto front), G-buffer bytes against error, and
// tiles against clusters on the pillars scene.
#include <algorithm>

#include "bench.h"
#include "bench_chart.h"

namespace rgraph::cli::bench {

void drawCharts(const std::string& dir, const std::vector<Point>& points, const Config& def, const std::string& machine,
                const std::string& sceneText) {
  using namespace chart;
  // 1. frame ms against light count, one line per method (the grid).
  {
    Chart c;
    c.title = "Frame time against light count (" + sizeText(def.size) + ", " + def.layout + " G-buffer, cut-off " +
              thresholdText(def.threshold) + ")";
    c.notes = {machine, sceneText};
    c.xLabel = "point lights";
    c.yLabel = "frame ms (median)";
    c.logX = c.logY = true;
    for (size_t mi = 0; mi < kMethods.size(); ++mi) {
      Series s;
      s.name = methodTitle(kMethods[mi]);
      s.color = static_cast<int>(mi);
      std::vector<const Point*> ps;
      for (const auto& p : points)
        if (p.ok() && p.cfg.method == kMethods[mi] && std::count(p.axes.begin(), p.axes.end(), "lights"))
          ps.push_back(&p);
      std::sort(ps.begin(), ps.end(), [](const Point* a, const Point* b) { return a->cfg.lights < b->cfg.lights; });
      for (const Point* p : ps) s.points.push_back({double(p->cfg.lights), median(p->m.frameMs), ""});
      if (!s.points.empty()) c.series.push_back(std::move(s));
    }
    // The exact loop (fullscreen, no cut-off) at each N: what the cut-off saves.
    Series exact;
    exact.name = "exact loop (no cut-off)";
    exact.color = 6;
    exact.dashed = true;
    for (const auto& p : points)
      if (p.ok() && std::count(p.axes.begin(), p.axes.end(), "lights_exact"))
        exact.points.push_back({double(p.cfg.lights), median(p.m.frameMs), ""});
    std::sort(exact.points.begin(), exact.points.end(),
              [](const chart::Point& a, const chart::Point& b) { return a.x < b.x; });
    if (!exact.points.empty()) c.series.push_back(std::move(exact));
    writeChart(c, dir, "frame_ms_vs_lights");
  }
  // 2. frame ms against error at the default scene and resolution, Pareto front marked.
  {
    Chart c;
    c.title = "Frame time against error (" + std::to_string(def.lights) + " lights, " + sizeText(def.size) + ")";
    c.notes = {machine,
               "error: PSNR against forward_lit with no cut-off (fp32 "
               "HDR); down and right is better; " +
                   std::string("PSNR capped at 100 dB")};
    c.xLabel = "PSNR dB (higher: closer to the reference)";
    c.yLabel = "frame ms (median)";
    c.logY = true;
    std::vector<chart::Point> all;
    std::vector<const Point*> src;
    for (size_t mi = 0; mi < kMethods.size(); ++mi) {
      Series s;
      s.name = methodTitle(kMethods[mi]);
      s.color = static_cast<int>(mi);
      s.line = false;
      for (const auto& p : points) {
        if (!p.ok() || p.cfg.method != kMethods[mi] || p.cfg.lights != def.lights || p.cfg.size != def.size ||
            p.cfg.pillars)
          continue;
        s.points.push_back({p.err.psnr, median(p.m.frameMs), ""});
        all.push_back(s.points.back());
        src.push_back(&p);
      }
      if (!s.points.empty()) c.series.push_back(std::move(s));
    }
    Series front;
    front.name = "Pareto front";
    front.color = 6;
    front.dashed = true;
    front.hollow = true;
    front.width = 1.5;
    for (size_t i : paretoFront(all, /*maximizeX=*/true, /*maximizeY=*/false)) {
      const Config& pc = src[i]->cfg;
      std::string label = pc.method == "forward_lit" ? "forward" : pc.method;
      if (pc.deferred()) label += " " + pc.layout;
      label += " " + thresholdText(pc.threshold);
      front.points.push_back({all[i].x, all[i].y, label});
    }
    if (!front.points.empty()) c.series.push_back(std::move(front));
    writeChart(c, dir, "frame_ms_vs_error");
  }
  // 3. G-buffer bytes per pixel against error, per layout.
  {
    Chart c;
    c.title = "G-buffer bytes per pixel against error (" + std::to_string(def.lights) + " lights, " +
              sizeText(def.size) + ")";
    c.notes = {machine, "bytes include depth; error: PSNR against forward_lit with no cut-off"};
    c.xLabel = "G-buffer bytes per pixel";
    c.yLabel = "PSNR dB";
    struct Mode {
      const char* axis;
      const char* name;
    };
    const Mode modes[] = {{"layout", "light volumes, cut-off 5/256"}, {"layout_exact", "fullscreen, no cut-off"}};
    int color = 0;
    for (const Mode& mode : modes) {
      Series s;
      s.name = mode.name;
      s.color = color++ == 0 ? 3 : 1;
      s.line = false;
      for (const std::string& layout : kLayouts)
        for (const auto& p : points)
          if (p.ok() && std::count(p.axes.begin(), p.axes.end(), mode.axis) && p.cfg.layout == layout)
            s.points.push_back({double(p.m.gbufferBytes), p.err.psnr, layout});
      std::sort(s.points.begin(), s.points.end(),
                [](const chart::Point& a, const chart::Point& b) { return a.x < b.x; });
      if (!s.points.empty()) c.series.push_back(std::move(s));
    }
    writeChart(c, dir, "bytes_vs_error");
  }
  // 4. Tiles against clusters: frame ms against light count for tiled and
  // clustered on the field and on its pillars variant (strong depth
  // discontinuities), when the sweep has the pillars axis.
  {
    Chart c;
    c.title = "Tiles against clusters (" + sizeText(def.size) + ", " + def.layout + " G-buffer, cut-off " +
              thresholdText(def.threshold) + ")";
    c.notes = {machine, "field: many-lights:N; pillars: many-lights:N:pillars (thin pillars near the camera over "
                        "the field and a far wall)"};
    c.xLabel = "point lights";
    c.yLabel = "frame ms (median)";
    c.logX = c.logY = true;
    struct Line {
      const char* method;
      const char* axis;
      const char* name;
      int color;
      bool dashed;
    };
    const Line lines[] = {{"tiled", "lights", "tiled, field", 4, true},
                          {"clustered", "lights", "clustered, field", 5, true},
                          {"tiled", "pillars", "tiled, pillars", 4, false},
                          {"clustered", "pillars", "clustered, pillars", 5, false}};
    bool pillars = false;
    for (const Line& l : lines) {
      Series s;
      s.name = l.name;
      s.color = l.color;
      s.dashed = l.dashed;
      for (const auto& p : points)
        if (p.ok() && p.cfg.method == l.method && std::count(p.axes.begin(), p.axes.end(), l.axis))
          s.points.push_back({double(p.cfg.lights), median(p.m.frameMs), ""});
      std::sort(s.points.begin(), s.points.end(),
                [](const chart::Point& a, const chart::Point& b) { return a.x < b.x; });
      pillars = pillars || (!s.points.empty() && std::string(l.axis) == "pillars");
      if (!s.points.empty()) c.series.push_back(std::move(s));
    }
    if (pillars) writeChart(c, dir, "tiles_vs_clusters");
  }
}

std::string sceneNote(const std::string& spec, bool procedural) {
  return "scene: " + (procedural ? std::string("many-lights:N (field grows with N)") : spec) +
         "; Blinn-Phong, classic attenuation";
}

}  // namespace rgraph::cli::bench
