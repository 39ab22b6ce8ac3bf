// glTF animation data (see gltf_internal.h): skin influences and morph
// targets of primitives, and for files that have animations, skins or morph
// targets the node table, skins and animations of Scene::animation
// (rgraph/animation.h evaluates them). Everything is checked here, so that
// evaluation never meets an index out of range or a non-finite number:
// refusals name the file and the JSON pointer of the value at fault.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "gltf_internal.h"
#include "rgraph/error.h"

namespace rgraph::gltf_detail {

namespace {

constexpr int F = TINYGLTF_COMPONENT_TYPE_FLOAT, B = TINYGLTF_COMPONENT_TYPE_BYTE,
              UB = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, S = TINYGLTF_COMPONENT_TYPE_SHORT,
              US = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;

std::string str(size_t v) { return std::to_string(v); }

int attribute(const std::map<std::string, int>& attributes, const std::string& name) {
  const auto it = attributes.find(name);
  return it == attributes.end() ? -1 : it->second;
}

}  // namespace

std::vector<float> GltfLoader::readFinite(int index, const std::string& pointer, const std::string& what,
                                          std::initializer_list<int> types, std::initializer_list<int> componentTypes) {
  size_t bad = SIZE_MAX;
  std::vector<float> v = readFloats(index, what, types, componentTypes, &bad);
  if (bad != SIZE_MAX) failAt(pointer, "accessor " + std::to_string(index) + " element " + str(bad) + " is not finite");
  return v;
}

// ------------------------------------------------------------ primitives

// Sets JOINTS_0/WEIGHTS_0, JOINTS_1/WEIGHTS_1, ... in pairs, each VEC4 per
// vertex: joints unsigned byte or short, weights float or normalized
// unsigned byte or short (glTF "Skinned Mesh Attributes").
void GltfLoader::readSkinAttributes(const tinygltf::Primitive& prim, MeshData& mesh, const std::string& what,
                                    const std::string& pointer) {
  const size_t n = mesh.positions.size();
  for (size_t set = 0;; ++set) {
    const std::string jn = "JOINTS_" + str(set), wn = "WEIGHTS_" + str(set);
    const int ja = attribute(prim.attributes, jn), wa = attribute(prim.attributes, wn);
    if (ja < 0 && wa < 0) break;
    if (ja < 0 || wa < 0)
      failAt(pointer + "/attributes/" + (ja < 0 ? wn : jn),
             "has no matching " + (ja < 0 ? jn : wn) + " (skin influences come in pairs)");
    if (wa >= 0 && size_t(wa) < model_.accessors.size()) {
      const tinygltf::Accessor& acc = model_.accessors[size_t(wa)];
      if (acc.componentType != F && !acc.normalized)
        failAt(pointer + "/attributes/" + wn,
               "integer weights must be normalized (accessor " + std::to_string(wa) + ")");
    }
    const std::vector<float> j = readFloats(ja, what + " " + jn, {TINYGLTF_TYPE_VEC4}, {UB, US});
    const std::vector<float> w =
        readFinite(wa, pointer + "/attributes/" + wn, what + " " + wn, {TINYGLTF_TYPE_VEC4}, {F, UB, US});
    if (j.size() != 4 * n || w.size() != 4 * n)
      failAt(
          pointer + "/attributes/" + (j.size() != 4 * n ? jn : wn),
          "count " + str((j.size() != 4 * n ? j.size() : w.size()) / 4) + " differs from the POSITION count " + str(n));
    SkinInfluences s;
    s.joints.resize(n);
    s.weights.resize(n);
    for (size_t v = 0; v < n; ++v) {
      s.joints[v] =
          glm::u16vec4(uint16_t(j[4 * v]), uint16_t(j[4 * v + 1]), uint16_t(j[4 * v + 2]), uint16_t(j[4 * v + 3]));
      s.weights[v] = glm::vec4(w[4 * v], w[4 * v + 1], w[4 * v + 2], w[4 * v + 3]);
    }
    mesh.influences.push_back(std::move(s));
  }
}

// targets[i].POSITION / NORMAL / TANGENT displacements (VEC3; float, or
// integers as KHR_mesh_quantization allows), one per vertex.
void GltfLoader::readMorphTargets(const tinygltf::Primitive& prim, MeshData& mesh, const std::string& what,
                                  const std::string& pointer) {
  const size_t n = mesh.positions.size();
  for (size_t ti = 0; ti < prim.targets.size(); ++ti) {
    MorphTarget target;
    for (const char* name : {"POSITION", "NORMAL", "TANGENT"}) {
      const int a = attribute(prim.targets[ti], name);
      if (a < 0) continue;
      const std::string ptr = pointer + "/targets/" + str(ti) + "/" + name;
      const std::vector<float> d =
          readFinite(a, ptr, what + " target " + str(ti) + " " + name, {TINYGLTF_TYPE_VEC3}, {F, B, UB, S, US});
      if (d.size() != 3 * n) failAt(ptr, "count " + str(d.size() / 3) + " differs from the POSITION count " + str(n));
      std::vector<glm::vec3>& out = name[0] == 'P'   ? target.positions
                                    : name[0] == 'N' ? target.normals
                                                     : target.tangents;
      out.resize(n);
      for (size_t v = 0; v < n; ++v) out[v] = glm::vec3(d[3 * v], d[3 * v + 1], d[3 * v + 2]);
    }
    mesh.morphTargets.push_back(std::move(target));
  }
}

// ------------------------------------------------------------ nodes and skins

bool GltfLoader::keepsNodes() const {
  if (!model_.animations.empty() || !model_.skins.empty()) return true;
  for (const tinygltf::Mesh& m : model_.meshes)
    for (const tinygltf::Primitive& p : m.primitives)
      if (!p.targets.empty()) return true;
  return false;
}

void GltfLoader::loadAnimationData() {
  SceneAnimation& anim = scene_.animation;
  loadNodes(anim);
  loadSkins(anim);
  checkSkinnedMeshes(anim);
  for (size_t i = 0; i < model_.animations.size(); ++i) loadAnimation(i, anim);
  anim.updateLayout();
}

// Every node of the file, with its glTF index (convert() refused nodes with
// two parents; traverse() refused cycles among the scene's nodes, and a cycle
// elsewhere is refused here).
void GltfLoader::loadNodes(SceneAnimation& out) {
  const size_t count = model_.nodes.size();
  out.nodes.resize(count);
  for (size_t i = 0; i < count; ++i)
    for (int c : model_.nodes[i].children) out.nodes[size_t(c)].parent = int(i);
  for (size_t i = 0; i < count; ++i) {
    const tinygltf::Node& gn = model_.nodes[i];
    SceneNode& n = out.nodes[i];
    const std::string ptr = "/nodes/" + str(i);
    n.name = gn.name;
    auto numbers = [&](const std::vector<double>& v, size_t size, const char* key) {
      if (v.empty()) return false;
      if (v.size() != size) failAt(ptr + "/" + key, "must have " + str(size) + " numbers");
      for (double d : v)
        if (!std::isfinite(d) || std::abs(d) > 3.0e38) failAt(ptr + "/" + key, "has a non-finite value");
      return true;
    };
    if (numbers(gn.matrix, 16, "matrix")) {
      n.hasMatrix = true;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) n.matrix[c][r] = float(gn.matrix[size_t(c * 4 + r)]);
    }
    if (numbers(gn.translation, 3, "translation"))
      n.translation = glm::vec3(gn.translation[0], gn.translation[1], gn.translation[2]);
    if (numbers(gn.rotation, 4, "rotation")) {
      const glm::quat q(float(gn.rotation[3]), float(gn.rotation[0]), float(gn.rotation[1]), float(gn.rotation[2]));
      n.rotation = glm::length(q) > 0.0f ? glm::normalize(q) : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
    }
    if (numbers(gn.scale, 3, "scale")) n.scale = glm::vec3(gn.scale[0], gn.scale[1], gn.scale[2]);
    if (gn.skin >= 0 && size_t(gn.skin) >= model_.skins.size())
      failAt(ptr + "/skin",
             "skin " + std::to_string(gn.skin) + " does not exist (" + str(model_.skins.size()) + " skins)");
    n.skin = gn.skin;
    // Morph weights: all primitives of a mesh have the same number of
    // targets, which the mesh's and the node's "weights" match.
    if (gn.mesh < 0 || size_t(gn.mesh) >= model_.meshes.size()) continue;
    const tinygltf::Mesh& gm = model_.meshes[size_t(gn.mesh)];
    const std::string mptr = "/meshes/" + std::to_string(gn.mesh);
    const size_t targets = gm.primitives.empty() ? 0 : gm.primitives[0].targets.size();
    for (size_t p = 1; p < gm.primitives.size(); ++p)
      if (gm.primitives[p].targets.size() != targets)
        failAt(mptr + "/primitives/" + str(p) + "/targets", "has " + str(gm.primitives[p].targets.size()) +
                                                                " morph targets, primitive 0 has " + str(targets) +
                                                                " (every primitive of a mesh must have as many)");
    auto weights = [&](const std::vector<double>& w, const std::string& wptr) {
      if (w.size() != targets) failAt(wptr, "has " + str(w.size()) + " weights for " + str(targets) + " morph targets");
      for (double d : w)
        if (!std::isfinite(d) || std::abs(d) > 3.0e38) failAt(wptr, "has a non-finite weight");
      return std::vector<float>(w.begin(), w.end());
    };
    if (!gn.weights.empty())
      n.weights = weights(gn.weights, ptr + "/weights");
    else if (!gm.weights.empty())
      n.weights = weights(gm.weights, mptr + "/weights");
    else
      n.weights.assign(targets, 0.0f);
  }
  // A cycle outside the default scene (traverse saw only the scene's nodes)
  // leaves its nodes out of the evaluation order.
  out.updateLayout();
  if (out.order.size() != count) {
    std::vector<char> seen(count, 0);
    for (int i : out.order) seen[size_t(i)] = 1;
    const size_t first = size_t(std::find(seen.begin(), seen.end(), 0) - seen.begin());
    failAt("/nodes/" + str(first), "is its own ancestor (cycle in the node hierarchy)");
  }
}

void GltfLoader::loadSkins(SceneAnimation& out) {
  for (size_t si = 0; si < model_.skins.size(); ++si) {
    const tinygltf::Skin& gs = model_.skins[si];
    const std::string ptr = "/skins/" + str(si);
    SceneSkin s;
    s.name = gs.name;
    if (gs.joints.empty()) failAt(ptr + "/joints", "a skin needs at least one joint");
    for (size_t j = 0; j < gs.joints.size(); ++j) {
      const int node = gs.joints[j];
      if (node < 0 || size_t(node) >= model_.nodes.size())
        failAt(ptr + "/joints/" + str(j),
               "node " + std::to_string(node) + " does not exist (" + str(model_.nodes.size()) + " nodes)");
      s.joints.push_back(node);
    }
    if (gs.skeleton >= 0 && size_t(gs.skeleton) >= model_.nodes.size())
      failAt(ptr + "/skeleton",
             "node " + std::to_string(gs.skeleton) + " does not exist (" + str(model_.nodes.size()) + " nodes)");
    s.skeleton = gs.skeleton;
    s.inverseBindMatrices.assign(s.joints.size(), glm::mat4(1.0f));  // glTF: identity when absent
    if (gs.inverseBindMatrices >= 0) {
      const std::string iptr = ptr + "/inverseBindMatrices";
      const std::vector<float> m = readFinite(gs.inverseBindMatrices, iptr, "skin " + str(si) + " inverseBindMatrices",
                                              {TINYGLTF_TYPE_MAT4}, {F});
      if (m.size() / 16 < s.joints.size())
        failAt(iptr, "has " + str(m.size() / 16) + " matrices for " + str(s.joints.size()) + " joints");
      for (size_t j = 0; j < s.joints.size(); ++j)
        for (int c = 0; c < 4; ++c)
          for (int r = 0; r < 4; ++r) s.inverseBindMatrices[j][c][r] = m[16 * j + size_t(4 * c + r)];
    }
    out.skins.push_back(std::move(s));
  }
}

// Every joint index a skinned node's primitives use lies within its skin
// (each mesh's largest index found once: many nodes may share one mesh).
void GltfLoader::checkSkinnedMeshes(const SceneAnimation& anim) {
  std::vector<int> largest(scene_.meshes.size(), -2);  // -2: not looked at yet
  auto largestJoint = [&](size_t mesh) {
    if (largest[mesh] == -2) {
      largest[mesh] = -1;
      for (const SkinInfluences& set : scene_.meshes[mesh].influences)
        for (const glm::u16vec4& j : set.joints)
          largest[mesh] = std::max({largest[mesh], int(j.x), int(j.y), int(j.z), int(j.w)});
    }
    return largest[mesh];
  };
  for (size_t ni = 0; ni < model_.nodes.size(); ++ni) {
    const tinygltf::Node& gn = model_.nodes[ni];
    if (gn.skin < 0 || gn.mesh < 0 || size_t(gn.mesh) >= model_.meshes.size()) continue;
    const size_t joints = anim.skins[size_t(gn.skin)].joints.size();
    for (size_t pi = 0; pi < model_.meshes[size_t(gn.mesh)].primitives.size(); ++pi) {
      const auto it = meshMap_.find({gn.mesh, pi});
      if (it == meshMap_.end() || it->second < 0) continue;  // not drawn (or not in the scene)
      if (largestJoint(size_t(it->second)) < int(joints)) continue;
      const MeshData& m = scene_.meshes[size_t(it->second)];
      for (size_t set = 0; set < m.influences.size(); ++set)
        for (size_t v = 0; v < m.influences[set].joints.size(); ++v)
          for (int c = 0; c < 4; ++c)
            if (m.influences[set].joints[v][c] >= joints)
              failAt("/meshes/" + std::to_string(gn.mesh) + "/primitives/" + str(pi) + "/attributes/JOINTS_" + str(set),
                     "joint index " + std::to_string(m.influences[set].joints[v][c]) + " (vertex " + str(v) +
                         ") is outside skin " + std::to_string(gn.skin) + " of node " + str(ni) + ", which has " +
                         str(joints) + " joints");
    }
  }
}

// ------------------------------------------------------------ animations

void GltfLoader::loadAnimation(size_t index, SceneAnimation& out) {
  const tinygltf::Animation& ga = model_.animations[index];
  const std::string ptr = "/animations/" + str(index);
  Animation a;
  a.name = ga.name;
  std::vector<int> outputType(ga.samplers.size(), 0);  // the output accessor's type
  for (size_t si = 0; si < ga.samplers.size(); ++si) {
    const tinygltf::AnimationSampler& gs = ga.samplers[si];
    const std::string sptr = ptr + "/samplers/" + str(si);
    AnimationSampler s;
    if (gs.interpolation == "STEP")
      s.interpolation = Interpolation::step;
    else if (gs.interpolation == "LINEAR" || gs.interpolation.empty())
      s.interpolation = Interpolation::linear;
    else if (gs.interpolation == "CUBICSPLINE")
      s.interpolation = Interpolation::cubicSpline;
    else
      failAt(sptr + "/interpolation", "unknown interpolation '" + gs.interpolation + "' (STEP, LINEAR or CUBICSPLINE)");
    // Samplers may share one large accessor: bound what they copy together,
    // before copying it.
    for (const int a : {gs.input, gs.output})
      if (a >= 0 && size_t(a) < model_.accessors.size())
        animationValues_ +=
            model_.accessors[size_t(a)].count *
            size_t(std::max(0, tinygltf::GetNumComponentsInType(uint32_t(model_.accessors[size_t(a)].type))));
    if (animationValues_ > kMaxAnimationValues)
      failAt(sptr, "the animations hold more than " + str(kMaxAnimationValues) + " key times and values in all");
    s.times = readFinite(gs.input, sptr + "/input", "animation " + str(index) + " sampler " + str(si) + " input",
                         {TINYGLTF_TYPE_SCALAR}, {F});
    if (s.times.empty()) failAt(sptr + "/input", "has no keyframes");
    for (size_t k = 0; k < s.times.size(); ++k) {
      if (s.times[k] < 0.0f)
        failAt(sptr + "/input", "key " + str(k) + " is at a negative time (" + std::to_string(s.times[k]) + " s)");
      if (k > 0 && !(s.times[k] > s.times[k - 1]))
        failAt(sptr + "/input", "key times must increase strictly: key " + str(k) + " (" + std::to_string(s.times[k]) +
                                    " s) does not come after key " + str(k - 1) + " (" +
                                    std::to_string(s.times[k - 1]) + " s)");
    }
    if (s.interpolation == Interpolation::cubicSpline && s.times.size() < 2)
      failAt(sptr + "/input", "CUBICSPLINE needs at least 2 keyframes");
    s.values = readFinite(gs.output, sptr + "/output", "animation " + str(index) + " sampler " + str(si) + " output",
                          {TINYGLTF_TYPE_SCALAR, TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4}, {F, B, UB, S, US});
    outputType[si] = model_.accessors[size_t(gs.output)].type;

    a.duration = std::max(a.duration, double(s.times.back()));
    a.samplers.push_back(std::move(s));
  }
  for (size_t ci = 0; ci < ga.channels.size(); ++ci) {
    const tinygltf::AnimationChannel& gc = ga.channels[ci];
    const std::string cptr = ptr + "/channels/" + str(ci);
    AnimationChannel c;
    if (gc.target_path == "translation")
      c.path = AnimationPath::translation;
    else if (gc.target_path == "rotation")
      c.path = AnimationPath::rotation;
    else if (gc.target_path == "scale")
      c.path = AnimationPath::scale;
    else if (gc.target_path == "weights")
      c.path = AnimationPath::weights;
    else {
      warnAt(cptr + "/target/path", "animation path '" + gc.target_path + "' is not supported; the channel is ignored");
      continue;
    }
    if (gc.target_node < 0 || size_t(gc.target_node) >= out.nodes.size())
      failAt(cptr + "/target/node",
             "node " + std::to_string(gc.target_node) + " does not exist (" + str(out.nodes.size()) + " nodes)");
    if (gc.sampler < 0 || size_t(gc.sampler) >= a.samplers.size())
      failAt(cptr + "/sampler",
             "sampler " + std::to_string(gc.sampler) + " does not exist (" + str(a.samplers.size()) + " samplers)");
    c.node = gc.target_node;
    c.sampler = gc.sampler;
    const SceneNode& node = out.nodes[size_t(c.node)];
    if (node.hasMatrix)
      failAt(cptr + "/target/node", "node " + std::to_string(c.node) +
                                        " is given by a matrix; glTF animates only nodes given by "
                                        "translation, rotation and scale");
    AnimationSampler& s = a.samplers[size_t(c.sampler)];
    const std::string sptr = ptr + "/samplers/" + std::to_string(c.sampler) + "/output";
    const int wantType = c.path == AnimationPath::weights    ? TINYGLTF_TYPE_SCALAR
                         : c.path == AnimationPath::rotation ? TINYGLTF_TYPE_VEC4
                                                             : TINYGLTF_TYPE_VEC3;
    if (outputType[size_t(c.sampler)] != wantType)
      failAt(sptr, "a " + gc.target_path + " channel needs " +
                       (wantType == TINYGLTF_TYPE_SCALAR ? "SCALAR"
                        : wantType == TINYGLTF_TYPE_VEC4 ? "VEC4"
                                                         : "VEC3") +
                       " output");
    const uint32_t components = c.path == AnimationPath::weights    ? uint32_t(node.weights.size())
                                : c.path == AnimationPath::rotation ? 4u
                                                                    : 3u;
    if (components == 0)
      failAt(cptr + "/target/node",
             "animates the morph weights of node " + std::to_string(c.node) + ", whose mesh has no morph targets");
    // (A sampler shared by channels: its output type and count fix its
    // components, so they agree wherever these checks pass.)
    const size_t perKey = size_t(components) * (s.interpolation == Interpolation::cubicSpline ? 3 : 1);
    if (s.values.size() != s.times.size() * perKey) {
      const size_t elementSize = c.path == AnimationPath::weights ? 1 : components;  // floats per accessor element
      failAt(sptr, "has " + str(s.values.size() / elementSize) + " elements for " + str(s.times.size()) + " keys; " +
                       interpolationName(s.interpolation) + " " + gc.target_path + " needs " +
                       str(s.times.size() * perKey / elementSize));
    }
    if (c.path == AnimationPath::rotation && s.components == 0) {
      // Unit quaternions: keys (not cubic tangents) normalized, zero-length ones refused.
      const bool cubic = s.interpolation == Interpolation::cubicSpline;
      for (size_t k = 0; k < s.times.size(); ++k) {
        float* q = s.values.data() + (cubic ? 3 * k + 1 : k) * 4;
        const double len =
            std::sqrt(double(q[0]) * q[0] + double(q[1]) * q[1] + double(q[2]) * q[2] + double(q[3]) * q[3]);
        if (!(len > 1e-12)) failAt(sptr, "rotation key " + str(k) + " is a zero quaternion");
        for (int i = 0; i < 4; ++i) q[i] = float(q[i] / len);
      }
    }
    s.components = components;
    a.channels.push_back(c);
  }
  out.animations.push_back(std::move(a));
}

}  // namespace rgraph::gltf_detail
