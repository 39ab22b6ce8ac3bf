// Fuzz target: glTF bytes (.gltf JSON or .glb binary) -> a Scene or a
// RuntimeError naming the file (rgraph::loadGltfFromMemory, what loadGltf
// runs on a file's contents). External URIs resolve against an empty
// directory, so only data: URIs and the GLB chunk provide buffers and images.
//
// Beyond "no crash, no sanitizer report": only RuntimeError may leave the
// loader, its message names the file, a loaded scene passes validate(), and
// every number the renderer reads is finite (scene_checks.h).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "fuzz_util.h"
#include "scene_checks.h"
#include "rgraph/error.h"
#include "rgraph/pass.h"
#include "rgraph/scene.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rgraph::fuzz::quietLogs();
  (void)rgraph::fuzz::privateBaseDir();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  // The name only labels messages; the loader tells the formats apart by content.
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string name = binary ? "fuzz-model.glb" : "fuzz-model.gltf";
  rgraph::Scene scene;
  if (!rgraph::fuzz::loadNamingTheFile(name, scene, [&] {
        return rgraph::loadGltfFromMemory(data, size, name, rgraph::fuzz::privateBaseDir());
      }))
    return 0;
  if (rgraph::fuzz::verbose())
    std::fprintf(stderr, "loaded: %zu primitives, %zu materials, %zu images, %zu point and %zu directional lights\n",
                 scene.primitives.size(), scene.materials.size(), scene.images.size(), scene.pointLights.size(),
                 scene.directionalLights.size());
  // What loadSceneAny does next with a model (a camera framing it, a light).
  rgraph::applySceneDefaults(scene);
  if (const std::string why = rgraph::fuzz::nonFiniteValue(scene); !why.empty())
    rgraph::fuzz::fail("a loaded scene holds a number the renderer cannot use: " + why);
  (void)rgraph::sceneFeatures(scene);
  (void)scene.camera.viewProjection(1.0f);
  return 0;
}
