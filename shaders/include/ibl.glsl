// Shared by the IBL pre-filter passes (passes/environment_cube,
// irradiance_cube, specular_cube, brdf_lut; docs/ibl.md): cube-face
// directions, the Hammersley set and GGX importance sampling, with the GGX
// of include/lighting.glsl (alpha = roughness^2).

const float IBL_PI = 3.14159265359;

// The world direction through texel coordinate uv (0..1, row 0 first) of
// cube face `face` (+x -x +y -y +z -z), as GL's cube map lookup defines it.
vec3 cubeFaceDirection(int face, vec2 uv) {
  vec2 c = uv * 2.0 - 1.0;
  vec3 d;
  if (face == 0) d = vec3(1.0, -c.y, -c.x);
  else if (face == 1) d = vec3(-1.0, -c.y, c.x);
  else if (face == 2) d = vec3(c.x, 1.0, c.y);
  else if (face == 3) d = vec3(c.x, -1.0, -c.y);
  else if (face == 4) d = vec3(c.x, -c.y, 1.0);
  else d = vec3(-c.x, -c.y, -1.0);
  return normalize(d);
}

vec2 hammersley(uint i, uint n) {
  return vec2(float(i) / float(n), float(bitfieldReverse(i)) * 2.3283064365386963e-10);
}

// A half vector around N distributed as GGX's D(h) (n.h).
vec3 importanceSampleGGX(vec2 xi, vec3 N, float roughness) {
  float a = roughness * roughness;
  float phi = 2.0 * IBL_PI * xi.x;
  float cosTheta = sqrt((1.0 - xi.y) / (1.0 + (a * a - 1.0) * xi.y));
  float sinTheta = sqrt(max(1.0 - cosTheta * cosTheta, 0.0));
  vec3 up = abs(N.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  vec3 T = normalize(cross(up, N));
  vec3 B = cross(N, T);
  return normalize(T * (cos(phi) * sinTheta) + B * (sin(phi) * sinTheta) + N * cosTheta);
}

float iblDistributionGGX(float NdotH, float roughness) {
  float a = roughness * roughness;
  float a2 = a * a;
  float d = NdotH * NdotH * (a2 - 1.0) + 1.0;
  return a2 / max(IBL_PI * d * d, 1e-7);
}
