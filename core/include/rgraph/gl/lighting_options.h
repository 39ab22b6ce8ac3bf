// Parameters shared by every pass that shades lights (deferred lighting,
// light volumes, tiled, forward_lit): one declaration, one meaning, the same
// shader defines, so that methods compared against each other differ only in
// how they visit lights.
#pragma once

#include <string>
#include <vector>

#include "rgraph/pass.h"

namespace rgraph::lighting {

// model, attenuation, threshold parameter declarations.
std::vector<ParamDecl> params(double defaultThreshold = 5.0 / 256.0, bool allowNoCutoff = true);
// The G-buffer layout parameter (learnopengl, pbr, compact, fp32).
ParamDecl layoutParam();

// Shader defines for the lighting model and attenuation of these params.
std::vector<std::string> defines(const ParamSet& params);
// GBUFFER_* define of the layout param.
std::string layoutDefine(const ParamSet& params);
// Every define a G-buffer writer or reader needs: the layout, and with
// constant_material, CONSTANT_MATERIAL + CONSTANT_METALLIC/ROUGHNESS values.
std::vector<std::string> gbufferDefines(const ParamSet& params);
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

// Binds the sampled G-buffer slots (position, normal, albedo, material, depth)
// to texture units 0..4; unbound slots get texture 0.
void bindGBuffer(PassContext& ctx);
// Checks that the slots a layout reads are bound; throws RuntimeError naming what is missing.
void requireGBuffer(PassContext& ctx, const std::string& passKind);
// Sampled G-buffer slot declarations (position, normal, albedo, material, depth).
std::vector<SlotDecl> gbufferSlots();
// The samplers of include/material.glsl, bound per draw by GpuScene (not slots).
std::vector<std::string> materialSamplers();
// The samplers of include/gbuffer_read.glsl for those slots, on the units
// bindGBuffer binds them to (for PassTypeDesc::programs).
std::vector<SamplerSlot> gbufferSamplers();

}  // namespace rgraph::lighting
