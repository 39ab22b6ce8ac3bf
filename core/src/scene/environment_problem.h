// Why an environment (Scene::environment) is unusable, or nullopt: a negative
// or non-finite intensity, colour or sky value, a zero sun direction or a
// radius outside (0, 45] degrees, an hdr image whose pixels do not fill
// width x height. Scene::validate and RenderScene::setEnvironment refuse
// such an environment. Not installed.
#pragma once

#include <optional>
#include <string>

#include "rgraph/scene.h"

namespace rgraph {
std::optional<std::string> environmentProblem(const Environment& env);
}  // namespace rgraph
