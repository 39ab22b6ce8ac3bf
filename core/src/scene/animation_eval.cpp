// Evaluating glTF animations on the CPU (rgraph/animation.h): sampling a
// channel at a time, the pose of every node, the joint matrices of every
// skin. GL-free, so that tests check what the renderer will upload against
// values derived by hand from the files' keyframes.
#include <algorithm>
#include <cmath>
#include <string>

#include "rgraph/animation.h"
#include "rgraph/error.h"

namespace rgraph {

const char* interpolationName(Interpolation i) {
  switch (i) {
    case Interpolation::step:
      return "STEP";
    case Interpolation::linear:
      return "LINEAR";
    case Interpolation::cubicSpline:
      return "CUBICSPLINE";
  }
  return "unknown";
}

glm::mat4 SceneNode::restMatrix() const {
  if (hasMatrix) return matrix;
  glm::mat4 m = glm::mat4_cast(rotation);
  m[0] *= scale.x;
  m[1] *= scale.y;
  m[2] *= scale.z;
  m[3] = glm::vec4(translation, 1.0f);
  return m;
}

std::span<const glm::mat4> Pose::skinJoints(const SceneAnimation& a, int skin) const {
  if (skin < 0 || size_t(skin) >= a.skins.size()) return {};
  const SceneSkin& s = a.skins[size_t(skin)];
  if (size_t(s.firstJoint) + s.joints.size() > joints.size()) return {};
  return {joints.data() + s.firstJoint, s.joints.size()};
}

std::span<const float> Pose::nodeWeights(const SceneAnimation& a, int node) const {
  if (node < 0 || size_t(node) >= a.nodes.size()) return {};
  const SceneNode& n = a.nodes[size_t(node)];
  if (size_t(n.firstWeight) + n.weights.size() > weights.size()) return {};
  return {weights.data() + n.firstWeight, n.weights.size()};
}

double loopTime(double seconds, double duration) {
  if (!(duration > 0.0) || !std::isfinite(seconds) || !std::isfinite(duration)) return 0.0;
  double t = std::fmod(seconds, duration);
  if (t < 0.0) t += duration;
  return t < duration ? t : 0.0;  // -tiny + duration may round up to duration
}

namespace {

void normalize4(float* q) {
  const double len = std::sqrt(double(q[0]) * q[0] + double(q[1]) * q[1] + double(q[2]) * q[2] + double(q[3]) * q[3]);
  if (len > 0.0)
    for (int i = 0; i < 4; ++i) q[i] = float(q[i] / len);
}

// glTF's slerp: along the shorter arc (b negated when a . b < 0); nearly
// equal keys fall back to a normalized lerp, where sin(angle) vanishes.
void slerp(const float* a, const float* b, double u, float* out) {
  double dot = 0.0;
  for (int i = 0; i < 4; ++i) dot += double(a[i]) * b[i];
  const double sign = dot < 0.0 ? -1.0 : 1.0;
  const double d = std::min(std::abs(dot), 1.0);
  double wa = 1.0 - u, wb = u;
  if (d < 1.0 - 1e-7) {
    const double angle = std::acos(d);
    const double s = std::sin(angle);
    wa = std::sin((1.0 - u) * angle) / s;
    wb = std::sin(u * angle) / s;
  }
  for (int i = 0; i < 4; ++i) out[i] = float(wa * a[i] + sign * wb * b[i]);
  normalize4(out);
}

}  // namespace

void sampleAnimation(const AnimationSampler& s, double t, bool rotation, float* out) {
  const size_t n = s.times.size();
  const size_t c = s.components;
  const bool cubic = s.interpolation == Interpolation::cubicSpline;
  // Key k's value (cubic keys are in-tangent, value, out-tangent).
  auto value = [&](size_t k) { return s.values.data() + (cubic ? 3 * k + 1 : k) * c; };
  if (n == 0 || s.values.size() < n * c * (cubic ? 3 : 1)) {
    std::fill(out, out + c, 0.0f);
    if (rotation && c == 4) out[3] = 1.0f;
    return;
  }
  size_t k = 0;
  double u = 0.0;
  if (t >= double(s.times.back())) {
    k = n - 1;
  } else if (t > double(s.times.front())) {
    k = size_t(
            std::upper_bound(s.times.begin(), s.times.end(), t, [](double x, float key) { return x < double(key); }) -
            s.times.begin()) -
        1;
    u = (t - double(s.times[k])) / (double(s.times[k + 1]) - double(s.times[k]));
  }
  if (u == 0.0 || s.interpolation == Interpolation::step) {
    std::copy(value(k), value(k) + c, out);
  } else if (s.interpolation == Interpolation::linear) {
    if (rotation && c == 4) {
      slerp(value(k), value(k + 1), u, out);
      return;
    }
    for (size_t i = 0; i < c; ++i) out[i] = float((1.0 - u) * value(k)[i] + u * value(k + 1)[i]);
  } else {
    // Hermite basis; tangents are per second, so times the key interval.
    const double td = double(s.times[k + 1]) - double(s.times[k]);
    const double u2 = u * u, u3 = u2 * u;
    const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    const float* v0 = value(k);
    const float* b0 = v0 + c;  // key k's out-tangent
    const float* v1 = value(k + 1);
    const float* a1 = v1 - c;  // key k+1's in-tangent
    for (size_t i = 0; i < c; ++i) out[i] = float(h00 * v0[i] + td * h10 * b0[i] + h01 * v1[i] + td * h11 * a1[i]);
  }
  if (rotation && c == 4) normalize4(out);
}

namespace {

void applyAnimation(const SceneAnimation& a, const Animation& anim, double seconds, Pose& out) {
  const double t = loopTime(seconds, anim.duration);
  float v[4];
  for (const AnimationChannel& ch : anim.channels) {
    if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size() || ch.node < 0 ||
        size_t(ch.node) >= a.nodes.size())
      continue;  // (the loader refuses these; a hand-made SceneAnimation may not)
    const AnimationSampler& s = anim.samplers[size_t(ch.sampler)];
    const size_t n = size_t(ch.node);
    switch (ch.path) {
      case AnimationPath::translation:
        if (s.components != 3) break;
        sampleAnimation(s, t, false, v);
        out.translation[n] = glm::vec3(v[0], v[1], v[2]);
        break;
      case AnimationPath::scale:
        if (s.components != 3) break;
        sampleAnimation(s, t, false, v);
        out.scale[n] = glm::vec3(v[0], v[1], v[2]);
        break;
      case AnimationPath::rotation:
        if (s.components != 4) break;
        sampleAnimation(s, t, true, v);
        out.rotation[n] = glm::quat(v[3], v[0], v[1], v[2]);  // glTF x,y,z,w; glm w,x,y,z
        break;
      case AnimationPath::weights: {
        const SceneNode& node = a.nodes[n];
        if (s.components != node.weights.size() || size_t(node.firstWeight) + node.weights.size() > out.weights.size())
          break;
        sampleAnimation(s, t, false, out.weights.data() + node.firstWeight);
        break;
      }
    }
  }
}

}  // namespace

void evaluatePose(const SceneAnimation& a, double seconds, int animation, Pose& out) {
  if (animation < kAllAnimations || animation >= int(a.animations.size()))
    throw RuntimeError("animation " + std::to_string(animation) + " does not exist (the scene has " +
                       std::to_string(a.animations.size()) + " animations)");
  const size_t n = a.nodes.size();
  out.translation.resize(n);
  out.rotation.resize(n);
  out.scale.resize(n);
  out.local.resize(n);
  out.world.resize(n);
  out.weights.assign(a.weightCount, 0.0f);
  for (size_t i = 0; i < n; ++i) {
    const SceneNode& node = a.nodes[i];
    out.translation[i] = node.translation;
    out.rotation[i] = node.rotation;
    out.scale[i] = node.scale;
    if (size_t(node.firstWeight) + node.weights.size() <= out.weights.size())
      std::copy(node.weights.begin(), node.weights.end(), out.weights.begin() + node.firstWeight);
  }
  if (animation >= 0) {
    applyAnimation(a, a.animations[size_t(animation)], seconds, out);
  } else if (animation == kAllAnimations) {
    for (const Animation& anim : a.animations) applyAnimation(a, anim, seconds, out);
  }
  for (size_t i = 0; i < n; ++i) {
    if (a.nodes[i].hasMatrix) {
      out.local[i] = a.nodes[i].matrix;
      continue;
    }
    glm::mat4 m = glm::mat4_cast(out.rotation[i]);
    m[0] *= out.scale[i].x;
    m[1] *= out.scale[i].y;
    m[2] *= out.scale[i].z;
    m[3] = glm::vec4(out.translation[i], 1.0f);
    out.local[i] = m;
  }
  for (int i : a.order) {
    const SceneNode& node = a.nodes[size_t(i)];
    out.world[size_t(i)] =
        (node.parent >= 0 ? out.world[size_t(node.parent)] : node.rootTransform) * out.local[size_t(i)];
  }
  out.joints.resize(a.jointCount);
  for (const SceneSkin& s : a.skins)
    for (size_t j = 0; j < s.joints.size() && s.firstJoint + j < out.joints.size(); ++j) {
      const glm::mat4 ibm = j < s.inverseBindMatrices.size() ? s.inverseBindMatrices[j] : glm::mat4(1.0f);
      const int node = s.joints[j];
      out.joints[s.firstJoint + j] = node >= 0 && size_t(node) < n ? out.world[size_t(node)] * ibm : ibm;
    }
}

Pose evaluatePose(const SceneAnimation& a, double seconds, int animation) {
  Pose p;
  evaluatePose(a, seconds, animation, p);
  return p;
}

}  // namespace rgraph
