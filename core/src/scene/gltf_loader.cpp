// glTF 2.0 loading with tinygltf (parsing only): the entry points, the bytes
// handed to tinygltf, node traversal, cameras and the conversion to a Scene.
// Accessors and meshes are in gltf_geometry.cpp, materials and lights in
// gltf_materials.cpp (see gltf_internal.h).
#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <spdlog/spdlog.h>

#include "gltf_internal.h"
#include "rgraph/error.h"

namespace rgraph {

namespace gltf_detail {

namespace {

// External files a glTF names (buffers, images) larger than this are refused
// before they are read: tinygltf reads a whole file into memory first.
constexpr uintmax_t kMaxExternalFile = uintmax_t(1) << 31;

// tinygltf's file access, replaced so that a URI naming a folder, a device or
// a missing file gets a reason (its own reader sizes a folder as 2^63 bytes
// and fails with std::bad_alloc). "Exists" is always yes: the read reports
// what is wrong, and a URI never falls back to the current directory.
bool fileExists(const std::string& /*path*/, void*) { return true; }
std::string expandFilePath(const std::string& path, void*) { return path; }
bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not supported\n";
  return false;
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  auto refuse = [&](const std::string& why) {
    if (err) *err += why;
    return false;
  };
  if (path.empty()) return refuse("the URI is empty");
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (st.type() == std::filesystem::file_type::not_found) return refuse("no such file");
  if (ec) return refuse("cannot access it (" + ec.message() + ")");
  if (std::filesystem::is_directory(st)) return refuse("it is a folder, not a file");
  if (!std::filesystem::is_regular_file(st)) return refuse("it is not a regular file");
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return refuse("cannot read its size (" + ec.message() + ")");
  if (size == 0) return refuse("the file is empty");
  if (size > kMaxExternalFile) return refuse("the file is larger than 2 GiB");
  std::ifstream f(path, std::ios::binary);
  if (!f) return refuse("cannot open it");
  out->resize(size_t(size));
  f.read(reinterpret_cast<char*>(out->data()), std::streamsize(size));
  if (f.gcount() != std::streamsize(size)) return refuse("cannot read it");
  return true;
}

uint32_t readU32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

}  // namespace

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
  return s;
}

Scene GltfLoader::load() {
  parse();
  scene_.source = name_;
  try {
    convert();
  } catch (const RuntimeError&) {
    throw;
  } catch (const std::exception& e) {
    fail(std::string("unexpected failure: ") + e.what());
  }
  scene_.warnings = std::move(warnings_);
  return std::move(scene_);
}

void GltfLoader::fail(const std::string& msg) const { throw RuntimeError(name_ + ": " + msg); }
void GltfLoader::warn(const std::string& msg) const {
  warnings_.push_back(name_ + ": " + msg);
  spdlog::warn("{}", warnings_.back());
}

std::string GltfLoader::where(const std::string& pointer) {
  std::string at = name_;
  if (!binary_) {
    if (!locator_) locator_.emplace(json_);
    if (auto lc = locator_->value(pointer)) at += ":" + std::to_string(lc->line) + ":" + std::to_string(lc->column);
  }
  return at + ": " + pointer;
}

void GltfLoader::failAt(const std::string& pointer, const std::string& msg) { throw RuntimeError(where(pointer) + ": " + msg); }
void GltfLoader::warnAt(const std::string& pointer, const std::string& msg) {
  warnings_.push_back(where(pointer) + ": " + msg);
  spdlog::warn("{}", warnings_.back());
}

// ------------------------------------------------------------ parsing

void GltfLoader::parse() {
  if (size_ == 0 || !data_) fail("the file is empty");
  // tinygltf takes the length as a 32-bit unsigned.
  if (size_ > size_t(UINT_MAX)) fail("the file is 4 GiB or larger; not supported");
  binary_ = size_ >= 4 && std::memcmp(data_, "glTF", 4) == 0;

  // tinygltf turns extras and extensions into nested values recursively: JSON
  // nested deep enough overflows the stack there, so bound it first. A .glb's
  // JSON chunk is where tinygltf will look for it (header checks are its own).
  if (!binary_) {
    json_ = std::string_view(reinterpret_cast<const char*>(data_), size_);
  } else if (size_ >= 20 && readU32(data_ + 16) == 0x4E4F534Au && readU32(data_ + 12) <= size_ - 20) {
    json_ = std::string_view(reinterpret_cast<const char*>(data_) + 20, readU32(data_ + 12));
  }
  if (size_t deep = config_detail::findNestingTooDeep(json_); deep != config_detail::SourceMap::npos) {
    if (!locator_) locator_.emplace(json_);
    const config_detail::LineColumn lc = locator_->position(deep);
    const std::string pos = std::to_string(lc.line) + ":" + std::to_string(lc.column);
    if (binary_) fail("JSON chunk, line " + pos + ": " + config_detail::nestingTooDeepMessage());
    throw RuntimeError(name_ + ":" + pos + ": " + config_detail::nestingTooDeepMessage());
  }

  checkDraco();

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(&imageCallback, nullptr);
  loader.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, nullptr});
  std::string err, warnText;
  bool ok = false;
  try {
    const unsigned int n = static_cast<unsigned int>(size_);
    ok = binary_ ? loader.LoadBinaryFromMemory(&model_, &err, &warnText, data_, n, baseDir_)
                 : loader.LoadASCIIFromString(&model_, &err, &warnText, reinterpret_cast<const char*>(data_), n, baseDir_);
  } catch (const std::exception& e) {
    fail(std::string("glTF parser failed: ") + e.what());
  }
  tinyWarn_ = trimmed(warnText);
  if (!ok) {
    std::string msg = std::string("cannot load ") + (binary_ ? "binary glTF" : "glTF") + ": " + trimmed(err);
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    if (!tinyWarn_.empty()) msg += " (warnings: " + tinyWarn_ + ")";
    fail(msg);
  }
  if (!tinyWarn_.empty()) {
    // An image tinygltf could not read is reported when a texture uses it
    // (decodedPixels refuses the file, naming it): logging tinygltf's words
    // too would say it twice.
    std::istringstream lines(tinyWarn_);
    for (std::string line; std::getline(lines, line);) {
      if (line.empty()) continue;
      if (line.rfind("File read error", 0) == 0 || line.find("for image[") != std::string::npos)
        imageWarn_ += (imageWarn_.empty() ? "" : "; ") + line;
      else
        warn(line);
    }
  }
  checkAsset();
}

// asset.version "2.x" (a newer minor version stays readable by a 2.0 loader,
// says the spec; another major version does not), minVersion at most 2.0,
// and only required extensions this loader implements.
void GltfLoader::checkAsset() {
  auto parseVersion = [](const std::string& v, int& major, int& minor) {
    size_t dot = v.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == v.size()) return false;
    for (size_t i = 0; i < v.size(); ++i)
      if (i != dot && !std::isdigit(static_cast<unsigned char>(v[i]))) return false;
    if (dot > 4 || v.size() - dot > 5) return false;  // no overflow below
    major = std::stoi(v.substr(0, dot));
    minor = std::stoi(v.substr(dot + 1));
    return true;
  };
  int major = 0, minor = 0;
  const std::string& version = model_.asset.version;
  if (!parseVersion(version, major, minor)) failAt("/asset/version", "expected \"2.0\" (MAJOR.MINOR), got \"" + version + "\"");
  if (major != 2) failAt("/asset/version", "glTF " + version + " is not supported (this loader reads glTF 2.x)");
  const std::string& minVersion = model_.asset.minVersion;
  if (!minVersion.empty()) {
    if (!parseVersion(minVersion, major, minor)) failAt("/asset/minVersion", "expected MAJOR.MINOR, got \"" + minVersion + "\"");
    if (major != 2 || minor != 0)
      failAt("/asset/minVersion", "the file needs glTF " + minVersion + "; this loader reads glTF 2.0");
  }
  for (size_t i = 0; i < model_.extensionsRequired.size(); ++i) {
    const std::string& ext = model_.extensionsRequired[i];
    if (ext != "KHR_lights_punctual" && ext != "KHR_materials_emissive_strength" && ext != "KHR_materials_specular" &&
        ext != "KHR_materials_unlit" && ext != "KHR_mesh_quantization")
      failAt("/extensionsRequired/" + std::to_string(i), "requires the unsupported extension " + ext);
  }
  if (model_.lights.size() > kMaxSceneLights)
    failAt("/extensions/KHR_lights_punctual/lights", std::to_string(model_.lights.size()) + " lights; at most " +
                                                          std::to_string(kMaxSceneLights) + " are supported");
}

// ------------------------------------------------------------ nodes

glm::mat4 GltfLoader::localMatrix(const tinygltf::Node& node, const std::string& what) const {
  auto finite = [&](const std::vector<double>& v, const char* name) {
    for (double d : v)
      if (!std::isfinite(d)) fail(what + ": '" + name + "' has a non-finite value");
  };
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) fail(what + ": 'matrix' must have 16 numbers");
    finite(node.matrix, "matrix");
    glm::mat4 m;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m[c][r] = float(node.matrix[size_t(c * 4 + r)]);  // column-major like glTF
    return m;
  }
  glm::mat4 m(1.0f);
  if (!node.translation.empty()) {
    if (node.translation.size() != 3) fail(what + ": 'translation' must have 3 numbers");
    finite(node.translation, "translation");
    m = glm::translate(m, glm::vec3(float(node.translation[0]), float(node.translation[1]), float(node.translation[2])));
  }
  if (!node.rotation.empty()) {
    if (node.rotation.size() != 4) fail(what + ": 'rotation' must have 4 numbers");
    finite(node.rotation, "rotation");
    glm::quat q(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]));  // w, x, y, z
    const float len = glm::length(q);
    if (len > 0.0f) m = m * glm::mat4_cast(q / len);
  }
  if (!node.scale.empty()) {
    if (node.scale.size() != 3) fail(what + ": 'scale' must have 3 numbers");
    finite(node.scale, "scale");
    m = glm::scale(m, glm::vec3(float(node.scale[0]), float(node.scale[1]), float(node.scale[2])));
  }
  return m;
}

// Depth-first, parents before children, children in file order, with an
// explicit stack: a chain of nodes as deep as the file is long must not
// overflow the C++ stack. A node met again while it is on the current path is
// a cycle; the visit count bounds what scenes listing nodes twice can cost.
void GltfLoader::traverse(const std::vector<int>& roots) {
  struct Step {
    int node;
    bool leave;         // true: the node's subtree is done, take it off the path
    glm::mat4 parent;   // the parent's world matrix (entering steps)
  };
  std::vector<Step> stack;
  std::vector<char> onPath(model_.nodes.size(), 0);
  size_t visits = 0;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, false, glm::mat4(1.0f)});
  while (!stack.empty()) {
    const Step step = stack.back();
    stack.pop_back();
    if (step.leave) {
      onPath[size_t(step.node)] = 0;
      continue;
    }
    const int n = step.node;
    if (n < 0 || size_t(n) >= model_.nodes.size())
      fail("node " + std::to_string(n) + " does not exist (" + std::to_string(model_.nodes.size()) + " nodes)");
    if (onPath[size_t(n)]) fail("node " + std::to_string(n) + " is its own ancestor (cycle in the node hierarchy)");
    if (++visits > 4 * model_.nodes.size() + 16) fail("node hierarchy references nodes repeatedly");
    onPath[size_t(n)] = 1;
    const tinygltf::Node& node = model_.nodes[size_t(n)];
    const std::string what = "node " + std::to_string(n) + (node.name.empty() ? "" : " ('" + node.name + "')");
    const glm::mat4 world = step.parent * localMatrix(node, what);
    visitNode(n, world);
    stack.push_back({n, true, glm::mat4(1.0f)});
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back({*it, false, world});
  }
}

// One node's own content: its mesh's primitives, its camera, its light.
void GltfLoader::visitNode(int nodeIndex, const glm::mat4& world) {
  const tinygltf::Node& node = model_.nodes[size_t(nodeIndex)];
  const std::string what = "node " + std::to_string(nodeIndex) + (node.name.empty() ? "" : " ('" + node.name + "')");
  if (node.mesh >= 0) {
    if (size_t(node.mesh) >= model_.meshes.size())
      fail(what + ": mesh " + std::to_string(node.mesh) + " does not exist (" + std::to_string(model_.meshes.size()) + " meshes)");
    const tinygltf::Mesh& gm = model_.meshes[size_t(node.mesh)];
    const std::optional<std::vector<glm::mat4>> instances = nodeInstances(nodeIndex, node);
    const size_t primitives = instances && instances->empty() ? 0 : gm.primitives.size();  // zero instances: none drawn
    for (size_t pi = 0; pi < primitives; ++pi) {
      const int mesh = sceneMesh(node.mesh, pi);
      if (mesh < 0) continue;
      Primitive p;
      p.mesh = mesh;
      p.material = primMaterial_[size_t(mesh)];
      p.transform = world;
      if (instances) p.instances = *instances;
      p.bounds = p.worldBounds(scene_.meshes[size_t(mesh)].bounds);
      p.name = node.name.empty() ? (gm.name.empty() ? what : gm.name) : node.name;
      if (keepNodes_) p.node = nodeIndex;
      scene_.primitives.push_back(std::move(p));
    }
  }
  if (node.camera >= 0) addCamera(node.camera, world, what);
  if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end()) {
    // (Value::Get asserts an object: check first.)
    if (!it->second.IsObject() || !it->second.Get("light").IsNumber())
      failAt("/nodes/" + std::to_string(nodeIndex) + "/extensions/KHR_lights_punctual", "expected {\"light\": index}");
    const tinygltf::Value& v = it->second.Get("light");
    // Out-of-range doubles must not reach an int conversion (undefined behaviour).
    const double light = v.GetNumberAsDouble();
    addLight(light >= 0.0 && light < double(INT_MAX) ? int(light) : -1, world, what);
  }
}

// The first perspective camera. Its values are held to the ranges scene files
// use (fov in (0, 180) degrees, near > 0, far > near when given).
void GltfLoader::addCamera(int index, const glm::mat4& world, const std::string& what) {
  if (index < 0 || size_t(index) >= model_.cameras.size())
    fail(what + ": camera " + std::to_string(index) + " does not exist (" + std::to_string(model_.cameras.size()) + " cameras)");
  if (scene_.hasCamera) return;  // the first camera wins
  const tinygltf::Camera& c = model_.cameras[size_t(index)];
  if (c.type != "perspective") {
    warn(what + ": camera type '" + c.type + "' is not supported; ignored");
    return;
  }
  const std::string ptr = "/cameras/" + std::to_string(index) + "/perspective";
  Camera cam;
  const auto& p = c.perspective;
  if (!(std::isfinite(p.yfov) && p.yfov > 0.0 && p.yfov < glm::pi<double>()))
    failAt(ptr + "/yfov", "must be in (0, pi) radians, got " + std::to_string(p.yfov));
  cam.fovY = float(glm::degrees(p.yfov));
  if (!(std::isfinite(p.znear) && p.znear > 0.0)) failAt(ptr + "/znear", "must be > 0, got " + std::to_string(p.znear));
  cam.near = float(p.znear);
  // zfar 0 is tinygltf's "absent" (an infinite projection).
  if (p.zfar != 0.0 && !(std::isfinite(p.zfar) && p.zfar > p.znear))
    failAt(ptr + "/zfar", "must be greater than znear, got " + std::to_string(p.zfar));
  cameraHasFar_ = p.zfar != 0.0;
  cam.far = cameraHasFar_ ? float(p.zfar) : cam.near * 1000.0f;
  cam.position = glm::vec3(world * glm::vec4(0, 0, 0, 1));
  glm::vec3 fwd = glm::mat3(world) * glm::vec3(0, 0, -1);
  glm::vec3 up = glm::mat3(world) * glm::vec3(0, 1, 0);
  fwd = glm::length(fwd) > 0.0f ? glm::normalize(fwd) : glm::vec3(0, 0, -1);
  cam.up = glm::length(up) > 0.0f ? glm::normalize(up) : up;
  cam.target = cam.position + fwd;
  if (const glm::vec3 valid = cam.validUp(); valid != cam.up) {
    warn(what + ": the camera's up vector is parallel to its view direction (a degenerate node transform); using (" +
         std::to_string(valid.x) + ", " + std::to_string(valid.y) + ", " + std::to_string(valid.z) + ")");
    cam.up = valid;
  }
  scene_.camera = cam;
  scene_.hasCamera = true;
}

// ------------------------------------------------------------ conversion

void GltfLoader::convert() {
  warnIgnoredFeatures();
  for (size_t i = 0; i < model_.materials.size(); ++i) scene_.materials.push_back(convertMaterial(i));

  // Every node has at most one parent (glTF requires disjoint trees).
  std::vector<int> parents(model_.nodes.size(), 0);
  for (size_t i = 0; i < model_.nodes.size(); ++i) {
    for (int c : model_.nodes[i].children) {
      if (c < 0 || size_t(c) >= model_.nodes.size())
        fail("node " + std::to_string(i) + ": child " + std::to_string(c) + " does not exist (" + std::to_string(model_.nodes.size()) +
             " nodes)");
      if (++parents[size_t(c)] > 1) fail("node " + std::to_string(c) + " has more than one parent");
    }
  }
  std::vector<int> roots;
  if (!model_.scenes.empty()) {
    int si = model_.defaultScene;
    if (si < 0 || size_t(si) >= model_.scenes.size()) {
      if (si >= 0) warn("default scene " + std::to_string(si) + " does not exist; using scene 0");
      si = 0;
    }
    roots = model_.scenes[size_t(si)].nodes;
  } else {
    for (size_t i = 0; i < model_.nodes.size(); ++i)
      if (parents[i] == 0) roots.push_back(int(i));
  }
  keepNodes_ = keepsNodes();
  traverse(roots);
  if (keepNodes_) loadAnimationData();

  if (scene_.primitives.empty()) warn("no triangle geometry in the default scene");
  if (scene_.hasCamera && !cameraHasFar_) {
    // Infinite far plane in the file: cover the scene instead.
    const Bounds b = scene_.bounds();
    if (!b.empty())
      scene_.camera.far = std::max(glm::length(b.center() - scene_.camera.position) + b.radius() * 2.0f, scene_.camera.near * 100.0f);
  }
  scene_.validate();
}

}  // namespace gltf_detail

Scene loadGltfFromMemory(const unsigned char* data, std::size_t size, const std::string& nameForMessages,
                         const std::string& baseDir) {
  return gltf_detail::GltfLoader(data, size, nameForMessages, baseDir).load();
}

Scene loadGltf(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_status st = std::filesystem::status(path, ec);
  if (st.type() == std::filesystem::file_type::not_found) throw RuntimeError(path + ": file not found");
  if (std::filesystem::is_directory(st)) throw RuntimeError(path + ": is a folder, not a glTF file");
  if (!std::filesystem::is_regular_file(st)) throw RuntimeError(path + ": not a regular file");
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw RuntimeError(path + ": cannot read the file size (" + ec.message() + ")");
  if (size > uintmax_t(UINT_MAX)) throw RuntimeError(path + ": the file is 4 GiB or larger; not supported");
  std::vector<unsigned char> bytes(static_cast<size_t>(size));
  std::ifstream f(path, std::ios::binary);
  if (!f) throw RuntimeError(path + ": cannot open the file");
  f.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size));
  if (f.gcount() != std::streamsize(size)) throw RuntimeError(path + ": cannot read the file");
  // Like tinygltf's own file loader: URIs resolve against the file's folder.
  return loadGltfFromMemory(bytes.data(), bytes.size(), path, std::filesystem::path(path).parent_path().string());
}

}  // namespace rgraph
