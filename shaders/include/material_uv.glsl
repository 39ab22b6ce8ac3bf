// Where a material texture is sampled: per texture unit, its UV set
// (glTF texCoord 0 or 1; scene.vert's vs_uv1 is the second) under its
// KHR_texture_transform matrix (offset * rotation * scale, column-major 3x2:
// identity without the extension). GpuScene::bindMaterial sets both per draw
// for units 0..12 (GpuScene::kMaterialTextureUnits; 5..10 are the lighting
// passes' and unused here, 11 and 12 KHR_materials_specular's).
// Sample unit U's texture at textureUv(U, fs.uv), never at fs.uv itself.
uniform mat3x2 u_uvTransform[13];
uniform int u_uvSet[13];

in vec2 vs_uv1;

vec2 textureUv(int unit, vec2 uv0) {
  vec2 uv = u_uvSet[unit] == 1 ? vs_uv1 : uv0;
  return u_uvTransform[unit] * vec3(uv, 1.0);
}
