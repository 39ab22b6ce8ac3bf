// `rgraph bench`, the post axis: bloom and SSAO methods on the shipped
// deferred-ssao-bloom pipeline (bench_post.h says what is measured).
#include "bench_post.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "bench.h"
#include "rgraph/error.h"
#include "rgraph/gl/executor.h"
#include "rgraph/pipeline_load.h"

namespace rgraph::cli::bench {

using nlohmann::json;

namespace {

const char* kPipeline = "deferred-ssao-bloom.json";
const std::map<std::string, std::set<std::string>> kEffectPasses = {
    {"bloom", {"bloom_bright", "bloom_blur", "bloom_composite"}}, {"ssao", {"ssao", "ssao_blur", "ssao_upsample"}}};
constexpr int kChainLevels = 6;
constexpr int kGrid = 8;  // bloom error: every 8th pixel of every 8th row

json& passNamed(json& pipeline, const std::string& name) {
  for (json& p : pipeline.at("passes"))
    if (p.at("name") == name) return p;
  throw RuntimeError(std::string(kPipeline) + " has no pass '" + name + "' (the post axis varies it)");
}

// The shipped pipeline with one effect's method set, the other as shipped;
// `output`: a resource to end the pipeline at (for the error), or "".
std::string variant(const json& shipped, const PostRow& row, const std::string& output) {
  json p = shipped;
  if (row.effect == "bloom") {
    // Both methods blur a full-size bright image (the chain with six levels),
    // so they are compared on the same input and against the same reference;
    // the shipped file blurs a half-size one with five levels.
    for (const char* r : {"bright", "blur_a", "blur_b"}) p.at("resources").at(r)["size"] = "output";
    p.at("resources").at("blur_b")["mips"] = kChainLevels;  // the chain's levels 1..6 in mip levels 0..5 (bloom_chain.h)
    json& params = passNamed(p, "bloom_blur")["params"];
    params = row.method == "gaussian" ? json{{"method", "gaussian"}, {"iterations", 6}, {"radius", 2.0}}
                                      : json{{"method", "mip_chain"}, {"levels", kChainLevels}};
  } else if (row.method == "full") {  // ssao at the G-buffer's size: no upsample
    p.at("resources").at("ao_raw")["size"] = "output";
    p.at("resources").erase("ao_half");
    passNamed(p, "ssao_blur")["outputs"]["ao"] = "ao";
    auto& passes = p.at("passes");
    passes.erase(std::remove_if(passes.begin(), passes.end(), [](const json& q) { return q.at("name") == "ssao_upsample"; }),
                 passes.end());
  } else if (row.method == "half_bilinear") {  // half size, sampled bilinearly by the lighting pass
    passNamed(p, "lighting")["inputs"]["ao"] = "ao_half";
    p.at("resources").erase("ao");
    auto& passes = p.at("passes");
    passes.erase(std::remove_if(passes.begin(), passes.end(), [](const json& q) { return q.at("name") == "ssao_upsample"; }),
                 passes.end());
  } else {
    passNamed(p, "ssao_upsample");  // as shipped: half size, depth-aware upsample
  }
  if (!output.empty()) p["output"] = output;
  return p.dump();
}

// Plugins are looked up by name, as for the shipped file.
PipelineConfig build(const std::string& text, const PostRow& row) {
  return loadPipelineTextOrThrow(text, std::string(kPipeline) + " (" + row.effect + " " + row.method + ")");
}

// ---- the bloom reference

// 2D Gaussians (weight, sigma in output pixels) whose sum is the blur a method stands for.
using Mixture = std::vector<std::pair<double, double>>;

// gaussian: `iterations` times a 9-tap binomial filter (C(12, 6+i) / 4070)
// with taps `radius` texels apart per axis: variance iterations * radius^2 *
// sum(i^2 w_i) (the central limit of the repeated filter).
// mip_chain: level k (1..L) passes k downsamples and k upsamples; a 13-tap
// downsample has variance 1.75 source texels^2 per axis (tap offsets 0, +-1,
// +-2 weighing 1/4, 1/2, 1/4: 1.5; each bilinear tap at a texel corner
// averages two texels: 0.25), a tent upsample 0.5 radius^2 plus the bilinear
// interpolation at a quarter texel (0.1875); the levels count 1 / L each.
Mixture nominalBlur(const std::string& method, double texelPx, double radius) {
  if (method == "gaussian") {
    double v9 = 0.0, c = 1.0;
    for (int j = 0; j <= 12; ++j) {
      if (j > 0) c = c * (12 - j + 1) / j;
      const int i = j - 6;
      if (std::abs(i) <= 4) v9 += i * i * c / 4070.0;
    }
    return {{1.0, texelPx * radius * std::sqrt(6.0 * v9)}};
  }
  Mixture m;
  double var = 0.0;
  for (int k = 1; k <= kChainLevels; ++k) {
    var += 1.75 * std::pow(4.0, k - 1) + (0.5 * radius * radius + 0.1875) * std::pow(4.0, k);
    m.push_back({1.0 / kChainLevels, texelPx * std::sqrt(var)});
  }
  return m;
}

double rmsSigma(const Mixture& m) {
  double v = 0.0;
  for (auto [w, s] : m) v += w * s * s;
  return std::sqrt(v);
}

// The mixture applied to `bright` (RGBA, rows top-down, edges clamped as the
// GPU's samplers do), at the grid's pixels: RGB per grid point.
std::vector<double> bloomReference(const std::vector<float>& bright, Extent size, const Mixture& mix) {
  const int w = int(size.width), h = int(size.height), gw = (w + kGrid - 1) / kGrid, gh = (h + kGrid - 1) / kGrid;
  std::vector<double> out(size_t(gw) * gh * 3, 0.0);
  for (auto [weight, sigma] : mix) {
    const int half = int(std::ceil(4.0 * sigma));
    std::vector<double> g(size_t(2 * half + 1));
    double sum = 0.0;
    for (int t = -half; t <= half; ++t) sum += g[size_t(t + half)] = std::exp(-0.5 * t * t / (sigma * sigma));
    for (double& v : g) v /= sum;
    std::vector<double> rows(size_t(h) * gw * 3, 0.0);  // horizontal pass, grid columns only
    for (int y = 0; y < h; ++y)
      for (int gx = 0; gx < gw; ++gx)
        for (int t = -half; t <= half; ++t) {
          const int x = std::clamp(gx * kGrid + t, 0, w - 1);
          const float* px = &bright[(size_t(y) * w + x) * 4];
          double* o = &rows[(size_t(y) * gw + gx) * 3];
          for (int c = 0; c < 3; ++c) o[c] += g[size_t(t + half)] * px[c];
        }
    for (int gy = 0; gy < gh; ++gy)
      for (int gx = 0; gx < gw; ++gx)
        for (int t = -half; t <= half; ++t) {
          const int y = std::clamp(gy * kGrid + t, 0, h - 1);
          for (int c = 0; c < 3; ++c)
            out[(size_t(gy) * gw + gx) * 3 + c] += weight * g[size_t(t + half)] * rows[(size_t(y) * gw + gx) * 3 + c];
        }
  }
  return out;
}

// Relative RMS error and PSNR (peak: the reference's maximum) of `bloom` at the grid.
void bloomError(const std::vector<float>& bloom, Extent size, const std::vector<double>& ref, PostRow& row) {
  const int w = int(size.width), gw = (w + kGrid - 1) / kGrid, gh = (int(size.height) + kGrid - 1) / kGrid;
  double err = 0.0, energy = 0.0, peak = 0.0;
  for (int gy = 0; gy < gh; ++gy)
    for (int gx = 0; gx < gw; ++gx)
      for (int c = 0; c < 3; ++c) {
        const double r = ref[(size_t(gy) * gw + gx) * 3 + c];
        const double d = bloom[(size_t(gy * kGrid) * w + gx * kGrid) * 4 + c] - r;
        err += d * d, energy += r * r, peak = std::max(peak, r);
      }
  row.relError = energy > 0.0 ? std::sqrt(err / energy) : 0.0;
  const double mse = err / (double(gw) * gh * 3);
  row.psnr = mse > 0.0 ? std::min(kPsnrCap, 10.0 * std::log10(peak * peak / mse)) : kPsnrCap;
}

Extent extentOf(const Executor& exec, const std::string& resource) {
  for (const auto& r : exec.plan().resources)
    if (r.name == resource) return r.extent;
  throw RuntimeError(std::string(kPipeline) + " has no resource '" + resource + "'");
}

// The error part of a bloom row: the pipeline ended at the blurred image.
void bloomRowError(const json& shipped, PostRow& row, const Scene& scene, ShaderLibrary& shaders) {
  PipelineConfig cfg = build(variant(shipped, row, "blur_a"), row);
  const std::unique_ptr<Executor> exec = makeExecutor(cfg, scene, row.size, shaders);
  exec->renderFrame();
  const Extent bright = extentOf(*exec, "bright");
  if (bright != row.size || extentOf(*exec, "blur_a") != row.size)
    throw RuntimeError("the post axis expects the bright and blurred images at the output size");
  const Mixture mix = nominalBlur(row.method, 1.0, row.method == "gaussian" ? 2.0 : 1.0);
  row.spreadPx = rmsSigma(mix);
  bloomError(exec->readTextureRGBA32F("blur_a"), row.size,
             bloomReference(exec->readTextureRGBA32F("bright"), row.size, mix), row);
}

// The ambient visibility the lighting pass sees, at the output size (R of
// RGBA): "ao", or for half_bilinear "ao_half" upsampled bilinearly as the
// lighting pass's sampler does (texel centres, edges clamped). That variant
// ends at the lighting pass's "hdr" (output-sized, so no size warning):
// nothing runs after the pass that reads "ao_half", so its texture still
// holds it.
std::vector<float> aoOf(const json& shipped, const PostRow& row, const Scene& scene, ShaderLibrary& shaders) {
  const bool bilinear = row.method == "half_bilinear";
  PipelineConfig cfg = build(variant(shipped, row, bilinear ? "hdr" : "ao"), row);
  const std::unique_ptr<Executor> exec = makeExecutor(cfg, scene, row.size, shaders);
  exec->renderFrame();
  if (!bilinear) return exec->readTextureRGBA32F("ao");
  const std::vector<float> half = exec->readTextureRGBA32F("ao_half");
  const Extent h = extentOf(*exec, "ao_half");
  const int W = int(row.size.width), H = int(row.size.height), w = int(h.width), hh = int(h.height);
  auto at = [&](int x, int y) { return half[(size_t(std::clamp(y, 0, hh - 1)) * w + std::clamp(x, 0, w - 1)) * 4]; };
  std::vector<float> out(size_t(W) * H * 4, 0.0f);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const double sx = (x + 0.5) * w / W - 0.5, sy = (y + 0.5) * hh / H - 0.5;
      const int bx = int(std::floor(sx)), by = int(std::floor(sy));
      const double fx = sx - bx, fy = sy - by;
      out[(size_t(y) * W + x) * 4] = float((1 - fy) * ((1 - fx) * at(bx, by) + fx * at(bx + 1, by)) +
                                           fy * ((1 - fx) * at(bx, by + 1) + fx * at(bx + 1, by + 1)));
    }
  return out;
}

// The rows of one effect, timed in turn frame by frame; their last images.
std::vector<std::vector<uint8_t>> timeGroup(const json& shipped, const std::vector<PostRow*>& rows,
                                            const PostPlan& plan, const Scene& scene, ShaderLibrary& shaders) {
  std::vector<std::unique_ptr<Executor>> execs;
  for (PostRow* r : rows) {
    PipelineConfig cfg = build(variant(shipped, *r, ""), *r);
    execs.push_back(makeExecutor(cfg, scene, r->size, shaders));
    r->allocatedBytes = execs.back()->plan().allocatedBytes;
    r->naiveBytes = execs.back()->plan().naiveBytes;
  }
  const std::set<std::string>& passes = kEffectPasses.at(rows.front()->effect);
  for (int f = 0; f < plan.warm + plan.timedFrames; ++f)
    for (size_t i = 0; i < rows.size(); ++i) {
      const double ms = timedFrame(*execs[i]);
      if (f < plan.warm) continue;
      rows[i]->frameMs.push_back(ms);
      if (!timedPasses(*execs[i])) continue;
      double effect = 0.0;
      for (const auto& t : execs[i]->timings())
        if (passes.count(t.name)) effect += t.ms;
      rows[i]->effectMs.push_back(effect);
    }
  std::vector<std::vector<uint8_t>> images;
  for (const auto& e : execs) images.push_back(e->readOutputRGBA8());
  return images;
}

void runEffect(const json& shipped, const std::vector<PostRow*>& rows, const PostPlan& plan, const Scene& scene,
               ShaderLibrary& shaders) {
  const std::vector<std::vector<uint8_t>> images = timeGroup(shipped, rows, plan, scene, shaders);
  if (rows.front()->effect == "bloom") {
    for (PostRow* r : rows) bloomRowError(shipped, *r, scene, shaders);
    return;
  }
  // ssao: every row against the first (full size), which is exact.
  const std::vector<float> full = aoOf(shipped, *rows.front(), scene, shaders);
  rows.front()->psnr = rows.front()->imagePsnr = kPsnrCap;
  for (size_t k = 1; k < rows.size(); ++k) {
    const std::vector<float> ao = aoOf(shipped, *rows[k], scene, shaders);
    double err = 0.0;
    for (size_t i = 0; i < full.size(); i += 4) err += (ao[i] - full[i]) * (ao[i] - full[i]);
    const double mse = err / double(full.size() / 4);
    rows[k]->relError = std::sqrt(mse);
    rows[k]->psnr = mse > 0.0 ? std::min(kPsnrCap, 10.0 * std::log10(1.0 / mse)) : kPsnrCap;
    rows[k]->imagePsnr = compareImages(images[k], images[0]).psnr;
  }
}

}  // namespace

PostPlan postPlan(bool quick) {
  PostPlan p;
  if (quick) p.timedFrames = 2;
  return p;
}

std::vector<PostRow> planPost(const PostPlan& plan) {
  std::vector<PostRow> rows;
  for (const auto& [effect, method] : std::vector<std::pair<const char*, const char*>>{
           {"bloom", "gaussian"}, {"bloom", "mip_chain"}, {"ssao", "full"}, {"ssao", "half"}, {"ssao", "half_bilinear"}}) {
    PostRow r;
    r.effect = effect, r.method = method, r.size = plan.size;
    rows.push_back(r);
  }
  return rows;
}

size_t runPost(std::vector<PostRow>& rows, const PostPlan& plan, const std::string& pipelineDir,
               ShaderLibrary& shaders) {
  size_t failures = 0;
  const std::string file = (std::filesystem::path(pipelineDir) / kPipeline).string();
  json shipped;
  try {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    shipped = json::parse(text.str());
  } catch (const std::exception& e) {
    for (auto& r : rows) r.error = file + ": " + e.what();
    return rows.size();
  }
  // Bloom: the default scene (its light markers glow). SSAO: objects on a
  // floor (the default scene's objects float: next to nothing occludes).
  for (size_t i = 0; i < rows.size();) {
    std::vector<PostRow*> group;
    for (; i < rows.size() && (group.empty() || rows[i].effect == group.front()->effect); ++i) group.push_back(&rows[i]);
    std::string methods;
    for (PostRow* r : group) {
      r->scene = r->effect == "bloom" ? "learnopengl:overview" : "many-lights:32";
      methods += (methods.empty() ? "" : ", ") + r->method;
    }
    std::fprintf(stderr, "[post] %s (%s) at %s:", group.front()->effect.c_str(), methods.c_str(),
                 sizeText(group.front()->size).c_str());
    try {
      const Scene scene = loadSceneAny(group.front()->scene);
      runEffect(shipped, group, plan, scene, shaders);
      for (PostRow* r : group)
        std::fprintf(stderr, " %s %.1f ms (frame %.1f);", r->method.c_str(), median(r->effectMs), median(r->frameMs));
      std::fprintf(stderr, "\n");
    } catch (const std::exception& e) {
      for (PostRow* r : group) r->error = e.what();
      std::fprintf(stderr, " failed: %s\n", e.what());
      failures += group.size();
    }
  }
  return failures;
}

json postJson(const PostRow& r) {
  json j = {{"axes", {"post"}},
            {"effect", r.effect},
            {"method", r.method},
            {"pipeline", kPipeline},
            {"scene", r.scene},
            {"width", r.size.width},
            {"height", r.size.height},
            {"frame_ms", r.frameMs},
            {"median_ms", median(r.frameMs)},
            {"effect_ms", r.effectMs},
            {"effect_median_ms", median(r.effectMs)},
            {"allocated_bytes", r.allocatedBytes},
            {"naive_bytes", r.naiveBytes}};
  if (r.effect == "bloom") {
    j["spread_rms_px"] = r.spreadPx;
    j["relative_rms_error"] = r.relError;
    j["psnr_db"] = r.psnr;
  } else {
    j["ao_rms_error"] = r.relError;
    j["ao_psnr_db"] = r.psnr;
    j["image_psnr_db"] = r.imagePsnr;
  }
  if (!r.ok()) j["error"] = r.error;
  return j;
}

void postChecks(const std::vector<PostRow>& rows, json& checks, std::vector<std::string>& summary) {
  auto find = [&](const char* effect, const char* method) -> const PostRow* {
    for (const auto& r : rows)
      if (r.ok() && r.effect == effect && r.method == method && !r.effectMs.empty()) return &r;
    return nullptr;
  };
  char buf[512];
  if (const PostRow *g = find("bloom", "gaussian"), *c = find("bloom", "mip_chain"); g && c) {
    const double speedup = median(g->effectMs) / median(c->effectMs);
    const bool pass = speedup >= 2.0 && c->spreadPx >= g->spreadPx;
    checks["post_bloom"] = {{"speedup", speedup},
                            {"gaussian_ms", median(g->effectMs)},
                            {"mip_chain_ms", median(c->effectMs)},
                            {"gaussian_relative_rms_error", g->relError},
                            {"mip_chain_relative_rms_error", c->relError},
                            {"gaussian_spread_px", g->spreadPx},
                            {"mip_chain_spread_px", c->spreadPx},
                            {"pass", pass}};
    std::snprintf(buf, sizeof buf,
                  "bloom at %s: mip_chain %.1f ms vs gaussian %.1f ms (%.2fx), spread %.1f vs %.1f px rms, error vs "
                  "reference %.1f%% (%.1f dB) vs %.1f%% (%.1f dB) (>= 2x and as wide: %s)",
                  sizeText(c->size).c_str(), median(c->effectMs), median(g->effectMs), speedup, c->spreadPx,
                  g->spreadPx, 100 * c->relError, c->psnr, 100 * g->relError, g->psnr, pass ? "yes" : "NO");
    summary.push_back(buf);
  }
  if (const PostRow *f = find("ssao", "full"), *h = find("ssao", "half"); f && h) {
    const double speedup = median(f->effectMs) / median(h->effectMs);
    const PostRow* b = find("ssao", "half_bilinear");
    checks["post_ssao"] = {{"speedup", speedup},
                           {"full_ms", median(f->effectMs)},
                           {"half_ms", median(h->effectMs)},
                           {"ao_rms_error", h->relError},
                           {"ao_psnr_db", h->psnr},
                           {"image_psnr_db", h->imagePsnr}};
    if (b) checks["post_ssao"]["half_bilinear"] = {{"ms", median(b->effectMs)}, {"ao_rms_error", b->relError},
                                                   {"ao_psnr_db", b->psnr}, {"image_psnr_db", b->imagePsnr}};
    std::snprintf(buf, sizeof buf,
                  "ssao at %s: half %.1f ms vs full %.1f ms (%.2fx), visibility RMS error %.4f (%.1f dB), image "
                  "%.1f dB against full",
                  sizeText(h->size).c_str(), median(h->effectMs), median(f->effectMs), speedup, h->relError, h->psnr,
                  h->imagePsnr);
    summary.push_back(buf);
    if (b) {
      std::snprintf(buf, sizeof buf,
                    "ssao half size, plain bilinear upsample instead: %.1f ms, visibility RMS error %.4f (%.1f dB), "
                    "image %.1f dB against full",
                    median(b->effectMs), b->relError, b->psnr, b->imagePsnr);
      summary.push_back(buf);
    }
  }
}

}  // namespace rgraph::cli::bench
