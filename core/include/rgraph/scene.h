// CPU-side scenes: geometry, materials, textures, lights and a camera, ready
// to upload. No GL include; GL enum values (wrap modes, filters) travel as the
// plain integers glTF uses, which are the GL values.
//
// Layout, chosen for upload:
//   Scene::meshes      geometry in its own local space, one per glTF primitive
//                      (separate attribute arrays, uint32 indices, CCW triangles);
//   Scene::primitives  draws: a mesh, a material and a world transform (node
//                      hierarchy flattened). Several draws may share a mesh;
//   Scene::materials   PBR metallic-roughness + a Blinn-Phong specular intensity;
//   Scene::textures    an image + a sampler; Scene::images decoded RGBA8 pixels
//                      (one image per colour space: an sRGB and a linear use of
//                      the same glTF image are two images);
//   lights, ambient term, camera;
//   Scene::animation   glTF nodes, skins and animations of animated files
//                      (rgraph/animation.h evaluates them; empty otherwise).
//
// Units: lengths in scene units, angles in degrees unless named otherwise.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "rgraph/animation.h"

namespace rgraph {

// ---------------------------------------------------------------- bounds

struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  bool empty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
  void expand(const glm::vec3& p);
  void expand(const Bounds& b);
  glm::vec3 center() const { return empty() ? glm::vec3(0.0f) : (min + max) * 0.5f; }
  glm::vec3 size() const { return empty() ? glm::vec3(0.0f) : max - min; }
  float radius() const { return empty() ? 0.0f : glm::length(max - min) * 0.5f; }
  // The box around the 8 transformed corners.
  Bounds transformed(const glm::mat4& m) const;
};

// Largest world-space coordinate a scene may use. Rendering is float math:
// beyond this the camera framing a scene (its distance times its near and far
// planes) overflows to infinity and the frame comes out empty, with no error.
// Float precision gave out long before: 1e15 units is far beyond any real scene.
inline constexpr float kMaxWorldCoordinate = 1e15f;

// ---------------------------------------------------------------- geometry

// One vertex of the interleaved layout (48 bytes): position, normal, uv0, tangent.
struct MeshVertex {
  glm::vec3 position;
  glm::vec3 normal;
  glm::vec2 uv;
  glm::vec4 tangent;  // (0,0,0,1) when the mesh has no tangents
};
static_assert(sizeof(MeshVertex) == 48, "MeshVertex must stay tightly packed");

// Triangle-list geometry in local space. Invariants (checked by valid()):
// positions, normals and uv0 have the same size; tangents, uv1 and colors are
// empty or that size too; indices.size() % 3 == 0 and every index < vertexCount().
// Triangles are counter-clockwise seen from their front side.
struct MeshData {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // unit length
  std::vector<glm::vec2> uv0;       // zeros when the source had none (hasUv0 false)
  std::vector<glm::vec2> uv1;       // empty unless the source had TEXCOORD_1
  std::vector<glm::vec4> colors;    // empty unless the source had COLOR_0: linear RGBA multiplying the
                                    // base colour (RGB sources get alpha 1)
  std::vector<glm::vec4> tangents;  // empty unless a material using the mesh has a normal map;
                                    // xyz unit, orthogonal to the normal; w = +-1 handedness
                                    // (bitangent = w * cross(normal, tangent.xyz))
  std::vector<uint32_t> indices;
  bool hasUv0 = false;
  Bounds bounds;                    // local space; see updateBounds()
  // Skinning and morphing (rgraph/animation.h): glTF JOINTS_n/WEIGHTS_n sets
  // of 4 influences, and morph targets; each array empty or one per vertex.
  // Bounds are the rest positions'.
  std::vector<SkinInfluences> influences;
  std::vector<MorphTarget> morphTargets;

  size_t vertexCount() const { return positions.size(); }
  size_t triangleCount() const { return indices.size() / 3; }
  bool hasTangents() const { return !tangents.empty(); }
  bool hasColors() const { return !colors.empty(); }
  bool hasUv1() const { return !uv1.empty(); }
  bool skinned() const { return !influences.empty(); }
  void updateBounds();
  // Checks the invariants above; on failure writes the reason to *why.
  bool valid(std::string* why = nullptr) const;
  // The interleaved form of the attributes (same vertex order as the arrays).
  std::vector<MeshVertex> interleaved() const;
};

// Per-vertex tangents from the UV layout: per-triangle accumulation, then
// Gram-Schmidt against the normal, handedness in w. Vertices without a usable
// UV gradient get an arbitrary unit tangent orthogonal to the normal.
void generateTangents(MeshData& mesh);
// Smooth normals: area-weighted average of the faces sharing each vertex.
void computeSmoothNormals(MeshData& mesh);
// Flat normals: unwelds the mesh (3 vertices per triangle) and gives each
// triangle its face normal (what glTF asks for when NORMAL is missing).
void computeFlatNormals(MeshData& mesh);

// Procedural meshes (with normals and uv0, no tangents: call generateTangents()).
MeshData makeCube(float halfExtent = 1.0f);  // 24 vertices, per-face normals, 12 triangles
MeshData makeUvSphere(float radius = 1.0f, int segments = 32, int rings = 16);
MeshData makePlane(float halfSizeX = 1.0f, float halfSizeZ = 1.0f, float uvScale = 1.0f);  // y = 0, facing +Y
// A closed unit icosphere (the light_volumes pass draws point lights with it): shared vertices (every edge used
// by exactly two triangles), outward CCW winding, normals = positions.
// subdivisions 0 gives the icosahedron (12 vertices, 20 triangles); each level
// multiplies the triangle count by 4. Valid range 0..7.
MeshData makeIcosphere(int subdivisions);
// (The spot-light volume, makeSpotVolume, is the light_volumes pass's:
// rgraph/passes/light_volume_meshes.h.)

// ---------------------------------------------------------------- materials and textures

enum class AlphaMode : uint8_t { opaque, mask, blend };
const char* alphaModeName(AlphaMode m);

// glTF sampler values (= GL enums).
struct SamplerDesc {
  static constexpr int kNearest = 9728, kLinear = 9729, kNearestMipmapNearest = 9984,
                       kLinearMipmapNearest = 9985, kNearestMipmapLinear = 9986,
                       kLinearMipmapLinear = 9987;
  static constexpr int kRepeat = 10497, kClampToEdge = 33071, kMirroredRepeat = 33648;
  int wrapS = kRepeat;
  int wrapT = kRepeat;
  int minFilter = kLinearMipmapLinear;  // glTF leaves it to the renderer when unset: we pick trilinear
  int magFilter = kLinear;
  bool usesMipmaps() const;
  bool operator==(const SamplerDesc&) const = default;
};

// Decoded pixels: RGBA8, rows top to bottom as stored in the file
// (uploading to GL as-is puts the first row at v = 0, which is what glTF UVs expect).
struct ImageData {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // width * height * 4
  bool srgb = false;          // base colour and emissive textures; upload as SRGB8_ALPHA8
};

struct SceneTexture {
  int image = -1;  // index into Scene::images
  SamplerDesc sampler;
};

struct TextureRef {
  int texture = -1;  // index into Scene::textures; -1: none
  int texCoord = 0;  // 0: uv0, 1: uv1 (a mesh without uv1 samples uv0)
  // KHR_texture_transform, applied to the UV set's coordinates: scaled, then
  // rotated by `rotation` radians (counter-clockwise in UV space, as the
  // extension defines it), then offset.
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;
  glm::vec2 scale{1.0f};
  bool valid() const { return texture >= 0; }
  // uv' = uvTransform() * (uv, 1): the extension's translation * rotation * scale
  // (column-major, 3 columns of 2 rows: x axis, y axis, offset).
  glm::mat3x2 uvTransform() const;
};

struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};
  float metallicFactor = 1.0f;
  float roughnessFactor = 1.0f;
  glm::vec3 emissiveFactor{0.0f};  // includes KHR_materials_emissive_strength
  TextureRef baseColorTexture;          // sRGB, alpha = coverage
  TextureRef metallicRoughnessTexture;  // linear: G roughness, B metallic
  TextureRef normalTexture;             // linear, tangent space
  TextureRef occlusionTexture;          // linear, R
  TextureRef emissiveTexture;           // sRGB
  // KHR_materials_specular, as the extension defines it for the PBR model:
  // dielectric F0 = min(0.04 * specularColorFactor * specularColorTexture.rgb, 1)
  //                 * specularFactor * specularTexture.a, F90 = specularFactor * specularTexture.a.
  glm::vec3 specularColorFactor{1.0f};
  float specularFactor = 1.0f;
  TextureRef specularTexture;       // linear, A
  TextureRef specularColorTexture;  // sRGB, RGB
  // KHR_materials_unlit: drawn as its base colour, no light (the lighting
  // passes see emissive = base colour, albedo 0, no specular).
  bool unlit = false;
  float normalScale = 1.0f;
  float occlusionStrength = 1.0f;
  AlphaMode alphaMode = AlphaMode::opaque;
  float alphaCutoff = 0.5f;  // used by AlphaMode::mask
  bool doubleSided = false;
  // Blinn-Phong specular intensity for the LearnOpenGL lighting model (the
  // G-buffer's albedo alpha). Not part of glTF: 0.5 unless a scene sets it.
  float specular = 0.5f;

  bool hasNormalMap() const { return normalTexture.valid(); }
  // Every texture it may sample (valid or not), for whatever treats them alike.
  std::array<const TextureRef*, 7> textures() const {
    return {&baseColorTexture, &metallicRoughnessTexture, &normalTexture, &occlusionTexture,
            &emissiveTexture,  &specularTexture,          &specularColorTexture};
  }
  // Light of its own: an emissive factor above zero, or unlit.
  bool emits() const { return unlit || emissiveFactor != glm::vec3(0.0f); }
  // Reflectance other than the PBR default (F0 0.04, F90 1): KHR_materials_specular
  // factors or textures, or unlit (no reflection at all).
  bool nonDefaultReflectance() const {
    return unlit || specularFactor != 1.0f || specularColorFactor != glm::vec3(1.0f) || specularTexture.valid() ||
           specularColorTexture.valid();
  }
  // Whether some texture samples the second UV set (texCoord 1).
  bool usesUv1() const;
};

// ---------------------------------------------------------------- draws

struct Primitive {
  int mesh = -1;      // index into Scene::meshes
  int material = -1;  // index into Scene::materials (always valid in a loaded scene)
  glm::mat4 transform{1.0f};  // local -> world
  Bounds bounds;              // world space
  std::string name;           // node name, for diagnostics
  // EXT_mesh_gpu_instancing: the mesh is drawn once per entry, with world
  // transform `transform * instances[i]` (one instanced draw; `bounds` cover
  // them all). Empty: one instance, `transform` alone.
  std::vector<glm::mat4> instances;
  // Whether shadow-map views draw it (GpuScene::Filter::shadowCasters):
  // scene files' "cast_shadows". Unset: Scene::castsShadows's default (every
  // primitive but those of a blend material: a glass pane lets light through).
  std::optional<bool> castShadows;

  // A constant rotation over time (scene files' "spin"): `degreesPerSecond`
  // about the world-space `axis` (unit) through the world point `pivot` (the
  // model's origin), applied after `transform`. 0 degrees per second: static.
  struct Spin {
    glm::vec3 pivot{0.0f};
    glm::vec3 axis{0.0f, 1.0f, 0.0f};
    float degreesPerSecond = 0.0f;
  } spin;

  // The glTF node that draws it, in Scene::animation.nodes (-1: none kept, a
  // static scene): its pose gives the primitive's matrix, skin and morph
  // weights at a time (rgraph/animation.h). `transform` is that node's rest
  // world matrix, what is drawn until the renderer plays animations.
  int node = -1;

  // World bounds of a mesh with local bounds `local` drawn by this primitive:
  // `local` under `transform`, over every instance.
  Bounds worldBounds(const Bounds& local) const;

  glm::mat3 normalMatrix() const { return glm::transpose(glm::inverse(glm::mat3(transform))); }
  // A negative determinant flips the winding: draw with the front face reversed.
  bool mirrored() const { return glm::determinant(glm::mat3(transform)) < 0.0f; }
  bool animated() const { return spin.degreesPerSecond != 0.0f; }
  // local -> world at `seconds` of animation time: `transform` turned by the
  // spin (`transform` itself when static). Bounds stay the static ones.
  glm::mat4 transformAt(double seconds) const;
};

// ---------------------------------------------------------------- lights and camera

// The most lights a scene may have (point and directional together): the
// many-lights:N limit, and what scene files and glTF models are held to.
inline constexpr size_t kMaxSceneLights = 100000;

// Default brightness threshold for light volumes (LearnOpenGL: 5/256).
inline constexpr float kLightThreshold = 5.0f / 256.0f;

struct DirectionalLight {
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit; the direction the light travels (shaders use -direction)
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  // Whether a shadow pipeline gives it a shadow map (scene files' "shadows";
  // a sun casts by default, glTF's directional lights too).
  bool castShadows = true;
};

// Radiance at distance d: color * intensity / (constant + linear d + quadratic d^2),
// zero beyond radius; a spot light also times its cone's falloff (below).
struct PointLight {
  glm::vec3 position{0.0f};
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float constant = 1.0f;
  float linear = 0.7f;
  float quadratic = 1.8f;
  float radius = 0.0f;  // light-volume radius; lightRadius(*this) unless the source gave one

  // A spot light (spot = true) lights only the cone of half-angle outerConeDeg
  // about `direction`: fully within innerConeDeg, with glTF KHR_lights_punctual's
  // angular falloff between (the square of a ramp linear in the cosine). Its
  // reach along the cone is `radius`, the same cut-off rule as a point light's.
  // Valid values (validatePointLight): 0 <= innerConeDeg < outerConeDeg <= 90.
  bool spot = false;
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // unit: where the cone points (world)
  float innerConeDeg = 0.0f;               // glTF's default 0
  float outerConeDeg = 45.0f;              // glTF's default pi/4

  // Whether a shadow pipeline gives it a shadow map (scene files' "shadows").
  // Unset: spot lights cast and point lights do not (a point light's shadow
  // is six maps: asked for, not assumed), glTF's lights likewise.
  std::optional<bool> castShadows;
  bool castsShadows() const { return castShadows.value_or(spot); }

  // Whether the forward pass may draw a marker at it (a small cube in its
  // colour, LearnOpenGL's light boxes): scene files' lights, yes; a glTF
  // file's own lights, no (the model draws its lamps; a cube would hide them).
  bool marker = true;
};

// Distance at which the light falls to `threshold`: solves
// constant + linear d + quadratic d^2 = max(color.r, color.g, color.b) * intensity / threshold.
// quadratic == 0: the linear solution. quadratic == 0 and linear == 0 (no falloff):
// +infinity (callers cap it, e.g. to the scene's bounds). 0 when the light never
// reaches the threshold. Negative coefficients are treated as 0.
float lightRadius(const PointLight& light, float threshold = kLightThreshold);

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f, 0.0f, 0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fovY = 45.0f;  // vertical, degrees
  float near = 0.1f;
  float far = 100.0f;

  glm::vec3 forward() const;  // unit, position -> target
  // `up`, unless it is (nearly) parallel to the view direction, where lookAt
  // has no orientation: then +Y, or -Z when looking along Y. Loaders warn when
  // they replace a source's up with it.
  glm::vec3 validUp() const;
  glm::mat4 view() const;     // glm::lookAt (right-handed, looks down -Z), with validUp()
  glm::mat4 projection(float aspect) const;  // glm::perspective, GL clip space (-1..1 depth)
  glm::mat4 viewProjection(float aspect) const { return projection(aspect) * view(); }
};

// A camera with the given vertical fov that sees all of `bounds`, looking at
// its centre from the +Z side and slightly above.
Camera frameBounds(const Bounds& bounds, float fovY = 45.0f);
// The same for a sphere: it fills the vertical field of view (the short side
// of a landscape frame) with a 5% margin.
Camera frameSphere(const glm::vec3& center, float radius, float fovY = 45.0f);
struct Scene;
// The default camera of a scene without one: looking at the centre of its
// bounds from the same direction as frameBounds, as close as keeps every
// vertex within 95% of the vertical field of view and of a square's width:
// the model's larger extent fills the short side of any landscape frame.
Camera frameScene(const Scene& scene, float fovY = 45.0f);
// The camera turned `degrees` about the axis through its target along its
// up vector (validUp()): position moves, target and up stay. `rgraph render
// --orbit D` shows frame i with orbitCamera(camera, D * i).
Camera orbitCamera(const Camera& camera, float degrees);

// ---------------------------------------------------------------- environment

// Light from every direction at infinity, for image-based lighting (the PBR
// pipelines' IBL passes pre-filter it; docs/ibl.md). Radiance in a world
// direction d (unit) is environmentRadiance(env, d); the passes' shaders
// compute the same function (shaders/include/environment.glsl).
struct Environment {
  enum class Kind { uniform, sky, hdr };
  Kind kind = Kind::uniform;
  float intensity = 1.0f;           // scales every kind's radiance (>= 0)
  glm::vec3 color{1.0f};            // uniform: the radiance everywhere (>= 0)
  // sky: a gradient from `horizon` to `zenith` above the horizon, `ground`
  // below it, and a sun: a disc of angular radius sunRadiusDeg around
  // sunDirection (unit, towards the sun) of radiance sunColor, its edge
  // smoothed over its outer fifth.
  glm::vec3 sunDirection{0.3f, 0.8f, 0.5f};
  glm::vec3 sunColor{1000.0f};
  float sunRadiusDeg = 2.0f;
  glm::vec3 zenith{0.25f, 0.45f, 0.9f}, horizon{0.9f, 0.9f, 1.0f}, ground{0.3f, 0.28f, 0.25f};
  // hdr: an equirectangular image (longitude along x from -z turning towards
  // +x, +y up at the top row), RGB floats, rows top-down.
  std::string file;
  uint32_t width = 0, height = 0;
  std::vector<float> rgb;
  bool operator==(const Environment&) const = default;
};

// The radiance of `env` towards world direction `d` (unit): what the
// environment pass writes into its cube map (the hdr kind sampled nearest).
glm::vec3 environmentRadiance(const Environment& env, const glm::vec3& d);
// Loads an equirectangular Radiance .hdr file (stb_image) into env.rgb,
// width and height; throws RuntimeError naming the file and stb's reason.
void loadEnvironmentHdr(Environment& env, const std::string& path);
// "sky", "color:R,G,B" or an .hdr file: the environment `rgraph render
// --environment` gives a scene. Throws RuntimeError naming the value.
Environment environmentFromSpec(const std::string& spec);

// ---------------------------------------------------------------- scene

struct Scene {
  std::string source;  // file or procedural spec it came from
  std::vector<MeshData> meshes;
  std::vector<Primitive> primitives;
  std::vector<Material> materials;
  std::vector<SceneTexture> textures;
  std::vector<ImageData> images;
  std::vector<DirectionalLight> directionalLights;
  std::vector<PointLight> pointLights;
  // Ambient light; the lighting pass adds albedo * ambient (LearnOpenGL: 0.1).
  glm::vec3 ambient{0.1f};
  Camera camera;
  bool hasCamera = false;  // false: `camera` is the default, not from the source
  // Image-based lighting (scene file key "environment"); none: the PBR
  // pipelines' IBL passes are culled and ambient is the constant above.
  std::optional<Environment> environment;
  // glTF nodes, skins and animations (rgraph/animation.h): empty unless a
  // loaded file has animations, skins or morph targets.
  SceneAnimation animation;
  // What the loaders warned about (also logged as spdlog warnings), in order:
  // features of the source that are not drawn and what is drawn instead
  // ("skins not applied: drawn in bind pose"), values replaced. `rgraph plan
  // --scene` lists them.
  std::vector<std::string> warnings;

  // Queries, so that a pipeline models no more than the scene needs. Material
  // queries look only at materials used by some primitive.
  bool hasPointLights() const { return !pointLights.empty(); }
  bool hasDirectionalLights() const { return !directionalLights.empty(); }
  bool hasBlendMaterials() const;
  bool hasMaskMaterials() const;
  bool hasNormalMaps() const;
  bool hasTextures() const;
  // Some drawn mesh has COLOR_0 vertex colours.
  bool hasVertexColors() const;
  // Some primitive is drawn as several instances (EXT_mesh_gpu_instancing).
  bool hasInstancing() const;
  // Any used material with a metallic-roughness texture, or metallic/roughness
  // factors that differ between used materials.
  bool hasMetallicRoughnessVariation() const;
  // Whether `p` is drawn into shadow maps: its castShadows, else true unless
  // its material blends.
  bool castsShadows(const Primitive& p) const;
  bool hasShadowCasters() const;         // some primitive casts
  bool hasShadowCastingLights() const;   // some light casts (castsShadows / castShadows)
  size_t triangleCount() const;  // over primitives (a shared mesh counts per draw, and per instance)
  size_t vertexCount() const;    // over primitives (likewise)
  Bounds bounds() const;         // world space, over primitives
  // The sphere the default camera frames: centred on bounds()'s centre,
  // reaching the farthest vertex a primitive draws (world space; an instanced
  // primitive: its mesh box's corners under each instance). Tighter than
  // bounds().radius() (half the box's diagonal) for all but box-shaped
  // scenes: a round model's box diagonal is sqrt(3) times its radius.
  struct Sphere {
    glm::vec3 center{0.0f};
    float radius = 0.0f;
  };
  Sphere boundingSphere() const;
  // Throws RuntimeError when an index is out of range, a mesh breaks its
  // invariants, or a number the renderer reads is unusable: world-space
  // geometry or a point light beyond kMaxWorldCoordinate, a non-finite light
  // value (an infinite radius aside), a camera whose view-projection is not finite.
  void validate() const;
};

// The valid ranges of lights, the ambient light and the camera, one set for
// scene files, glTF-loaded and procedural scenes and the embedding API
// (scenes/README.md lists them): nullopt when the value is valid, else which
// member breaks them, named by its scene-file key ("intensity", "fov",
// "outer_cone_deg"; "" for a rule over several) and why.
//   point light: position finite within kMaxWorldCoordinate; color and
//     intensity >= 0; constant, linear, quadratic >= 0, not all 0; radius >= 0
//     (or +infinity: no falloff); a spot's direction a unit vector and
//     0 <= inner_cone_deg < outer_cone_deg <= 90
//   directional light: a finite non-zero direction; color, intensity >= 0
//   camera: position and target finite within kMaxWorldCoordinate and apart;
//     a non-zero up; 0 < fov < 180 degrees; 0 < near < far (finite)
//   ambient: finite, >= 0
struct SceneValueProblem {
  std::string key;
  std::string message;
};
std::optional<SceneValueProblem> pointLightProblem(const PointLight& light);
std::optional<SceneValueProblem> directionalLightProblem(const DirectionalLight& light);
std::optional<SceneValueProblem> cameraProblem(const Camera& camera);
std::optional<SceneValueProblem> ambientProblem(const glm::vec3& ambient);

// Those checks (and, for the camera, a finite view-projection), as validate()
// makes them and for edits made after loading (rgraph/renderer.h). Throw
// RuntimeError "<where>: point light <index>: intensity: must be >= 0, got -1"
// and the like.
void validatePointLight(const PointLight& light, size_t index, const std::string& where);
void validateDirectionalLight(const DirectionalLight& light, size_t index, const std::string& where);
void validateCamera(const Camera& camera, const std::string& where);
void validateAmbient(const glm::vec3& ambient, const std::string& where);

struct SceneFeatures;  // rgraph/pass.h
// What this scene needs from a pipeline (point lights, blending, normal maps,
// metallic/roughness variation), for PassTypeDesc::adapt hooks.
SceneFeatures sceneFeatures(const Scene& scene);
// The same seen from `camera` at this aspect (width / height): the shadow
// facts (SceneFeatures::shadowLights) depend on the view. The one-argument
// form uses scene.camera at 16:9.
SceneFeatures sceneFeatures(const Scene& scene, const Camera& camera, float aspect);

// Appends `src` to `dst` under `transform` (primitives, point and directional
// lights, and animation nodes, skins and animations with `transform` above
// src's root nodes; src's camera is taken only when dst has none). Indices are rebased.
void appendScene(Scene& dst, Scene src, const glm::mat4& transform = glm::mat4(1.0f));

// When the scene has no camera: frameScene(scene). When it has no lights at
// all: one directional light from above-front-right (ambient is kept).
void applySceneDefaults(Scene& scene);

// ---------------------------------------------------------------- loading
// Every loader throws rgraph::RuntimeError naming the file and the problem.

// glTF 2.0 (.gltf with external or embedded buffers, .glb). Default scene (or
// all root nodes), triangle primitives (strips and fans turned into triangle
// lists; points and lines skipped with a warning), KHR_mesh_quantization,
// materials, textures, samplers, KHR_lights_punctual (point, spot and
// directional lights), the first perspective camera, KHR_materials_specular (onto Material::specular),
// KHR_materials_emissive_strength. No defaults added: see loadSceneAny.
// Features not drawn get one warning each per file ("skins ignored: drawn in
// bind pose"; the table is in scenes/README.md), kept in Scene::warnings;
// Draco-compressed primitives without uncompressed accessors are refused.
// Values outside the ranges of the glTF schema (metallic 9, a negative light
// intensity, asset version 3.0; the table is in scenes/README.md) are refused
// with file:line:column (.gltf) and the JSON path. JSON nested deeper than 256
// levels is refused before it is parsed; node hierarchies of any depth load.
Scene loadGltf(const std::string& path);
// The same from bytes in memory (what loadGltf reads the file into): .glb when
// the data starts with the magic "glTF", else .gltf JSON text. Messages name
// `nameForMessages`; external buffers and images resolve against `baseDir`
// ("" = the current directory). Throws rgraph::RuntimeError on anything
// malformed, and never crashes on any bytes (it is fuzzed).
Scene loadGltfFromMemory(const unsigned char* data, std::size_t size, const std::string& nameForMessages,
                         const std::string& baseDir);

// Scene file (JSON), documented in scenes/README.md:
// {"models": [{"file": "x.gltf", "transform": {"translation": [..], "rotation_euler_deg": [..],
//   "scale": s | [..]}} | {"shape": "cube"|"sphere"|"plane", "material": {..}, "transform": ..}],
//  "lights": [{"type": "point", ...}, {"type": "spot", ...}, {"type": "directional", ...}], "ambient": s | [..],
//  "camera": {"position": [..], "target": [..], "up": [..], "fov": 45, "near": 0.1, "far": 100}}
// Relative paths resolve against the scene file's folder. Without "camera" one frames the scene; without
// "lights" (and none in the models) applySceneDefaults adds one; radii of lights without falloff are capped
// to reach the whole scene. A "file" model may carry a "material" whose values override the model's.
// Errors read file:line:column: /json/pointer: message. At most kMaxSceneLights lights.
Scene loadSceneFile(const std::string& path);
// The same from text (any bytes: malformed input throws RuntimeError, never crashes; it is fuzzed).
Scene parseSceneText(const std::string& text, const std::string& file, const std::string& baseDir);

// "path.json" -> loadSceneFile; "path.gltf" / "path.glb" -> loadGltf + applySceneDefaults;
// "learnopengl" -> makeLearnOpenGLScene(); "learnopengl:overview" -> the same
// scene seen from above and behind, all 9 objects in view (rgraph render's default);
// "learnopengl:shadows" -> makeLearnOpenGLShadowsScene(); "many-lights:N[:seed]" -> makeManyLightsScene(N, seed);
// "many-lights:N[:seed]:pillars" -> makeManyLightsPillarsScene(N, seed);
// "thin" -> makeThinScene(); "walker" -> makeWalkerScene().
Scene loadSceneAny(const std::string& spec);

// ---------------------------------------------------------------- procedural scenes

// The LearnOpenGL deferred-shading demo: 9 objects (cubes and spheres in a
// checkerboard, edge 1 / diameter 1 = the chapter's 0.5 scale of a [-1,1] model)
// at x,z in {-3,0,3}, y = -0.5, no floor (the chapter has none); 32 point lights
// placed as the chapter's code does (srand(13), rand() reproduced by GlibcRandom),
// constant 1, linear 0.7, quadratic 1.8; camera at (0,0,5) looking down -Z, fov 45,
// near 0.1, far 100; ambient 0.1; one material with a procedural albedo texture, specular 0.5.
Scene makeLearnOpenGLScene();
// The same scene seen from (0, 4.5, 9.5) towards (0, -0.75, 0): every object
// and light in view (loadSceneAny "learnopengl:overview", rgraph render's default).
Scene makeLearnOpenGLOverviewScene();
// The same 9 objects and 32 point lights (which cast no shadows: the
// default for point lights) seen as learnopengl:overview is, standing on a
// floor ("floor", 20 x 20 at y = -1, where the objects' shadows land) under
// a shadow-casting sun from above-front-left: loadSceneAny "learnopengl:shadows".
Scene makeLearnOpenGLShadowsScene();

// A field of cubes and spheres on a floor plane with n point lights (0..kMaxSceneLights)
// spread over it from a seeded PRNG. The field grows with n; each light's
// attenuation is chosen so its radius keeps ~16 lights overlapping on average.
Scene makeManyLightsScene(int n, uint32_t seed = 1);
// The same field and lights seen from low at its near end along the floor to
// a wall across the far end ("far_wall"), through a row of 7 tall, thin
// pillars ("pillar<i>") close to the camera: strong depth discontinuities,
// where a 2D screen tile holds pixels near the camera and at the far wall
// (what clustered shading is for). loadSceneAny "many-lights:N[:seed]:pillars".
Scene makeManyLightsPillarsScene(int n, uint32_t seed = 1);

// Edges that alias, for anti-aliasing measurements (rgraph bench's aa axis;
// loadSceneAny "thin"): a dark floor (one primitive "floor"), a fence of
// kThinScenePosts posts 0.03 wide ("post<i>", x in -4..4, z = 0, 1.2 high),
// kThinSceneWires wires 0.008 thick along the fence, each tilted 0.5-1.25 degrees
// ("wire<i>"), and a far grid of kThinSceneGridBars bars 0.03 wide lying on the
// floor at z in -18..-6 ("bar_x<i>", "bar_z<i>"); flat-coloured materials, one
// directional and 4 point lights, a camera at (0, 1.6, 5.5). Deterministic.
inline constexpr int kThinScenePosts = 25, kThinSceneWires = 4, kThinSceneGridBars = 42;
Scene makeThinScene();

// Skinned figures on a walk cycle, for anti-aliasing in skinned motion (rgraph
// bench's aa axis; loadSceneAny "walker"): three figures 1.8 high
// ("walker0".."walker2", one skinned mesh of 11 joints: hips, spine, head,
// thighs, shins, upper arms, forearms; 2 influences per vertex where a limb
// meets its parent) side-on to the camera, out of step, on a floor ("floor")
// before 5 tall boxes ("pillar<i>"); one animation "walk" (a 1-second
// stride, LINEAR keys: joint rotations and the hips' bob); flat colours, one
// directional and 3 point lights; a camera at (0, 1.3, 4.6). Deterministic.
Scene makeWalkerScene();

// glibc's rand()/random() (TYPE_3 additive feedback generator) reimplemented, so
// the LearnOpenGL light placement is the same on every platform.
class GlibcRandom {
 public:
  explicit GlibcRandom(uint32_t seed = 1);
  int next();  // 0 .. 2^31-1, the sequence glibc's rand() gives after srand(seed)
  static constexpr int kMax = 2147483647;

 private:
  int32_t state_[31];
  int f_ = 3;
  int r_ = 0;
};

}  // namespace rgraph
