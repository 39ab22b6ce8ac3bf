// RenderScene: one scene's CPU data, its light edits and its one GPU upload,
// shared by every renderer drawing it (rgraph/renderer.h).
#include "../scene/environment_problem.h"
#include "render_scene_impl.h"
#include "rgraph/error.h"
#include "rgraph/gl/gpu_scene.h"
#include "rgraph/renderer.h"

namespace rgraph {

namespace {
// What a scene built in code may leave out and loaders fill in (renderer.h,
// fromScene): bounds from the geometry, light radii from the attenuation.
// What is there already (a loader's, the caller's) is kept.
void deriveSceneFacts(Scene& scene) {
  for (MeshData& mesh : scene.meshes)
    if (mesh.bounds.empty()) mesh.updateBounds();
  for (Primitive& p : scene.primitives)
    if (p.bounds.empty()) p.bounds = p.worldBounds(scene.meshes[size_t(p.mesh)].bounds);
  for (PointLight& l : scene.pointLights)
    if (l.radius == 0.0f) l.radius = lightRadius(l);
}
}  // namespace

RenderScene::RenderScene() : impl_(std::make_unique<Impl>()) {}
RenderScene::~RenderScene() = default;

std::shared_ptr<RenderScene> RenderScene::load(const std::string& spec) { return fromScene(loadSceneAny(spec)); }

std::shared_ptr<RenderScene> RenderScene::fromScene(Scene scene) {
  scene.validate();
  if (scene.pointLights.size() + scene.directionalLights.size() > kMaxSceneLights)
    throw RuntimeError((scene.source.empty() ? std::string("scene") : scene.source) + ": " +
                       std::to_string(scene.pointLights.size() + scene.directionalLights.size()) +
                       " lights, more than the " + std::to_string(kMaxSceneLights) + " a scene may have");
  deriveSceneFacts(scene);
  std::shared_ptr<RenderScene> s(new RenderScene());
  s->impl_->scene = std::move(scene);
  s->impl_->numberPrimitives();  // each primitive an object the API can move
  // Animated scenes start at rest (skinned and morphed objects' bounds then cover their rest pose).
  if (!s->impl_->scene.animation.empty()) s->impl_->applyPose(0.0, kRestPose);
  return s;
}

const Scene& RenderScene::scene() const { return impl_->scene; }
size_t RenderScene::pointLightCount() const { return impl_->scene.pointLights.size(); }

const PointLight& RenderScene::pointLight(size_t index) const {
  impl_->checkIndex(index, "pointLight");
  return impl_->scene.pointLights[index];
}

void RenderScene::setPointLight(size_t index, const PointLight& light) {
  impl_->checkIndex(index, "setPointLight");
  validatePointLight(light, index, impl_->where());
  impl_->scene.pointLights[index] = light;
  impl_->lightsEdited();
}

size_t RenderScene::addPointLight(const PointLight& light) {
  Scene& s = impl_->scene;
  const size_t index = s.pointLights.size();
  if (index + s.directionalLights.size() >= kMaxSceneLights)
    throw RuntimeError(impl_->where() + ": cannot add a light: the scene has the most a scene may have (" +
                       std::to_string(kMaxSceneLights) + ")");
  validatePointLight(light, index, impl_->where());
  s.pointLights.push_back(light);
  impl_->lightsEdited();
  return index;
}

void RenderScene::removePointLight(size_t index) {
  impl_->checkIndex(index, "removePointLight");
  impl_->scene.pointLights.erase(impl_->scene.pointLights.begin() + static_cast<std::ptrdiff_t>(index));
  impl_->lightsEdited();
}

void RenderScene::setPointLights(std::vector<PointLight> lights) {
  if (lights.size() + impl_->scene.directionalLights.size() > kMaxSceneLights)
    throw RuntimeError(impl_->where() + ": " + std::to_string(lights.size()) + " point lights, more than a scene may have (" +
                       std::to_string(kMaxSceneLights) + " lights in all)");
  for (size_t i = 0; i < lights.size(); ++i) validatePointLight(lights[i], i, impl_->where());
  impl_->scene.pointLights = std::move(lights);
  impl_->lightsEdited();
}

void RenderScene::setDirectionalLights(std::vector<DirectionalLight> lights) {
  if (lights.size() + impl_->scene.pointLights.size() > kMaxSceneLights)
    throw RuntimeError(impl_->where() + ": too many lights (" + std::to_string(kMaxSceneLights) + " in all)");
  for (size_t i = 0; i < lights.size(); ++i) validateDirectionalLight(lights[i], i, impl_->where());
  impl_->scene.directionalLights = std::move(lights);
  impl_->lightsEdited();
}

void RenderScene::setAmbient(const glm::vec3& ambient) {
  validateAmbient(ambient, impl_->where());
  impl_->scene.ambient = ambient;
  impl_->lightsEdited();
}

uint64_t RenderScene::lightsVersion() const { return impl_->lightsVersion; }

void RenderScene::setEnvironment(std::optional<Environment> environment) {
  if (environment)
    if (const auto problem = environmentProblem(*environment)) throw RuntimeError(impl_->where() + ": " + *problem);
  impl_->scene.environment = std::move(environment);
  ++impl_->environmentVersion;
}

uint64_t RenderScene::environmentVersion() const { return impl_->environmentVersion; }

GpuScene& RenderScene::gpu() {
  if (!impl_->gpu) {
    impl_->gpu = std::make_unique<GpuScene>(impl_->scene);
    ++impl_->uploads;
    if (impl_->gpu->deforms()) impl_->gpu->setPose(impl_->pose.joints, impl_->pose.weights);
    for (size_t i = 0; i < impl_->hidden.size(); ++i)
      if (impl_->hidden[i]) impl_->gpu->setVisible(i, false);
  } else {
    impl_->gpu->requireUploadContext("RenderScene::gpu");
  }
  return *impl_->gpu;
}

uint64_t RenderScene::uploadCount() const { return impl_->uploads; }

}  // namespace rgraph
