#version 450 core
// A triangle covering the viewport, from gl_VertexID alone (draw 3 vertices,
// empty VAO). v_uv is 0..1 over the viewport, (0,0) at the bottom left.
out vec2 v_uv;

void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));  // (0,0) (2,0) (0,2)
  v_uv = p;
  gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
