#version 450 core
// passes/irradiance_cube: the cosine-weighted mean of the environment over
// the hemisphere around each texel's direction, E/pi (so a uniform radiance
// L gives L): a (phi, theta) grid of midpoints, weights cos sin, normalised
// by their sum. Sampled from a level of the environment cube whose texels
// are twice the grid's spacing (u_sourceLod, passes/irradiance_cube).
#include "include/ibl.glsl"

uniform int u_face;
uniform float u_sourceLod;
layout(binding = 0) uniform samplerCube u_environment;

in vec2 v_uv;
layout(location = 0) out vec4 outColor;

const int PHI_STEPS = 64;
const int THETA_STEPS = 16;

void main() {
  vec3 N = cubeFaceDirection(u_face, v_uv);
  vec3 up = abs(N.y) < 0.999 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
  vec3 T = normalize(cross(up, N));
  vec3 B = cross(N, T);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (int p = 0; p < PHI_STEPS; ++p) {
    float phi = (float(p) + 0.5) * 2.0 * IBL_PI / float(PHI_STEPS);
    for (int t = 0; t < THETA_STEPS; ++t) {
      float theta = (float(t) + 0.5) * 0.5 * IBL_PI / float(THETA_STEPS);
      vec3 L = T * (cos(phi) * sin(theta)) + B * (sin(phi) * sin(theta)) + N * cos(theta);
      float w = cos(theta) * sin(theta);
      sum += textureLod(u_environment, L, u_sourceLod).rgb * w;
      weight += w;
    }
  }
  outColor = vec4(sum / weight, 1.0);
}
