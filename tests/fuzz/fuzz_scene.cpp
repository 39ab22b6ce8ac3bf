// Fuzz target: scene file text -> a Scene or a RuntimeError naming the file
// (rgraph::parseSceneText, what `--scene x.json` runs). Model references
// resolve against a private directory that holds only two small models,
// model.glb and model.gltf (tests/fuzz/corpus/gltf/embedded-everything.*), so
// scenes can place real models without reading anything else from disk.
//
// Beyond "no crash, no sanitizer report": only RuntimeError may leave the
// loader, its message names the file, a loaded scene passes validate(), and
// every number the renderer reads is finite (scene_checks.h).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "fuzz_util.h"
#include "scene_checks.h"
#include "rgraph/error.h"
#include "rgraph/pass.h"
#include "rgraph/scene.h"

namespace {
constexpr const char* kFile = "fuzz-scene.json";
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  rgraph::fuzz::quietLogs();
  const std::filesystem::path dir = rgraph::fuzz::privateBaseDir();
  const std::filesystem::path models = RGRAPH_FUZZ_SCENE_MODELS;
  for (const char* ext : {".glb", ".gltf"}) {
    std::error_code ec;
    std::filesystem::copy_file(models / (std::string("embedded-everything") + ext), dir / (std::string("model") + ext),
                               ec);
    if (ec) rgraph::fuzz::fail("cannot copy the scene target's model" + std::string(ext) + ": " + ec.message());
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  rgraph::Scene scene;
  if (!rgraph::fuzz::loadNamingTheFile(kFile, scene, [&] {
        return rgraph::parseSceneText(text, kFile, rgraph::fuzz::privateBaseDir());
      }))
    return 0;
  if (const std::string why = rgraph::fuzz::nonFiniteValue(scene); !why.empty())
    rgraph::fuzz::fail("a loaded scene holds a number the renderer cannot use: " + why);
  if (rgraph::fuzz::verbose())
    std::fprintf(stderr, "loaded: %zu primitives, %zu point and %zu directional lights\n", scene.primitives.size(),
                 scene.pointLights.size(), scene.directionalLights.size());
  // What the renderer asks of every scene before drawing it.
  (void)rgraph::sceneFeatures(scene);
  (void)scene.bounds();
  (void)scene.camera.viewProjection(1.0f);
  return 0;
}
