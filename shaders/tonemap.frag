#version 450 core
// HDR -> display: exposure, Reinhard or ACES (Narkowicz fit), then the sRGB
// transfer unless the target is an sRGB texture (GL applies it on write).
in vec2 v_uv;
layout(binding = 0) uniform sampler2D u_hdr;
uniform float u_exposure;
uniform int u_operator;     // 0 reinhard, 1 aces, 2 none (clamp)
uniform int u_encodeSrgb;   // 1: apply the sRGB transfer in the shader
uniform float u_gamma;      // 0: the exact sRGB curve, else pow(1/gamma)
layout(location = 0) out vec4 outColor;

vec3 aces(vec3 x) {
  const float a = 2.51, b = 0.03, c = 2.43, d = 0.59, e = 0.14;
  return clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0, 1.0);
}

vec3 srgbEncode(vec3 c) {
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
  vec3 hdr = texelFetch(u_hdr, ivec2(gl_FragCoord.xy), 0).rgb;
  // A NaN or Inf that reached the HDR target must not reach the output.
  hdr = mix(hdr, vec3(0.0), bvec3(isnan(hdr.r) || isinf(hdr.r), isnan(hdr.g) || isinf(hdr.g),
                                  isnan(hdr.b) || isinf(hdr.b)));
  vec3 c = max(hdr, vec3(0.0)) * u_exposure;
  if (u_operator == 0) c = c / (1.0 + c);
  else if (u_operator == 1) c = aces(c);
  c = clamp(c, 0.0, 1.0);
  if (u_encodeSrgb != 0) c = u_gamma > 0.0 ? pow(c, vec3(1.0 / u_gamma)) : srgbEncode(c);
  outColor = vec4(c, 1.0);
}
