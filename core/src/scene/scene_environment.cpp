// Environments (Scene::environment): the radiance function the IBL passes
// pre-filter, the .hdr loader and the CLI's --environment values. The
// shaders' copy of environmentRadiance is shaders/include/environment.glsl:
// the IBL oracle tests integrate this one on the CPU and compare.
#include <algorithm>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <vector>

#include <glm/glm.hpp>
#include <stb_image.h>

#include "rgraph/error.h"
#include "environment_problem.h"
#include "image_bytes.h"
#include "rgraph/scene.h"

namespace rgraph {

namespace {

// An 8k equirectangular map is 8192x4096; twice that is room to spare, and
// bounds what a hostile header can make us allocate.
constexpr int kMaxEnvironmentSide = 16384;

constexpr float kPi = 3.14159265358979f;

glm::vec3 skyRadiance(const Environment& env, const glm::vec3& d) {
  const float e = d.y;
  glm::vec3 c = e >= 0.0f ? glm::mix(env.horizon, env.zenith, std::sqrt(e))
                          : glm::mix(env.horizon, env.ground, std::min(1.0f, -e * 8.0f));
  const float r = glm::radians(env.sunRadiusDeg);
  const float angle = std::acos(std::clamp(glm::dot(d, glm::normalize(env.sunDirection)), -1.0f, 1.0f));
  const float t = std::clamp((r - angle) / (0.2f * r), 0.0f, 1.0f);
  return c + env.sunColor * t;
}

glm::vec3 hdrRadiance(const Environment& env, const glm::vec3& d) {
  if (env.width == 0 || env.height == 0) return glm::vec3(0.0f);
  const float u = 0.5f + std::atan2(d.x, -d.z) / (2.0f * kPi);
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
  const auto x = std::min<uint32_t>(env.width - 1, static_cast<uint32_t>(std::max(0.0f, u * float(env.width))));
  const auto y = std::min<uint32_t>(env.height - 1, static_cast<uint32_t>(std::max(0.0f, v * float(env.height))));
  const float* p = &env.rgb[(size_t(y) * env.width + x) * 3];
  return {p[0], p[1], p[2]};
}

bool finiteNonNegative(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f;
}

}  // namespace

std::optional<std::string> environmentProblem(const Environment& env) {
  if (!(std::isfinite(env.intensity) && env.intensity >= 0.0f)) return "environment intensity must be finite and >= 0";
  if (!finiteNonNegative(env.color)) return "environment color must be finite and >= 0";
  if (env.kind == Environment::Kind::sky) {
    if (!finiteNonNegative(env.sunColor) || !finiteNonNegative(env.zenith) || !finiteNonNegative(env.horizon) ||
        !finiteNonNegative(env.ground))
      return "environment sky colours must be finite and >= 0";
    const float len = glm::length(env.sunDirection);
    if (!(len > 0.0f) || !std::isfinite(len)) return "environment sun direction must be a finite, non-zero vector";
    if (!(env.sunRadiusDeg > 0.0f && env.sunRadiusDeg <= 45.0f)) return "environment sun radius must be in (0, 45] degrees";
  }
  if (env.kind == Environment::Kind::hdr && (env.width == 0 || env.height == 0 ||
                                             env.rgb.size() != size_t(env.width) * env.height * 3))
    return "an hdr environment needs width x height RGB pixels";
  return std::nullopt;
}

glm::vec3 environmentRadiance(const Environment& env, const glm::vec3& d) {
  switch (env.kind) {
    case Environment::Kind::uniform: return env.color * env.intensity;
    case Environment::Kind::sky: return skyRadiance(env, d) * env.intensity;
    case Environment::Kind::hdr: return hdrRadiance(env, d) * env.intensity;
  }
  return glm::vec3(0.0f);
}

void loadEnvironmentHdr(Environment& env, const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw RuntimeError(path + ": environment image not found");
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw RuntimeError(path + ": cannot read the environment image");
  if (bytes.size() > size_t(INT_MAX)) throw RuntimeError(path + ": the environment image is too large");
  if (const auto why = image_bytes::problem(bytes.data(), bytes.size(), /*allowHdr=*/true))
    throw RuntimeError(path + ": cannot read the environment image (" + *why + ")");
  int w = 0, h = 0, comp = 0;
  const int n = int(bytes.size());
  if (!stbi_info_from_memory(bytes.data(), n, &w, &h, &comp))
    throw RuntimeError(path + ": cannot read the environment image (" + stbi_failure_reason() + ")");
  if (w <= 0 || h <= 0 || w > kMaxEnvironmentSide || h > kMaxEnvironmentSide)
    throw RuntimeError(path + ": the environment image is " + std::to_string(w) + "x" + std::to_string(h) +
                       " (at most " + std::to_string(kMaxEnvironmentSide) + " on a side)");
  float* px = stbi_loadf_from_memory(bytes.data(), n, &w, &h, &comp, 3);
  if (!px) throw RuntimeError(path + ": cannot read the environment image (" + stbi_failure_reason() + ")");
  env.kind = Environment::Kind::hdr;
  env.file = path;
  env.width = static_cast<uint32_t>(w);
  env.height = static_cast<uint32_t>(h);
  env.rgb.assign(px, px + size_t(w) * size_t(h) * 3);
  stbi_image_free(px);
  for (float f : env.rgb)
    if (!std::isfinite(f) || f < 0.0f)
      throw RuntimeError(path + ": the environment image holds a value that is negative or not finite");
}

Environment environmentFromSpec(const std::string& spec) {
  Environment env;
  if (spec == "sky") {
    env.kind = Environment::Kind::sky;
    return env;
  }
  if (spec.rfind("color:", 0) == 0) {
    std::istringstream in(spec.substr(6));
    char c1 = 0, c2 = 0;
    glm::vec3 v{-1.0f};
    in >> v.x >> c1 >> v.y >> c2 >> v.z;
    if (!in || c1 != ',' || c2 != ',' || !in.eof() || !(v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f) ||
        !std::isfinite(v.x + v.y + v.z))
      throw RuntimeError("environment '" + spec + "': expected color:R,G,B with finite values >= 0");
    env.color = v;
    return env;
  }
  loadEnvironmentHdr(env, spec);
  return env;
}

}  // namespace rgraph
