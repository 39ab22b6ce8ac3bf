#version 450 core
// Bloom, step 1: the bright part of the HDR image, with a soft threshold
// (a quadratic knee below the threshold), written at the bright target's
// size. At half size each target pixel sits between four source texels, so
// the bilinear tap averages 2x2 of them.
in vec2 v_uv;
layout(binding = 0) uniform sampler2D u_hdr;
uniform float u_threshold;  // brightness (max channel) where bloom starts
uniform float u_knee;       // width of the soft transition below it (0: hard cut)
uniform float u_clamp;      // brightest value kept (fireflies)
layout(location = 0) out vec4 outColor;

void main() {
  vec3 c = texture(u_hdr, v_uv).rgb;
  // A NaN or Inf must not spread through the blur.
  if (any(isnan(c)) || any(isinf(c))) c = vec3(0.0);
  c = min(max(c, vec3(0.0)), vec3(u_clamp));
  float brightness = max(c.r, max(c.g, c.b));
  float soft = clamp(brightness - u_threshold + u_knee, 0.0, 2.0 * u_knee);
  soft = soft * soft / (4.0 * u_knee + 1e-5);
  float contribution = max(soft, brightness - u_threshold) / max(brightness, 1e-5);
  outColor = vec4(c * contribution, 1.0);
}
