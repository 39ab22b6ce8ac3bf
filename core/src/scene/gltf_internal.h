// Internal to the glTF loader: one GltfLoader per load, its member functions
// split by subject over three files:
//   gltf_loader.cpp     bytes -> tinygltf model (nesting bound, file access),
//                       node traversal, cameras, conversion;
//   gltf_geometry.cpp   accessors, buffer views, sparse data, meshes;
//   gltf_materials.cpp  images, textures, materials, lights, value ranges;
//   gltf_animation.cpp  skin influences, morph targets, nodes, skins, animations.
// Every accessor, buffer view, index and texture reference is validated
// before it is read: tinygltf does not check all of them.
#pragma once

#include <tiny_gltf.h>

#include <cstddef>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "../config/json_text.h"
#include "rgraph/scene.h"

namespace rgraph::gltf_detail {

inline constexpr size_t kMaxElements = size_t(1) << 26;          // per accessor
inline constexpr size_t kMaxUnbackedElements = size_t(1) << 24;  // accessors without a buffer view (zeros)
inline constexpr int kMaxImageSide = 16384;
inline constexpr size_t kMaxInstances = size_t(1) << 20;          // per node (EXT_mesh_gpu_instancing)
inline constexpr size_t kMaxAnimationValues = size_t(1) << 27;    // key times and values over all animations

std::string trimmed(std::string s);

// Decodes any stb_image format to RGBA8 into `image` (gltf_materials.cpp).
bool decodeImage(tinygltf::Image* image, const unsigned char* bytes, size_t size, std::string* err);
// tinygltf's image callback: decodes images given by URI; images stored in
// buffer views are decoded later, after their buffer view has been checked.
bool imageCallback(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int, int,
                   const unsigned char* bytes, int size, void*);

// A TRIANGLE_STRIP or TRIANGLE_FAN index sequence as a triangle list (gltf_geometry.cpp).
std::vector<uint32_t> trianglesFrom(int mode, const std::vector<uint32_t>& sequence);

struct AccessorInfo {
  const unsigned char* data = nullptr;  // first element; nullptr: zeros (no buffer view)
  size_t stride = 0;
  size_t count = 0;
  int componentType = 0;
  int components = 0;
  bool normalized = false;
};

class GltfLoader {
 public:
  GltfLoader(const unsigned char* data, size_t size, std::string name, std::string baseDir)
      : data_(data), size_(size), name_(std::move(name)), baseDir_(std::move(baseDir)) {}

  Scene load();

 private:
  // ------------------------------------------------ gltf_loader.cpp
  [[noreturn]] void fail(const std::string& msg) const;
  void warn(const std::string& msg) const;
  // A value at a JSON pointer of the document: "name:line:col: /pointer: msg"
  // (line and column within the JSON of a .glb are not given: a binary file).
  [[noreturn]] void failAt(const std::string& pointer, const std::string& msg);
  void warnAt(const std::string& pointer, const std::string& msg);
  std::string where(const std::string& pointer);

  void parse();
  void checkAsset();
  void convert();
  glm::mat4 localMatrix(const tinygltf::Node& node, const std::string& what) const;
  void traverse(const std::vector<int>& roots);
  void visitNode(int nodeIndex, const glm::mat4& world);
  void addCamera(int index, const glm::mat4& world, const std::string& what);

  // ------------------------------------------------ gltf_ignored.cpp
  // "<feature> ignored: <instead>", once per feature per file.
  void warnIgnored(const std::string& feature, const std::string& instead);
  // Refuses Draco-compressed primitives by name (before tinygltf parses);
  // warns when they have uncompressed accessors, which are drawn.
  void checkDraco();
  void warnIgnoredFeatures();

  // ------------------------------------------------ gltf_geometry.cpp
  AccessorInfo checkAccessor(int index, const std::string& what, std::initializer_list<int> types,
                             std::initializer_list<int> componentTypes) const;
  std::string checkBufferView(int index, const std::string& what) const;
  // firstNonFinite (when given, SIZE_MAX on entry): set to the first element
  // holding a NaN or infinity (read as 0).
  std::vector<float> readFloats(int index, const std::string& what, std::initializer_list<int> types,
                                std::initializer_list<int> componentTypes, size_t* firstNonFinite = nullptr) const;
  void applySparse(const tinygltf::Accessor& acc, const std::string& name, const AccessorInfo& info,
                   std::vector<float>& out, size_t* firstNonFinite = nullptr) const;
  std::vector<uint32_t> readIndices(int index, const std::string& what, size_t vertexCount) const;
  int sceneMesh(int mi, size_t pi);
  void checkAttributeTypes(const tinygltf::Primitive& prim, const std::string& pointer);
  // `pointer`: the primitive's JSON pointer, for located refusals.
  MeshData buildMesh(const tinygltf::Primitive& prim, const std::string& what, const std::string& pointer);
  std::optional<std::vector<glm::mat4>> nodeInstances(int nodeIndex, const tinygltf::Node& node);

  // ------------------------------------------------ gltf_animation.cpp
  // JOINTS_n/WEIGHTS_n and morph targets of a primitive into `mesh` (its
  // positions read): before anything reorders vertices.
  void readSkinAttributes(const tinygltf::Primitive& prim, MeshData& mesh, const std::string& what, const std::string& pointer);
  void readMorphTargets(const tinygltf::Primitive& prim, MeshData& mesh, const std::string& what, const std::string& pointer);
  // A float accessor whose every value must be finite (refused at `pointer`, naming the element).
  std::vector<float> readFinite(int index, const std::string& pointer, const std::string& what, std::initializer_list<int> types,
                                std::initializer_list<int> componentTypes);
  // Whether the file needs its node table (animations, skins, morph targets).
  bool keepsNodes() const;
  // Scene::animation from the file's nodes, skins and animations (after traverse).
  void loadAnimationData();
  void loadNodes(SceneAnimation& out);
  void loadSkins(SceneAnimation& out);
  void checkSkinnedMeshes(const SceneAnimation& anim);
  void loadAnimation(size_t index, SceneAnimation& out);

  // ------------------------------------------------ gltf_materials.cpp
  const std::vector<uint8_t>& decodedPixels(int gltfImage, const std::string& what);
  int sceneImage(int gltfImage, bool srgb, const std::string& what);
  TextureRef textureRef(int gltfTexture, int texCoord, bool srgb, const std::string& what);
  // KHR_texture_transform of a textureInfo onto `ref`; `pointer`: the textureInfo's JSON pointer.
  void textureTransform(TextureRef& ref, const tinygltf::ExtensionMap& extensions, const std::string& pointer);
  Material convertMaterial(size_t index);
  int defaultMaterial();
  void addLight(int index, const glm::mat4& world, const std::string& what);
  void spotCone(const tinygltf::Light& l, const std::string& ptr, const glm::mat4& world, PointLight& p);
  // Range checks (refusals name the JSON pointer): a number in [lo, hi]; an
  // array of N numbers each in [lo, hi].
  float checkedNumber(double v, float lo, float hi, const std::string& pointer);
  template <size_t N>
  glm::vec<N, float> checkedFactor(const std::vector<double>& v, float lo, float hi, const std::string& pointer);
  // Fills out's KHR_materials_specular fields and its Blinn-Phong specular.
  void specularFromExtension(const tinygltf::Value& ext, const std::string& pointer, const std::string& what,
                             Material& out);

  // ------------------------------------------------ state
  const unsigned char* data_;
  size_t size_;
  std::string name_;
  std::string baseDir_;
  bool binary_ = false;
  std::string_view json_;                               // the JSON text (.gltf) or chunk (.glb)
  std::optional<config_detail::JsonLocator> locator_;  // positions in json_, on first use
  tinygltf::Model model_;
  std::string tinyWarn_;
  std::string imageWarn_;  // tinygltf's warnings about images it could not read (not logged)
  mutable std::vector<std::string> warnings_;  // every warning given, for Scene::warnings
  std::set<std::string> ignoredFeatures_;      // warned about by warnIgnored
  Scene scene_;
  std::map<std::pair<int, bool>, int> imageMap_;
  std::map<std::pair<int, bool>, int> textureMap_;
  std::map<std::pair<int, size_t>, int> meshMap_;
  std::vector<int> primMaterial_;  // per scene mesh: its material
  int resolvedMaterial_ = -1;
  int defaultMaterial_ = -1;
  bool cameraHasFar_ = false;
  bool keepNodes_ = false;  // keepsNodes(), decided before traverse
  size_t animationValues_ = 0;  // floats read into animation samplers so far
};

}  // namespace rgraph::gltf_detail
