// RenderScene's state (rgraph/renderer.h), shared by its two source files:
// render_scene.cpp (loading, lights, the upload) and
// render_scene_instances.cpp (objects, meshes and materials made in code).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/renderer.h"

namespace rgraph {

struct RenderScene::Impl {
  Scene scene;
  std::unique_ptr<GpuScene> gpu;
  uint64_t uploads = 0;
  uint64_t lightsVersion = 0;
  uint64_t environmentVersion = 0;

  // Objects: ids[i] is scene.primitives[i]'s, hidden[i] whether it is hidden
  // (given to the GpuScene when it is made); indexOf maps an id to i.
  std::vector<uint64_t> ids;
  std::vector<bool> hidden;
  std::unordered_map<uint64_t, size_t> indexOf;
  uint64_t nextId = 1;
  uint64_t instancesVersion = 0;
  // Materials that setMaterialParameters gave an object of its own, by
  // object id, and those of removed objects, reused before the scene grows.
  std::unordered_map<uint64_t, size_t> ownMaterial;
  std::vector<size_t> freeMaterials;

  // Animation (render_scene_animation.cpp): the pose of the last setTime
  // (evaluated at rest until then) and each node's world matrix as last
  // given to its objects; the objects' bounds at the pose.
  Pose pose;
  double time = 0.0;
  std::vector<glm::mat4> givenWorld;
  PosedBounds posedBounds;
  // Poses the scene (setTime's work, kRestPose from fromScene).
  void applyPose(double seconds, int animation);

  std::string where() const { return scene.source.empty() ? std::string("scene") : scene.source; }
  void lightsEdited() {
    ++lightsVersion;
    if (gpu) gpu->lightsChanged();
  }
  void checkIndex(size_t index, const char* what) const {
    if (index >= scene.pointLights.size())
      throw RuntimeError(std::string("RenderScene::") + what + ": no point light " + std::to_string(index) + " (the scene has " +
                         std::to_string(scene.pointLights.size()) + ")");
  }
  // Gives every primitive an id (fromScene).
  void numberPrimitives();
  // The primitive index of `id`, or RuntimeError "RenderScene::<call>: no instance 7 ...".
  size_t find(InstanceId id, const char* call) const;
  // "instance 7 ('crate')" (the name left out when empty).
  std::string describe(size_t primitive) const;
};

}  // namespace rgraph
