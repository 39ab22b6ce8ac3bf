// Scene files (JSON) and the scene spec dispatcher (loadSceneAny).
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "../config/json_text.h"
#include "rgraph/error.h"
#include "rgraph/scene.h"

namespace rgraph {

namespace {

// ordered: members in file order, so messages come out in the order a reader meets them.
using json = nlohmann::ordered_json;
namespace cd = config_detail;

class SceneFileParser {
 public:
  SceneFileParser(std::string file, std::string baseDir) : file_(std::move(file)), baseDir_(std::move(baseDir)) {}

  Scene parse(const std::string& text) {
    locator_.emplace(text);
    // Before the parser sees the text: the nesting bound (as for pipelines),
    // and the light cap, since a million lights cost tens of seconds and
    // gigabytes of parsing before any check on the document could run.
    if (size_t deep = cd::findNestingTooDeep(text); deep != cd::SourceMap::npos) failAtOffset(deep, cd::nestingTooDeepMessage());
    if (size_t extra = cd::findTopLevelArrayElement(text, "lights", kMaxSceneLights); extra != cd::SourceMap::npos)
      failAtOffset(extra, "/lights/" + std::to_string(kMaxSceneLights) + ": " + tooManyLights("more than " + std::to_string(kMaxSceneLights)));
    json doc;
    if (auto error = cd::parseJsonText(text, doc)) failAtOffset(error->offset, "invalid JSON: " + error->message);
    if (!doc.is_object()) fail("", "the scene file must be a JSON object");
    unknownKeys(doc, "", {"models", "lights", "ambient", "environment", "camera", "name", "description", "$schema"});

    Scene scene;
    scene.source = file_;
    if (doc.contains("models")) {
      const json& models = doc["models"];
      if (!models.is_array()) fail("/models", "expected an array");
      for (size_t i = 0; i < models.size(); ++i) addModel(scene, models[i], "/models/" + std::to_string(i));
    }
    const bool hasLightsKey = doc.contains("lights");
    if (hasLightsKey) {
      const json& lights = doc["lights"];
      if (!lights.is_array()) fail("/lights", "expected an array");
      // (The text check above does not see a key spelled with escapes.)
      if (lights.size() > kMaxSceneLights) fail("/lights", tooManyLights(std::to_string(lights.size())));
      for (size_t i = 0; i < lights.size(); ++i) addLight(scene, lights[i], "/lights/" + std::to_string(i));
    }
    if (doc.contains("ambient")) {
      scene.ambient = vec3OrScalar(doc["ambient"], "/ambient", kAnyValue);
      if (auto p = ambientProblem(scene.ambient)) fail("/ambient", p->message);
    }
    if (doc.contains("environment")) scene.environment = environment(doc["environment"], "/environment");
    if (doc.contains("camera")) {
      scene.camera = camera(doc["camera"], "/camera");
      scene.hasCamera = true;
    }
    if (!scene.hasCamera) {
      scene.camera = frameBounds(scene.bounds());
      scene.hasCamera = true;
    }
    // Default light only when the file says nothing about lights ("lights": [] means none).
    if (!hasLightsKey) applySceneDefaults(scene);
    if (const size_t n = scene.pointLights.size() + scene.directionalLights.size(); n > kMaxSceneLights)
      fail(hasLightsKey ? "/lights" : "/models", tooManyLights(std::to_string(n) + " (the models' lights included)"));
    // Lights without falloff (linear = quadratic = 0) have an infinite radius: cap it to reach the whole scene.
    const Bounds b = scene.bounds();
    for (size_t i = 0; i < scene.pointLights.size(); ++i) {
      PointLight& l = scene.pointLights[i];
      if (std::isfinite(l.radius)) continue;
      float reach = scene.camera.far;
      if (!b.empty())
        for (int c = 0; c < 8; ++c)
          reach = std::max(reach, glm::distance(l.position, glm::vec3((c & 1) ? b.max.x : b.min.x, (c & 2) ? b.max.y : b.min.y,
                                                                       (c & 4) ? b.max.z : b.min.z)));
      spdlog::warn("{}: no falloff (linear and quadratic are 0): radius capped to {}", where("/lights/" + std::to_string(i)), reach);
      l.radius = reach;
    }
    scene.validate();
    return scene;
  }

 private:
  // "file:line:col: /pointer" (the position of the value, or of its nearest
  // ancestor the scanner found; just "file: /pointer" if none).
  std::string where(const std::string& ptr, bool atKey = false) const {
    const std::optional<cd::LineColumn> lc = atKey ? locator_->key(ptr) : locator_->value(ptr);
    std::string at = file_;
    if (lc) at += ":" + std::to_string(lc->line) + ":" + std::to_string(lc->column);
    return at + ": " + (ptr.empty() ? std::string("/") : ptr);
  }

  [[noreturn]] void fail(const std::string& ptr, const std::string& msg) const { throw RuntimeError(where(ptr) + ": " + msg); }

  void warn(const std::string& ptr, const std::string& msg, bool atKey = false) const {
    spdlog::warn("{}: {}", where(ptr, atKey), msg);
  }

  [[noreturn]] void failAtOffset(size_t offset, const std::string& msg) const {
    const cd::LineColumn lc = locator_->position(offset);
    throw RuntimeError(file_ + ":" + std::to_string(lc.line) + ":" + std::to_string(lc.column) + ": " + msg);
  }

  // The ranges of lights, ambient and camera are the API's too (pointLightProblem
  // and the others, rgraph/scene.h): values are read as given, then checked there.
  static constexpr float kAnyValue = -std::numeric_limits<float>::max();
  [[noreturn]] void failProblem(const std::string& ptr, const SceneValueProblem& p) const {
    fail(p.key.empty() ? ptr : ptr + "/" + p.key, p.message);
  }

  static std::string tooManyLights(const std::string& count) {
    return count + " lights; a scene may have at most " + std::to_string(kMaxSceneLights) + " (the many-lights:N limit)";
  }

  float number(const json& j, const std::string& ptr) const {
    if (!j.is_number()) fail(ptr, std::string("expected a number, got ") + j.type_name());
    const double d = j.get<double>();
    if (!std::isfinite(d)) fail(ptr, "expected a finite number");
    return float(d);
  }

  float numberOr(const json& obj, const char* key, const std::string& ptr, float fallback) const {
    auto it = obj.find(key);
    return it == obj.end() ? fallback : number(*it, ptr + "/" + key);
  }

  // An optional boolean key: nullopt when absent.
  std::optional<bool> flag(const json& obj, const char* key, const std::string& ptr) const {
    auto it = obj.find(key);
    if (it == obj.end()) return std::nullopt;
    if (!it->is_boolean()) fail(ptr + "/" + key, std::string("expected true or false, got ") + it->type_name());
    return it->get<bool>();
  }

  // A model's "cast_shadows" (its primitives) and "light_shadows" (the lights
  // its glTF file brings), over what the file or the defaults say.
  void applyShadowKeys(Scene& model, const json& j, const std::string& ptr) const {
    if (const auto cast = flag(j, "cast_shadows", ptr))
      for (Primitive& p : model.primitives) p.castShadows = *cast;
    if (const auto lights = flag(j, "light_shadows", ptr)) {
      for (PointLight& l : model.pointLights) l.castShadows = *lights;
      for (DirectionalLight& l : model.directionalLights) l.castShadows = *lights;
    }
  }

  glm::vec3 vec3(const json& j, const std::string& ptr) const {
    if (!j.is_array() || j.size() != 3) fail(ptr, "expected an array of 3 numbers");
    return glm::vec3(number(j[0], ptr + "/0"), number(j[1], ptr + "/1"), number(j[2], ptr + "/2"));
  }

  glm::vec3 vec3OrScalar(const json& j, const std::string& ptr, float minValue) const {
    glm::vec3 v;
    if (j.is_number()) {
      v = glm::vec3(number(j, ptr));
    } else if (j.is_array() && j.size() == 3) {
      v = vec3(j, ptr);
    } else {
      fail(ptr, "expected a number or an array of 3 numbers");
    }
    if (v.x < minValue || v.y < minValue || v.z < minValue) fail(ptr, "values must be >= " + std::to_string(minValue));
    return v;
  }

  std::string string(const json& j, const std::string& ptr) const {
    if (!j.is_string()) fail(ptr, std::string("expected a string, got ") + j.type_name());
    return j.get<std::string>();
  }

  const json& object(const json& j, const std::string& ptr) const {
    if (!j.is_object()) fail(ptr, std::string("expected an object, got ") + j.type_name());
    return j;
  }

  void unknownKeys(const json& obj, const std::string& ptr, std::initializer_list<const char*> known) const {
    for (auto it = obj.begin(); it != obj.end(); ++it)
      if (std::find_if(known.begin(), known.end(), [&](const char* k) { return it.key() == k; }) == known.end())
        warn(ptr + "/" + cd::escapePointerToken(it.key()), "unknown key ignored", true);
  }

  // "environment": exactly one of "color" (uniform radiance), "sky" (the
  // procedural sky, its keys optional) or "hdr" (an equirectangular .hdr file
  // relative to the scene file), and an optional "intensity".
  Environment environment(const json& j, const std::string& ptr) const {
    object(j, ptr);
    unknownKeys(j, ptr, {"color", "sky", "hdr", "intensity"});
    const int kinds = int(j.contains("color")) + int(j.contains("sky")) + int(j.contains("hdr"));
    if (kinds != 1) fail(ptr, "an environment needs exactly one of \"color\", \"sky\" or \"hdr\"");
    Environment env;
    env.intensity = numberOr(j, "intensity", ptr, 1.0f);
    if (env.intensity < 0.0f) fail(ptr + "/intensity", "must be >= 0");
    if (j.contains("color")) {
      env.kind = Environment::Kind::uniform;
      env.color = vec3OrScalar(j["color"], ptr + "/color", 0.0f);
    } else if (j.contains("sky")) {
      const std::string sp = ptr + "/sky";
      const json& sky = object(j["sky"], sp);
      unknownKeys(sky, sp, {"sun_direction", "sun_color", "sun_radius_deg", "zenith", "horizon", "ground"});
      env.kind = Environment::Kind::sky;
      if (sky.contains("sun_direction")) {
        const glm::vec3 d = vec3(sky["sun_direction"], sp + "/sun_direction");
        if (!(glm::length(d) > 0.0f) || !std::isfinite(glm::length(d)))
          fail(sp + "/sun_direction", "must be a finite, non-zero vector");
        env.sunDirection = glm::normalize(d);
      }
      if (sky.contains("sun_color")) env.sunColor = vec3OrScalar(sky["sun_color"], sp + "/sun_color", 0.0f);
      env.sunRadiusDeg = numberOr(sky, "sun_radius_deg", sp, env.sunRadiusDeg);
      if (!(env.sunRadiusDeg > 0.0f && env.sunRadiusDeg <= 45.0f)) fail(sp + "/sun_radius_deg", "must be in (0, 45]");
      if (sky.contains("zenith")) env.zenith = vec3OrScalar(sky["zenith"], sp + "/zenith", 0.0f);
      if (sky.contains("horizon")) env.horizon = vec3OrScalar(sky["horizon"], sp + "/horizon", 0.0f);
      if (sky.contains("ground")) env.ground = vec3OrScalar(sky["ground"], sp + "/ground", 0.0f);
    } else {
      const std::string rel = string(j["hdr"], ptr + "/hdr");
      if (rel.empty()) fail(ptr + "/hdr", "empty path");
      std::filesystem::path p(rel);
      if (p.is_relative()) p = std::filesystem::path(baseDir_) / p;
      try {
        loadEnvironmentHdr(env, p.lexically_normal().string());
      } catch (const RuntimeError& e) {
        fail(ptr + "/hdr", e.what());
      }
      env.intensity = numberOr(j, "intensity", ptr, 1.0f);
    }
    return env;
  }

  // translation * Rz * Ry * Rx * scale: rotation_euler_deg rotates about X, then Y, then Z (fixed axes).
  glm::mat4 transform(const json& j, const std::string& ptr) const {
    object(j, ptr);
    unknownKeys(j, ptr, {"translation", "rotation_euler_deg", "scale"});
    glm::mat4 m(1.0f);
    if (j.contains("translation")) m = glm::translate(m, vec3(j["translation"], ptr + "/translation"));
    if (j.contains("rotation_euler_deg")) {
      const glm::vec3 r = glm::radians(vec3(j["rotation_euler_deg"], ptr + "/rotation_euler_deg"));
      m = glm::rotate(m, r.z, glm::vec3(0, 0, 1));
      m = glm::rotate(m, r.y, glm::vec3(0, 1, 0));
      m = glm::rotate(m, r.x, glm::vec3(1, 0, 0));
    }
    if (j.contains("scale")) {
      const glm::vec3 s = vec3OrScalar(j["scale"], ptr + "/scale", kAnyValue);
      if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f) fail(ptr + "/scale", "scale must not be zero");
      m = glm::scale(m, s);
    }
    return m;
  }

  // A shape's material: the values `j` gives over the scene-file defaults.
  Material material(const json& j, const std::string& ptr) const {
    object(j, ptr);
    unknownKeys(j, ptr, {"name", "baseColor", "metallic", "roughness", "emissive", "specular", "alphaMode", "alphaCutoff", "doubleSided"});
    Material m;
    m.name = j.contains("name") ? string(j["name"], ptr + "/name") : std::string("material");
    m.metallicFactor = 0.0f;
    m.roughnessFactor = 0.5f;
    materialValues(j, ptr, m);
    return m;
  }

  // A file model's "material": the values it gives replace those of every
  // material of the model (glTF has no Blinn-Phong specular, for one).
  void overrideMaterials(Scene& model, const json& j, const std::string& ptr) const {
    object(j, ptr);
    unknownKeys(j, ptr, {"baseColor", "metallic", "roughness", "emissive", "specular", "alphaMode", "alphaCutoff", "doubleSided"});
    for (Material& m : model.materials) materialValues(j, ptr, m);
  }

  // Applies the material values present in `j` to `m` (absent keys keep m's).
  // Ranges are the glTF schema's (scenes/README.md), which glTF files are held to as well.
  void materialValues(const json& j, const std::string& ptr, Material& m) const {
    auto unitNumber = [&](const json& v, const std::string& p) {
      const float x = number(v, p);
      if (x < 0.0f || x > 1.0f) fail(p, "must be in [0, 1]");
      return x;
    };
    if (j.contains("baseColor")) {
      const json& c = j["baseColor"];
      const std::string cp = ptr + "/baseColor";
      if (!c.is_array() || (c.size() != 3 && c.size() != 4)) fail(cp, "expected an array of 3 or 4 numbers");
      for (size_t i = 0; i < c.size(); ++i) m.baseColorFactor[int(i)] = unitNumber(c[i], cp + "/" + std::to_string(i));
    }
    auto unit = [&](const char* key, float fallback) {
      const float v = numberOr(j, key, ptr, fallback);
      if (v < 0.0f || v > 1.0f) fail(ptr + "/" + key, "must be in [0, 1]");
      return v;
    };
    m.metallicFactor = unit("metallic", m.metallicFactor);
    m.roughnessFactor = unit("roughness", m.roughnessFactor);
    m.specular = unit("specular", m.specular);
    m.alphaCutoff = unit("alphaCutoff", m.alphaCutoff);
    if (j.contains("emissive")) m.emissiveFactor = vec3OrScalar(j["emissive"], ptr + "/emissive", 0.0f);
    if (j.contains("alphaMode")) {
      const std::string a = string(j["alphaMode"], ptr + "/alphaMode");
      if (a == "opaque" || a == "OPAQUE") m.alphaMode = AlphaMode::opaque;
      else if (a == "mask" || a == "MASK") m.alphaMode = AlphaMode::mask;
      else if (a == "blend" || a == "BLEND") m.alphaMode = AlphaMode::blend;
      else fail(ptr + "/alphaMode", "expected \"opaque\", \"mask\" or \"blend\", got \"" + a + "\"");
    }
    if (const auto twoSided = flag(j, "doubleSided", ptr)) m.doubleSided = *twoSided;
  }

  void addModel(Scene& scene, const json& j, const std::string& ptr) const {
    object(j, ptr);
    unknownKeys(j, ptr, {"file", "shape", "material", "transform", "name", "size", "spin", "cast_shadows", "light_shadows"});
    const glm::mat4 xf = j.contains("transform") ? transform(j["transform"], ptr + "/transform") : glm::mat4(1.0f);
    // Parsed before the model is loaded, so a bad spin is reported without reading a file.
    const Primitive::Spin turn = j.contains("spin") ? spin(j["spin"], ptr + "/spin", xf) : Primitive::Spin{};
    const size_t firstPrimitive = scene.primitives.size();
    auto animate = [&] {
      for (size_t i = firstPrimitive; i < scene.primitives.size(); ++i) scene.primitives[i].spin = turn;
    };
    const bool hasFile = j.contains("file"), hasShape = j.contains("shape");
    if (hasFile == hasShape) fail(ptr, "a model needs exactly one of \"file\" or \"shape\"");
    if (hasFile) {
      const std::string rel = string(j["file"], ptr + "/file");
      if (rel.empty()) fail(ptr + "/file", "empty path");
      std::filesystem::path p(rel);
      if (p.is_relative()) p = std::filesystem::path(baseDir_) / p;
      const std::string path = p.lexically_normal().string();
      std::error_code ec;
      if (!std::filesystem::exists(path, ec)) fail(ptr + "/file", "model file not found: " + path);
      Scene model;
      try {
        model = loadGltf(path);
      } catch (const RuntimeError& e) {
        fail(ptr + "/file", e.what());
      }
      if (j.contains("material")) overrideMaterials(model, j["material"], ptr + "/material");
      applyShadowKeys(model, j, ptr);
      appendScene(scene, std::move(model), xf);
      animate();
      return;
    }
    const std::string shape = string(j["shape"], ptr + "/shape");
    if (j.contains("light_shadows")) fail(ptr + "/light_shadows", "a shape brings no lights (\"light_shadows\" is for a model file's)");
    Scene s;
    if (shape == "cube") {
      s.meshes.push_back(makeCube(0.5f));
    } else if (shape == "sphere") {
      s.meshes.push_back(makeUvSphere(0.5f));
    } else if (shape == "plane") {
      glm::vec3 size(1.0f);
      if (j.contains("size")) size = vec3OrScalar(j["size"], ptr + "/size", 0.0f);
      s.meshes.push_back(makePlane(size.x * 0.5f, size.z * 0.5f, std::max(size.x, size.z) * 0.5f));
    } else {
      fail(ptr + "/shape", "expected \"cube\", \"sphere\" or \"plane\", got \"" + shape + "\"");
    }
    s.materials.push_back(j.contains("material") ? material(j["material"], ptr + "/material") : Material{});
    if (!j.contains("material")) {
      s.materials.back().name = "default";
      s.materials.back().metallicFactor = 0.0f;
      s.materials.back().roughnessFactor = 0.5f;
    }
    Primitive p;
    p.mesh = 0;
    p.material = 0;
    p.name = j.contains("name") ? string(j["name"], ptr + "/name") : shape;
    p.bounds = s.meshes[0].bounds;
    s.primitives.push_back(p);
    applyShadowKeys(s, j, ptr);
    appendScene(scene, std::move(s), xf);
    animate();
  }

  // "spin": {"axis": [x, y, z], "degrees_per_second": s}, about the model's
  // origin (its transform's translation), axis in world space.
  Primitive::Spin spin(const json& j, const std::string& ptr, const glm::mat4& xf) const {
    object(j, ptr);
    unknownKeys(j, ptr, {"axis", "degrees_per_second"});
    if (!j.contains("degrees_per_second")) fail(ptr, "a spin needs \"degrees_per_second\"");
    Primitive::Spin s;
    s.pivot = glm::vec3(xf[3]);
    if (j.contains("axis")) {
      glm::vec3 a = vec3(j["axis"], ptr + "/axis");
      // Scaled by its largest component first: the length of [1e38, 1e38, 0] overflows a float.
      const float largest = std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)});
      if (!(largest > 0.0f) || !std::isfinite(largest)) fail(ptr + "/axis", "must be a finite, non-zero vector");
      a /= largest;
      s.axis = glm::normalize(a);
    }
    s.degreesPerSecond = number(j["degrees_per_second"], ptr + "/degrees_per_second");
    // number() checks the double; one beyond the float range turns infinite here.
    if (!std::isfinite(s.degreesPerSecond))
      fail(ptr + "/degrees_per_second", "expected a finite number of degrees per second");
    return s;
  }

  // A spot light's cone: "direction" (where it points; any finite non-zero
  // length), "outer_cone_deg" (default 45) and "inner_cone_deg" (default 0),
  // half-angles from the axis in glTF's ranges: 0 <= inner < outer <= 90.
  void spotCone(const json& j, const std::string& ptr, PointLight& l) const {
    if (!j.contains("direction")) fail(ptr, "a spot light needs \"direction\"");
    glm::vec3 d = vec3(j["direction"], ptr + "/direction");
    // Scaled by its largest component first: the length of [1e38, 1e38, 0] overflows a float.
    const float largest = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
    if (!(largest > 0.0f) || !std::isfinite(largest)) fail(ptr + "/direction", "must be a finite, non-zero vector");
    l.spot = true;
    l.direction = glm::normalize(d / largest);
    l.outerConeDeg = numberOr(j, "outer_cone_deg", ptr, 45.0f);
    l.innerConeDeg = numberOr(j, "inner_cone_deg", ptr, 0.0f);
  }

  void addLight(Scene& scene, const json& j, const std::string& ptr) const {
    object(j, ptr);
    if (!j.contains("type")) fail(ptr, "missing \"type\" (\"point\", \"spot\" or \"directional\")");
    const std::string type = string(j["type"], ptr + "/type");
    const float intensity = numberOr(j, "intensity", ptr, 1.0f);
    const glm::vec3 color = j.contains("color") ? vec3OrScalar(j["color"], ptr + "/color", kAnyValue) : glm::vec3(1.0f);
    if (type == "point" || type == "spot") {
      const bool spot = type == "spot";
      if (spot)
        unknownKeys(j, ptr, {"type", "position", "direction", "inner_cone_deg", "outer_cone_deg", "color", "intensity",
                             "constant", "linear", "quadratic", "radius", "shadows"});
      else
        unknownKeys(j, ptr,
                    {"type", "position", "color", "intensity", "constant", "linear", "quadratic", "radius", "shadows"});
      if (!j.contains("position")) fail(ptr, std::string("a ") + type + " light needs \"position\"");
      PointLight l;
      l.position = vec3(j["position"], ptr + "/position");
      l.color = color;
      l.intensity = intensity;
      l.constant = numberOr(j, "constant", ptr, 1.0f);
      l.linear = numberOr(j, "linear", ptr, 0.7f);
      l.quadratic = numberOr(j, "quadratic", ptr, 1.8f);
      l.radius = j.contains("radius") ? number(j["radius"], ptr + "/radius") : 0.0f;
      if (spot) spotCone(j, ptr, l);
      l.castShadows = flag(j, "shadows", ptr);
      if (auto p = pointLightProblem(l)) failProblem(ptr, *p);
      if (!j.contains("radius")) l.radius = lightRadius(l);
      scene.pointLights.push_back(l);
    } else if (type == "directional") {
      unknownKeys(j, ptr, {"type", "direction", "color", "intensity", "shadows"});
      if (!j.contains("direction")) fail(ptr, "a directional light needs \"direction\"");
      DirectionalLight l;
      l.direction = vec3(j["direction"], ptr + "/direction");
      l.color = color;
      l.intensity = intensity;
      l.castShadows = flag(j, "shadows", ptr).value_or(true);
      if (auto p = directionalLightProblem(l)) failProblem(ptr, *p);
      const glm::vec3 d = l.direction;
      l.direction = glm::normalize(d / std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}));
      scene.directionalLights.push_back(l);
    } else {
      fail(ptr + "/type", "expected \"point\", \"spot\" or \"directional\", got \"" + type + "\"");
    }
  }

  Camera camera(const json& j, const std::string& ptr) const {
    object(j, ptr);
    unknownKeys(j, ptr, {"position", "target", "forward", "up", "fov", "near", "far"});
    Camera c;
    if (!j.contains("position")) fail(ptr, "a camera needs \"position\"");
    c.position = vec3(j["position"], ptr + "/position");
    if (j.contains("target") && j.contains("forward")) fail(ptr, "give \"target\" or \"forward\", not both");
    if (j.contains("target")) {
      c.target = vec3(j["target"], ptr + "/target");
    } else if (j.contains("forward")) {
      const glm::vec3 f = vec3(j["forward"], ptr + "/forward");
      if (glm::length(f) == 0.0f) fail(ptr + "/forward", "must not be the zero vector");
      c.target = c.position + glm::normalize(f);
    } else {
      c.target = c.position + glm::vec3(0, 0, -1);
    }
    if (j.contains("up")) c.up = vec3(j["up"], ptr + "/up");
    c.fovY = numberOr(j, "fov", ptr, 45.0f);
    c.near = numberOr(j, "near", ptr, 0.1f);
    c.far = numberOr(j, "far", ptr, 100.0f);
    if (auto p = cameraProblem(c)) failProblem(ptr, *p);
    c.up = glm::normalize(c.up / std::max({std::abs(c.up.x), std::abs(c.up.y), std::abs(c.up.z)}));
    // Looking straight along up (e.g. straight down with the default up) leaves the view without an orientation.
    if (const glm::vec3 valid = c.validUp(); valid != c.up) {
      warn(j.contains("up") ? ptr + "/up" : ptr, "the up vector is parallel to the view direction; using up = [" + std::to_string(valid.x) +
                                                     ", " + std::to_string(valid.y) + ", " + std::to_string(valid.z) + "]");
      c.up = valid;
    }
    return c;
  }

  std::string file_;
  std::string baseDir_;
  mutable std::optional<cd::JsonLocator> locator_;  // positions in the text, scanned when a message needs one
};

std::string lowerExtension(const std::string& spec) {
  std::string ext = std::filesystem::path(spec).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

bool parseUint(std::string_view s, uint64_t& out) {
  if (s.empty()) return false;
  auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}

}  // namespace

Scene parseSceneText(const std::string& text, const std::string& file, const std::string& baseDir) {
  return SceneFileParser(file, baseDir).parse(text);
}

Scene loadSceneFile(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (std::filesystem::is_directory(st)) throw RuntimeError(path + ": is a folder, not a scene file");
  if (!std::filesystem::is_regular_file(st)) throw RuntimeError(path + ": scene file not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RuntimeError(path + ": cannot open the scene file");
  // One copy of the text in memory (a stringstream would hold two).
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw RuntimeError(path + ": cannot read the scene file size (" + ec.message() + ")");
  std::string text(size_t(size), '\0');
  in.read(text.data(), std::streamsize(text.size()));
  if (in.gcount() != std::streamsize(text.size())) throw RuntimeError(path + ": cannot read the scene file");
  const std::string base = std::filesystem::absolute(std::filesystem::path(path), ec).parent_path().string();
  return parseSceneText(text, path, base);
}

Scene loadSceneAny(const std::string& spec) {
  if (spec == "learnopengl") return makeLearnOpenGLScene();
  if (spec == "thin") return makeThinScene();
  if (spec == "walker") return makeWalkerScene();
  if (spec == "learnopengl:overview") return makeLearnOpenGLOverviewScene();
  if (spec == "learnopengl:shadows") return makeLearnOpenGLShadowsScene();
  const std::string prefix = "many-lights:";
  if (spec.rfind(prefix, 0) == 0) {
    std::string_view rest(spec);
    rest.remove_prefix(prefix.size());
    // N, then an optional seed, then an optional "pillars".
    bool pillars = false;
    if (rest.size() >= 8 && rest.substr(rest.size() - 8) == ":pillars") {
      pillars = true;
      rest.remove_suffix(8);
    }
    std::string_view countText = rest, seedText;
    if (size_t colon = rest.find(':'); colon != std::string_view::npos) {
      countText = rest.substr(0, colon);
      seedText = rest.substr(colon + 1);
    }
    uint64_t count = 0, seed = 1;
    if (!parseUint(countText, count) || count > kMaxSceneLights)
      throw RuntimeError("scene '" + spec + "': expected many-lights:N[:seed][:pillars] with N in 0.." + std::to_string(kMaxSceneLights));
    if (!seedText.empty() && (!parseUint(seedText, seed) || seed > UINT32_MAX))
      throw RuntimeError("scene '" + spec + "': the seed must be an unsigned 32-bit integer (or 'pillars')");
    return pillars ? makeManyLightsPillarsScene(int(count), uint32_t(seed)) : makeManyLightsScene(int(count), uint32_t(seed));
  }
  const std::string ext = lowerExtension(spec);
  if (ext == ".json") return loadSceneFile(spec);
  if (ext == ".gltf" || ext == ".glb") {
    Scene s = loadGltf(spec);
    applySceneDefaults(s);
    return s;
  }
  throw RuntimeError("unknown scene '" + spec +
                     "': expected a scene file (.json), a glTF model (.gltf, .glb), 'learnopengl', 'learnopengl:overview', 'learnopengl:shadows', 'thin', 'walker' or 'many-lights:N'");
}

}  // namespace rgraph
