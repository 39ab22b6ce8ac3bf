// Parameters shared by every pass that shades lights (deferred lighting,
// light volumes, tiled, forward_lit): one declaration, one meaning, the same
// shader defines, so that methods compared against each other differ only in
// how they visit lights. G-buffer readers take their layout facts from
// gbuffer_layout.h.
#pragma once

#include <string>
#include <vector>

#include "rgraph/format_sets.h"
#include "rgraph/pass.h"

namespace rgraph::lighting {

// The formats an HDR lighting target may have: hdrFormats() (rgraph/format_sets.h).
// For compute passes storing into an HDR target: the GLSL image format
// qualifier (rgba16f, rgba32f, r11f_g11f_b10f) and the GL internal format.
const char* hdrImageQualifier(Format f);
uint32_t hdrImageFormat(Format f);
// model, attenuation, threshold parameter declarations.
std::vector<ParamDecl> params(double defaultThreshold = 5.0 / 256.0, bool allowNoCutoff = true);
// The G-buffer layout parameter of a reader: the layouts of gbuffer::layouts().
ParamDecl layoutParam();

// Shader defines for the lighting model and attenuation of these params.
std::vector<std::string> defines(const ParamSet& params);
// GBUFFER_* define of the layout param (gbuffer::Layout::define).
std::string layoutDefine(const ParamSet& params);
// Every define a G-buffer writer or reader needs: the layout, and with
// constant_material, CONSTANT_MATERIAL + CONSTANT_METALLIC/ROUGHNESS values.
std::vector<std::string> gbufferDefines(const ParamSet& params);
// The two variants of a scene-drawing program: `spec`, and `spec` with
// HAS_NORMAL_MAPS. Which one runs follows the scene (normalMapVariant), so a
// pass declares both and validate checks both.
std::vector<ShaderProgramSpec> normalMapVariants(const ShaderProgramSpec& spec);
// The index in normalMapVariants of the pass's scene: 1 with normal maps.
size_t normalMapVariant(const PassContext& ctx);
// defines() and gbufferDefines(): what a pass that shades lights from the
// G-buffer compiles its program with.
std::vector<std::string> shadingDefines(const ParamSet& params);
// constant_material, metallic, roughness: set by adaptGBuffer for scenes with
// one metallic/roughness, so no G-buffer target carries them.
std::vector<ParamDecl> constantMaterialParams();
// The adapt hook of every pass that writes or reads the G-buffer material target.
void adaptGBuffer(const SceneFeatures& features, PassAdaptation& adaptation);
// adaptGBuffer, and without point lights in the scene, point_lights = false:
// the adapt hook of the passes that shade point lights from the G-buffer in one
// go (deferred_lighting, tiled_deferred).
void adaptPointLightShading(const SceneFeatures& features, PassAdaptation& adaptation);
float threshold(const ParamSet& params);

// Rule (PassTypeDesc::rules): the slots the pass's layout reads are bound
// (gbuffer::Layout::readerSlots), its sentence listing them per layout.
PassRule gbufferReaderRule();
// The layout's optional targets (emissive, reflectance) bound exactly when
// their parameter is on: the geometry pass's outputs (writes) or a reader's
// inputs; one slot error per mismatch. Used by both rules.
void checkOptionalTargets(const PassCheckContext& ctx, PassChecks& checks, bool writes);
// What every pass that reads the G-buffer declares alike: name, description,
// the sampled G-buffer slots (gbufferSlots), the checks that its layout's
// slots are bound (gbufferReaderRule) and that its layout is its writer's
// (gbuffer::sameLayoutAsWriterRule), needsScene, and adaptGBuffer as its adapt
// hook. The pass adds its own slots, params and programs.
PassTypeDesc gbufferReader(std::string name, std::string description);
// A compute lighting pass (tiled_deferred, clustered_deferred): gbufferReader,
// the HDR "color" slot written with image stores (loaded: lights added to
// it), params(), layoutParam(), point_lights and ambient_and_sun, and
// adaptPointLightShading. The pass adds its own params and programs.
PassTypeDesc computeLightingPass(std::string name, std::string description);
// Sampled G-buffer slot declarations (position, normal, albedo, material, depth).
std::vector<SlotDecl> gbufferSlots();
// The samplers of include/material.glsl, bound per draw by GpuScene (not slots).
std::vector<std::string> materialSamplers();
// The samplers of include/gbuffer_read.glsl for those slots, on units 0..4
// (for PassTypeDesc::programs: the executor binds the slots there).
std::vector<SamplerSlot> gbufferSamplers();

}  // namespace rgraph::lighting
