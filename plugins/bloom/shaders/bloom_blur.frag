#version 450 core
// Bloom, step 2: one direction of a separable 9-tap Gaussian (LearnOpenGL's
// bloom chapter). The pass ping-pongs horizontal and vertical passes between
// its two targets. u_image may be smaller or larger than the target: it is
// sampled at the target pixel's uv with bilinear filtering.
layout(binding = 0) uniform sampler2D u_image;
uniform vec2 u_targetTexel;  // 1 / target size
uniform vec2 u_step;         // uv offset between taps (direction * radius / source size)
layout(location = 0) out vec4 outColor;

const float kWeights[5] = float[](0.2270270270, 0.1945945946, 0.1216216216, 0.0540540541, 0.0162162162);

void main() {
  vec2 uv = gl_FragCoord.xy * u_targetTexel;
  vec3 sum = texture(u_image, uv).rgb * kWeights[0];
  for (int i = 1; i < 5; ++i) {
    sum += texture(u_image, uv + u_step * float(i)).rgb * kWeights[i];
    sum += texture(u_image, uv - u_step * float(i)).rgb * kWeights[i];
  }
  outColor = vec4(sum, 1.0);
}
