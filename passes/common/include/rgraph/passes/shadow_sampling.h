// How lighting passes read shadows: the per-frame shadow data buffer that the
// shadow_map template's "info" instance writes (its layout: the C++ mirror of
// shaders/include/shadows.glsl's ShadowInfo block), and what every lighting
// pass type declares to sample it (slots, params, defines, samplers, the
// rule tying the "shadows" param to its inputs, the adapt hook that compiles
// the shadow code out when the scene casts nothing). Stated here once for the
// five lighting methods.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rgraph/pass.h"
#include "rgraph/passes/shadow_views.h"

namespace rgraph {
class GpuScene;
}

namespace rgraph::shadows {

// Shadowed lights a pipeline may have at once (the buffer holds this many maps).
constexpr uint32_t kMaxMaps = 64;
// Storage-buffer binding of ShadowInfo, texture units of the atlas (compare
// sampler) and of its raw depths (pcss's blocker search).
constexpr uint32_t kInfoBinding = 6;
constexpr int kAtlasUnit = 6;
constexpr int kDepthsUnit = 7;
// Texture unit of the EVSM moments (shadow_filter evsm; the shadow_moments pass).
constexpr int kMomentsUnit = 8;

// std430 mirrors of shadows.glsl (checked against glslang's reflection by
// the ShadowInfoLayout test).
struct GpuShadowMap {
  glm::mat4 viewProj[6];  // per layer: cascade k, face k (+x -x +y -y +z -z), or [0] for a spot light
  glm::vec4 splits;       // directional: the far view depth of cascades 0..3
  glm::ivec4 layers;      // x: first atlas layer, y: layer count, z: kind (0 directional, 1 spot, 2 point)
  glm::vec4 texel;        // directional: world units per texel of cascades 0..3; spot, point: x at distance 1,
                          // y: the near plane (EVSM's linear depth)
  glm::vec4 light;        // spot, point: xyz position, w: far plane
};
static_assert(sizeof(GpuShadowMap) == 448);

struct GpuShadowHeader {
  glm::ivec4 counts{0, -1, 0, 0};  // x: maps, y: the first directional light's map (-1: none), z: lights
  glm::vec4 params{0.0f};          // x: normal offset (texels), y: pcss light size (texels at the map's near side),
                                   // z, w: EVSM's positive and negative exponents (before evsmMaxExponent's clamp)
};
static_assert(sizeof(GpuShadowHeader) == 32);

// Bytes of the buffer for a scene with `lights` point and spot lights.
uint64_t infoBytes(uint32_t lights);

struct InfoOptions {
  float normalOffset = 1.0f;   // texels along the surface normal
  float pcssLightSize = 4.0f;  // texels
  float evsmPositive = 40.0f, evsmNegative = 5.0f;  // EVSM exponents (clamped per format where used)
};

// The largest EVSM exponent c the moments format holds: exp(c)^2 (the second
// moment) must stay finite, with a margin for the sums of the blur. rgba32f:
// 42 (e^84 = 3e36 of 3.4e38); rgba16f: 5.5 (e^11 = 60000 of 65504).
float evsmMaxExponent(Format moments);
// The buffer's content for this frame: header, kMaxMaps maps (the unused
// zero), then per light of GpuScene's light buffer (point lights, then spot
// lights, each in scene order) its map index or -1.
std::vector<uint8_t> packInfo(const Scene& scene, const std::vector<ShadowedLight>& lights,
                              const std::vector<ShadowView>& views, const InfoOptions& options);

// ---- What a lighting pass declares to read shadows.

// "shadows" (the atlas, compare sampler), "shadow_info" (the buffer),
// "shadow_depths" (the atlas again, raw depths: pcss only) and
// "shadow_moments" (the shadow_moments pass's EVSM moments: evsm only).
std::vector<SlotDecl> slots();
// "shadows" (bool), "shadow_filter" (hard, pcf, pcss, evsm), "pcf_size",
// "evsm_bleed".
std::vector<ParamDecl> params();
// SHADOWS, SHADOW_FILTER_*, SHADOW_PCF_SIZE=N, SHADOW_EVSM_BLEED=x when the
// params ask for shadows.
std::vector<std::string> defines(const ParamSet& p);
// The atlas (and pcss's depths, evsm's moments) on their units.
std::vector<SamplerSlot> samplers(const ParamSet& p);
// "shadows": true needs "shadows" and "shadow_info" bound (and "shadow_depths"
// with pcss, "shadow_moments" with evsm); binding them needs "shadows": true,
// and binding "shadow_moments" needs evsm.
PassRule rule();
// No caster or no casting light in view: "shadows" off and the inputs
// unbound (the template's expansion removes their writers alike).
void adapt(const SceneFeatures& f, PassAdaptation& a);
// Binds the info buffer at kInfoBinding when the pass reads shadows, and
// sets `program`'s u_shadowPositionError from the position target's format
// (and u_evsmMaxExponent from the moments' format with evsm).
void bindInfo(PassContext& ctx, uint32_t program);
// The relative error of the surface positions a pass reads: 2^-11 from a
// half-float position target, 2^-23 from a float one, 2^-20 rebuilt from depth.
float positionError(const PassContext& ctx);

// The above, as a lighting pass type takes them: slots(), params() and
// rule() added to `d`, and adapt() chained after the type's own hook (set
// before this call; not run when that hook disables the pass).
void declareReader(PassTypeDesc& d);
// defines(p) and samplers(p) added to a program that includes shadows.glsl.
void addToProgram(ShaderProgramSpec& s, const ParamSet& p);
// "shadows" off and the inputs unbound, with `why` noted (adapt's reasons, or
// a pass's own: forward with no blended surface to light).
void compileOut(PassAdaptation& a, const std::string& why);

}  // namespace rgraph::shadows
