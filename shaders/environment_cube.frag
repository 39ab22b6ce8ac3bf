#version 450 core
// passes/environment_cube: the scene's environment into one face of a cube
// map (level 0), as core/src/scene/scene_environment.cpp's
// environmentRadiance computes it (the IBL oracle tests compare the two).
#include "include/ibl.glsl"

uniform int u_face;
uniform int u_kind;  // 0 uniform, 1 sky, 2 hdr (Environment::Kind)
uniform float u_intensity;
uniform vec3 u_color;
uniform vec3 u_sunDirection;  // unit, towards the sun
uniform vec3 u_sunColor;
uniform float u_sunRadius;    // radians
uniform vec3 u_zenith, u_horizon, u_ground;
layout(binding = 0) uniform sampler2D u_equirect;  // hdr: longitude along x from -z towards +x, +y up at row 0

in vec2 v_uv;
layout(location = 0) out vec4 outColor;

vec3 sky(vec3 d) {
  float e = d.y;
  vec3 c = e >= 0.0 ? mix(u_horizon, u_zenith, sqrt(e)) : mix(u_horizon, u_ground, min(1.0, -e * 8.0));
  float angle = acos(clamp(dot(d, u_sunDirection), -1.0, 1.0));
  float t = clamp((u_sunRadius - angle) / (0.2 * u_sunRadius), 0.0, 1.0);
  return c + u_sunColor * t;
}

vec3 equirect(vec3 d) {
  vec2 uv = vec2(0.5 + atan(d.x, -d.z) / (2.0 * IBL_PI), acos(clamp(d.y, -1.0, 1.0)) / IBL_PI);
  return textureLod(u_equirect, uv, 0.0).rgb;
}

void main() {
  vec3 d = cubeFaceDirection(u_face, v_uv);
  vec3 c = u_kind == 0 ? u_color : (u_kind == 1 ? sky(d) : equirect(d));
  outColor = vec4(c * u_intensity, 1.0);
}
