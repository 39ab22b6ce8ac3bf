#include "rgraph/passes/shadow_sampling.h"

#include <GL/glcorearb.h>

#include <cstdio>
#include <cstring>

#include "rgraph/format_sets.h"
#include "rgraph/pass_decl.h"
#include "rgraph/scene.h"

namespace rgraph::shadows {

uint64_t infoBytes(uint32_t lights) {
  // At least one light entry: an empty runtime array is still an array.
  return sizeof(GpuShadowHeader) + kMaxMaps * sizeof(GpuShadowMap) + 4ull * std::max(lights, 1u);
}

namespace {

int kindCode(LightKind k) { return k == LightKind::directional ? 0 : k == LightKind::spot ? 1 : 2; }

// Scene::pointLights index -> index in GpuScene's light buffer (point lights
// first, then spot lights, scene order within each).
std::vector<uint32_t> bufferIndices(const Scene& scene) {
  std::vector<uint32_t> at(scene.pointLights.size());
  uint32_t next = 0;
  for (int spots = 0; spots < 2; ++spots)
    for (size_t i = 0; i < scene.pointLights.size(); ++i)
      if (scene.pointLights[i].spot == (spots == 1)) at[i] = next++;
  return at;
}

}  // namespace

std::vector<uint8_t> packInfo(const Scene& scene, const std::vector<ShadowedLight>& lights,
                              const std::vector<ShadowView>& views, const InfoOptions& options) {
  const uint32_t lightCount = static_cast<uint32_t>(scene.pointLights.size());
  GpuShadowHeader header;
  header.counts = glm::ivec4(static_cast<int>(std::min<size_t>(lights.size(), kMaxMaps)), -1,
                             static_cast<int>(lightCount), 0);
  header.params = glm::vec4(options.normalOffset, options.pcssLightSize, options.evsmPositive, options.evsmNegative);
  std::vector<GpuShadowMap> maps(kMaxMaps, GpuShadowMap{});
  std::vector<int32_t> lightMap(std::max(lightCount, 1u), -1);
  const std::vector<uint32_t> atBuffer = bufferIndices(scene);
  for (size_t m = 0; m < lights.size() && m < kMaxMaps; ++m) {
    const ShadowedLight& l = lights[m];
    GpuShadowMap& g = maps[m];
    g.layers = glm::ivec4(static_cast<int>(l.firstLayer), static_cast<int>(l.layers), kindCode(l.kind), 0);
    for (const ShadowView& v : views) {
      if (v.layer < l.firstLayer || v.layer >= l.firstLayer + l.layers) continue;
      const uint32_t k = v.layer - l.firstLayer;
      if (k >= 6) continue;
      g.viewProj[k] = v.proj * v.view;
      if (l.kind == LightKind::directional) {
        if (k < 4) {
          g.splits[k] = v.splitFar;
          g.texel[k] = v.texelWorld;
        }
      } else {
        g.texel.x = v.texelWorld;
        g.texel.y = v.nearPlane;
        g.light = glm::vec4(v.lightPosition, v.farPlane);
      }
    }
    if (l.kind == LightKind::directional) {
      if (l.light == 0) header.counts.y = static_cast<int>(m);
    } else if (l.light < lightCount) {
      lightMap[atBuffer[l.light]] = static_cast<int>(m);
    }
  }
  std::vector<uint8_t> bytes(infoBytes(lightCount));
  std::memcpy(bytes.data(), &header, sizeof header);
  std::memcpy(bytes.data() + sizeof header, maps.data(), maps.size() * sizeof(GpuShadowMap));
  std::memcpy(bytes.data() + sizeof header + maps.size() * sizeof(GpuShadowMap), lightMap.data(),
              lightMap.size() * sizeof(int32_t));
  return bytes;
}

float evsmMaxExponent(Format moments) { return moments == Format::rgba16f ? 5.5f : 42.0f; }

std::vector<SlotDecl> slots() {
  using namespace rgraph::decl;
  SamplerState compare;
  compare.compare = SamplerState::Compare::less_equal;  // linear: each tap a hardware 2x2 comparison
  SamplerState raw;
  raw.filter = SamplerState::Filter::nearest;
  SamplerState trilinear;  // moments filter linearly, and the lookup picks the receiver's mip level
  trilinear.mip = SamplerState::MipFilter::linear;
  return {
      sampledWith(slot("shadows", Access::sampled, false, SlotDecl::Load::never,
                       "shadow atlas (depth array, every shadow map's layers) read with a compare sampler",
                       depthFormats()),
                  compare),
      slot("shadow_info", Access::storage_read, false, SlotDecl::Load::never,
           "per-frame shadow data (the shadow_map template's info buffer): which light samples which layers how"),
      sampledWith(slot("shadow_depths", Access::sampled, false, SlotDecl::Load::never,
                       "the shadow atlas again, its raw depths (shadow_filter pcss: the blocker search)",
                       depthFormats()),
                  raw),
      sampledWith(slot("shadow_moments", Access::sampled, false, SlotDecl::Load::never,
                       "EVSM moments of every shadow map's layers, blurred and mip-mapped (the shadow_moments pass; "
                       "shadow_filter evsm)",
                       {Format::rgba32f, Format::rgba16f}),
                  trilinear),
  };
}

std::vector<ParamDecl> params() {
  using namespace rgraph::decl;
  return {
      param("shadows", ParamType::boolean, false,
            "multiply each shadowed light by its visibility (bind shadows and shadow_info); off: no shadow code"),
      param("shadow_filter", ParamType::enumeration, std::string("pcf"),
            "hard (one comparison per pixel), pcf (NxN bilinear comparisons), pcss (blocker search, then a "
            "kernel widening with the receiver's distance from its blocker) or evsm (exponential variance maps: "
            "bind shadow_moments)",
            {"hard", "pcf", "pcss", "evsm"}),
      ranged("pcf_size", ParamType::integer, int64_t{3}, 1.0, 9.0, "pcf and pcss: taps per side of the kernel (odd: 1, 3, 5, 7, 9)"),
      ranged("evsm_bleed", ParamType::number, 0.2, 0.0, 0.95,
             "evsm: light-bleeding reduction, the visibility below this share cut to 0 and the rest rescaled "
             "(0: none; higher trades light leaks for darker penumbrae)"),
  };
}

std::vector<std::string> defines(const ParamSet& p) {
  if (!p.getBool("shadows")) return {};
  const std::string filter = p.getString("shadow_filter");
  int size = static_cast<int>(p.getInt("pcf_size"));
  if (size % 2 == 0) ++size;  // an even size has no centre tap: the next odd one
  char bleed[32];  // a GLSL float literal, to a thousandth
  std::snprintf(bleed, sizeof bleed, "%.3f", p.getNumber("evsm_bleed"));
  return {"SHADOWS", "SHADOW_MAX_MAPS=" + std::to_string(kMaxMaps),
          filter == "hard"   ? "SHADOW_FILTER_HARD"
          : filter == "pcss" ? "SHADOW_FILTER_PCSS"
          : filter == "evsm" ? "SHADOW_FILTER_EVSM"
                             : "SHADOW_FILTER_PCF",
          "SHADOW_PCF_SIZE=" + std::to_string(size), std::string("SHADOW_EVSM_BLEED=") + bleed};
}

std::vector<SamplerSlot> samplers(const ParamSet& p) {
  if (!p.getBool("shadows")) return {};
  std::vector<SamplerSlot> s = {{"shadows", "u_shadowAtlas", kAtlasUnit}};
  if (p.getString("shadow_filter") == "pcss") s.push_back({"shadow_depths", "u_shadowDepths", kDepthsUnit});
  if (p.getString("shadow_filter") == "evsm") s.push_back({"shadow_moments", "u_shadowMoments", kMomentsUnit});
  return s;
}

PassRule rule() {
  PassRule r;
  r.text = "shadows: true needs inputs shadows and shadow_info (and shadow_depths with shadow_filter pcss, "
           "shadow_moments with shadow_filter evsm); binding them needs shadows: true, and shadow_moments evsm";
  r.check = [](const PassCheckContext& ctx, PassChecks& checks) {
    const bool on = ctx.params().getBool("shadows");
    const std::string filter = ctx.params().getString("shadow_filter");
    // The filter a slot is read with alone ("": every filter).
    auto onlyWith = [](const std::string& slot) {
      return slot == "shadow_depths" ? std::string("pcss") : slot == "shadow_moments" ? std::string("evsm") : std::string();
    };
    for (const char* name : {"shadows", "shadow_info", "shadow_depths", "shadow_moments"}) {
      const std::string slot = name;
      const std::string only = onlyWith(slot);
      const bool needed = on && (only.empty() || filter == only);
      if (needed && !ctx.bound(slot))
        checks.slotError(slot, "input '" + slot + "' is needed with \"shadows\": true" +
                                   (only.empty() ? "" : " and shadow_filter " + only) + " but not bound");
      else if (!on && ctx.bound(slot))
        checks.slotError(slot, "input '" + slot +
                                   "' is bound but \"shadows\" is false: set \"shadows\": true to read it, or unbind it");
      // shadow_depths stays allowed with every filter (the shipped pipelines
      // bind it for a switch to pcss); the moments are drawn for evsm alone.
      else if (on && slot == "shadow_moments" && filter != "evsm" && ctx.bound(slot))
        checks.slotError(slot, "input 'shadow_moments' is bound but shadow_filter is " + filter +
                                   ": set \"shadow_filter\": \"evsm\" to read it, or unbind it");
    }
  };
  return r;
}

void adapt(const SceneFeatures& f, PassAdaptation& a) {
  if (!a.params.getBool("shadows")) return;
  std::string why;
  if (!f.shadowCasters) why = "no primitive casts a shadow";
  else if (f.shadowLights.empty()) why = "no casting light reaches the view";
  if (!why.empty()) compileOut(a, why);
}

void compileOut(PassAdaptation& a, const std::string& why) {
  if (!a.params.getBool("shadows")) return;
  a.params.set("shadows", false);
  a.unbindSlots.insert(a.unbindSlots.end(), {"shadows", "shadow_info", "shadow_depths", "shadow_moments"});
  a.notes.push_back(why + ": shadow code compiled out");
}

void declareReader(PassTypeDesc& d) {
  for (auto& s : slots()) d.slots.push_back(std::move(s));
  for (auto& p : params()) d.params.push_back(std::move(p));
  d.rules.push_back(rule());
  d.adapt = [own = std::move(d.adapt)](const SceneFeatures& f, PassAdaptation& a) {
    if (own) own(f, a);
    // A disabled pass reads nothing (the graph keeps no writer alive for it).
    if (!a.disable) adapt(f, a);
  };
}

void addToProgram(ShaderProgramSpec& s, const ParamSet& p) {
  for (auto& d : defines(p)) s.defines.push_back(std::move(d));
  for (auto& sampler : samplers(p)) s.samplers.push_back(std::move(sampler));
}

float positionError(const PassContext& ctx) {
  if (!ctx.bound("position")) return 1.0f / (1 << 20);  // rebuilt from depth: about a 20-bit mantissa's
  const Format f = ctx.format("position");
  return f == Format::rgba16f || f == Format::rgb16f ? 1.0f / (1 << 11) : 1.0f / (1 << 23);
}

void bindInfo(PassContext& ctx, uint32_t program) {
  if (!ctx.params().getBool("shadows") || !ctx.bound("shadow_info")) return;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kInfoBinding, ctx.buffer("shadow_info"));
  glProgramUniform1f(program, glGetUniformLocation(program, "u_shadowPositionError"), positionError(ctx));
  if (ctx.bound("shadow_moments"))
    glProgramUniform1f(program, glGetUniformLocation(program, "u_evsmMaxExponent"),
                       evsmMaxExponent(ctx.format("shadow_moments")));
}

}  // namespace rgraph::shadows
