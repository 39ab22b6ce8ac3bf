#version 450 core
// Half-size "ambient visibility" for the ssao_upsample oracle
// (tests/plugin/plugin_oracle_ssao_upsample_test.cpp): per texel, the
// G-buffer texel ssao.frag would read for it at half size (2x + 1, 2y + 1)
// decides: 1 where nothing was drawn, u_color.x where its world z is above
// u_value (the near plane), u_color.y elsewhere (the far one).
layout(binding = 0) uniform sampler2D input0;  // G-buffer world position, w 1 where covered
uniform vec4 u_color;
uniform float u_value;
layout(location = 0) out vec4 outColor;

void main() {
  vec4 p = texelFetch(input0, ivec2(gl_FragCoord.xy * 2.0), 0);
  float ao = p.w <= 0.5 ? 1.0 : (p.z > u_value ? u_color.x : u_color.y);
  outColor = vec4(ao, 0.0, 0.0, 1.0);
}
