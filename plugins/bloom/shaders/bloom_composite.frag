#version 450 core
// Bloom, step 3: the blurred bright image added to the HDR image,
// upsampled bilinearly when it is smaller. With u_hasHdr = 0 the pass blends
// additively into the target it loads and writes only the bloom.
in vec2 v_uv;
layout(binding = 0) uniform sampler2D u_hdr;
layout(binding = 1) uniform sampler2D u_bloom;
uniform int u_hasHdr;
uniform float u_intensity;
layout(location = 0) out vec4 outColor;

void main() {
  vec3 bloom = texture(u_bloom, v_uv).rgb * u_intensity;
  vec3 base = vec3(0.0);
  float alpha = 1.0;
  if (u_hasHdr != 0) {
    vec4 hdr = texelFetch(u_hdr, ivec2(gl_FragCoord.xy), 0);
    base = hdr.rgb;
    alpha = hdr.a;
  }
  outColor = vec4(base + bloom, alpha);
}
