// Included by include_ok.frag.
vec4 halfOf(vec4 c) { return c * 0.5; }
