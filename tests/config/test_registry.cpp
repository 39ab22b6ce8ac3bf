#include "test_registry.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rgraph/format_sets.h"

namespace rgraph::test {
namespace {

class NoopPass : public PassInstance {
 public:
  void execute(PassContext&) override {}
};

SlotDecl slot(std::string name, Access access, bool required = true, SlotDecl::Load load = SlotDecl::Load::never,
              std::vector<Format> formats = {}, bool msaa = false) {
  SlotDecl s;
  s.name = std::move(name);
  s.access = access;
  s.required = required;
  s.load = load;
  s.formats = std::move(formats);
  s.acceptsMultisample = msaa;
  return s;
}

ParamDecl param(std::string name, ParamType type, ParamValue def, std::optional<double> min = {},
                std::optional<double> max = {}, std::vector<std::string> choices = {}) {
  ParamDecl p;
  p.name = std::move(name);
  p.type = type;
  p.defaultValue = std::move(def);
  p.min = min;
  p.max = max;
  p.choices = std::move(choices);
  return p;
}

PassTypeDesc type(std::string name, std::vector<SlotDecl> slots, std::vector<ParamDecl> params = {},
                  bool sideEffect = false) {
  PassTypeDesc t;
  t.name = std::move(name);
  t.description = "test pass " + t.name;
  t.slots = std::move(slots);
  t.params = std::move(params);
  t.sideEffect = sideEffect;
  t.create = [] { return std::make_unique<NoopPass>(); };
  return t;
}

PassRegistry makeRegistry() {
  using L = SlotDecl::Load;
  PassRegistry r;
  std::vector<PassTypeDesc> types;
  types.push_back(type("fullscreen",
                       {slot("source", Access::sampled), slot("aux", Access::sampled, false),
                        slot("color", Access::color_attachment, true, L::optional)},
                       {param("exposure", ParamType::number, 1.0, 0.0, 10.0)}));
  types.push_back(
      type("geometry",
           {slot("color", Access::color_attachment, true, L::never,
                 {Format::rgba8, Format::rgba16f, Format::srgb8_alpha8}, true),
            slot("depth", Access::depth_attachment, true, L::never,
                 depthFormats(), true)}));
  types.push_back(type("blit", {slot("src", Access::blit_src), slot("dst", Access::blit_dst, true, L::optional)}));
  types.push_back(type(
      "blend", {slot("color", Access::color_attachment, true, L::required), slot("overlay", Access::sampled, false)}));
  types.push_back(
      type("resolve", {slot("src", Access::sampled, true, L::never, {}, true), slot("dst", Access::color_attachment)}));
  types.push_back(type("readback", {slot("src", Access::sampled)}, {}, true));
  types.push_back(type("decal", {slot("color", Access::color_attachment, false, L::optional)}));
  types.push_back(
      type("histogram", {slot("image", Access::sampled), slot("bins", Access::storage_write, true, L::optional)}));
  types.push_back(type(
      "tweak", {slot("color", Access::color_attachment)},
      {param("flag", ParamType::boolean, false), param("count", ParamType::integer, int64_t{4}, 0, 16),
       param("gain", ParamType::number, 1.0, 0.0, 10.0), param("label", ParamType::string, std::string("x")),
       param("mode", ParamType::enumeration, std::string("nice"), {}, {}, {"fast", "nice", "exact"}),
       param("tint", ParamType::vec3, std::vector<double>{1, 1, 1}, 0.0, 1.0),
       param("rect", ParamType::vec4, std::vector<double>{0, 0, 1, 1}), param("bias", ParamType::number, 0.0, -1.0),
       param("big", ParamType::integer, int64_t{0}), param("program", ParamType::shader, std::string("x.frag"))}));
  for (auto& t : types) {
    std::string error;
    if (!r.add(std::move(t), &error)) throw std::logic_error("test registry: " + error);
  }
  return r;
}

}  // namespace

const PassRegistry& testRegistry() {
  static const PassRegistry registry = makeRegistry();
  return registry;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace rgraph::test
