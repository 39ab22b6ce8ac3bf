// Per-layer views of a layered draw (GpuScene::drawLayered; std140, uniform
// buffer 1): instance i of each draw writes layer u_layerBase.x + i with
// u_layerViewProj[i]. Keep in sync with core/src/gl/frame_block.h
// (LayerViewsBlock, kLayerViewsPerBlock).
layout(std140, binding = 1) uniform LayerViews {
  ivec4 u_layerBase;            // x: the layer instance 0 writes
  mat4 u_layerViewProj[32];     // each instance's view-projection
};
