// What the image-based lighting passes share (passes/environment_cube,
// irradiance_cube, specular_cube, brdf_lut, environment_background and the
// lighting passes that read their output; docs/ibl.md).
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include "rgraph/format.h"
#include "rgraph/pass.h"

namespace rgraph::ibl {

// Formats of the cube maps the pre-filter passes write.
std::vector<Format> cubeFormats();
// Draws `program` (fullscreen.vert + a shader reading u_face) over each face
// of levels [0, levels) of the cube bound to `slot`, calling perLevel(level)
// before a level's faces (level-dependent uniforms).
void drawFaces(PassContext& ctx, uint32_t program, std::string_view slot, uint32_t levels,
               const std::function<void(uint32_t level)>& perLevel = {});
// Mip levels of the texture bound to `slot` (GL_TEXTURE_IMMUTABLE_LEVELS).
uint32_t levels(PassContext& ctx, std::string_view slot);

// The lighting passes' side: slots irradiance, specular and brdf_lut
// (optional, sampled on units 9, 10, 11) and the param "ibl"; the
// HAS_ENVIRONMENT define and the samplers when it is on; a rule that they
// are bound then; scene adaptation (declareReader wraps the type's adapt
// hook) turns it off when the scene has no environment, so that its images
// stay those of the constant ambient, bit for bit. setUniforms: per frame,
// u_hasEnvironment (a pipeline run unadapted on a scene without one keeps
// the constant ambient).
void declareReader(PassTypeDesc& d);
void addToProgram(ShaderProgramSpec& s, const ParamSet& p);
void adapt(const SceneFeatures& f, PassAdaptation& a);
void setUniforms(PassContext& ctx, uint32_t program);

}  // namespace rgraph::ibl
