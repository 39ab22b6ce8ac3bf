// Per-layer views of a layered draw (GpuScene::drawLayered; std140, uniform
// buffer 1): view i of each draw writes layer u_layerBase.x + i with
// u_layerViewProj[i]; GL instance k draws view k % u_layerBase.y (of scene
// instance k / u_layerBase.y, for EXT_mesh_gpu_instancing primitives). Keep in sync with core/src/gl/frame_block.h
// (LayerViewsBlock, kLayerViewsPerBlock).
layout(std140, binding = 1) uniform LayerViews {
  ivec4 u_layerBase;            // x: the layer view 0 writes; y: the views in this block
  mat4 u_layerViewProj[32];     // each instance's view-projection
};
