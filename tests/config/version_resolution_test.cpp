// The loader resolves version names once, through the compiler: what it marks
// as the imported output image and the resources its slot-format messages
// name are what compile() resolves those names to (Plan::resources[].versions).
// Checked on random configs full of in-place versions, names written twice,
// loops, disabled pass-throughs and wrong formats, where a resolution of its
// own (the loader had one) answers differently from the compiler's.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <string>
#include <vector>

#include "test_registry.h"

namespace rgraph {
namespace {

class RandomConfig {
 public:
  explicit RandomConfig(uint32_t seed) : rng_(seed) {}

  std::string next() {
    const std::vector<std::string> formats = {"rgba8", "r32f", "depth24", "rgba16f", "srgb8_alpha8"};
    const std::vector<std::string> resources = {"a", "b", "c", "d", "e"};
    const size_t nRes = 1 + pick(resources.size());
    std::vector<std::string> names(resources.begin(), resources.begin() + static_cast<long>(nRes));
    for (const char* v : {"v1", "v2", "v3", "v4", "v5", "zz"}) names.push_back(v);
    auto name = [&] { return "\"" + names[pick(names.size())] + "\""; };

    std::string text = "{\"version\": 1, \"resources\": {";
    for (size_t r = 0; r < nRes; ++r)
      text += (r ? ", \"" : "\"") + resources[r] + "\": {\"format\": \"" + formats[pick(formats.size())] + "\"}";
    text += "},\n\"passes\": [\n";
    const size_t nPass = 1 + pick(8);
    for (size_t p = 0; p < nPass; ++p) {
      text += p ? ",\n{" : "{";
      text += "\"name\": \"p" + std::to_string(p) + "\", ";
      if (pick(6) == 0) text += "\"enabled\": false, ";
      switch (pick(5)) {
        case 0:
          text += "\"type\": \"fullscreen\", \"inputs\": {\"source\": " + name() +
                  (pick(2) ? ", \"color\": " + name() : std::string()) + "}, \"outputs\": {\"color\": " + name() + "}";
          break;
        case 1:
          text +=
              "\"type\": \"blend\", \"inputs\": {\"color\": " + name() + "}, \"outputs\": {\"color\": " + name() + "}";
          break;
        case 2:  // color and depth accept only their own formats; an input here is refused (output-only)
          text += "\"type\": \"geometry\", " + (pick(5) == 0 ? "\"inputs\": {\"color\": " + name() + "}, " : "") +
                  "\"outputs\": {\"color\": " + name() + ", \"depth\": " + name() + "}";
          break;
        case 3:
          text += "\"type\": \"blit\", \"inputs\": {\"src\": " + name() + (pick(2) ? ", \"dst\": " + name() : "") +
                  "}, \"outputs\": {\"dst\": " + name() + "}";
          break;
        default:
          text += "\"type\": \"decal\", " + (pick(2) ? "\"inputs\": {\"color\": " + name() + "}, " : "") +
                  "\"outputs\": {\"color\": " + name() + "}";
      }
      text += "}";
    }
    return text + "\n],\n\"output\": " + name() + "}\n";
  }

 private:
  size_t pick(size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng_); }
  std::mt19937 rng_;
};

// The resource whose versions (as compile() lists them) include `name`, or "".
std::string compiledResourceOf(const Plan& plan, const std::string& name) {
  for (const auto& r : plan.resources)
    for (const auto& v : r.versions)
      if (v == name) return r.name;
  return {};
}

TEST(VersionResolution, LoaderAndCompilerResolveEveryVersionNameAlike) {
  RandomConfig gen(20261130);
  size_t formatMessages = 0, outputsImported = 0, outputsUnresolved = 0;
  for (int i = 0; i < 3000; ++i) {
    const std::string text = gen.next();
    Diagnostics diags;
    ConfigDocument doc = ConfigDocument::parseText(text, "random.json", diags);
    ASSERT_TRUE(doc.ok()) << text;
    const PipelineConfig cfg = doc.build(test::testRegistry(), diags);
    const Plan plan = compile(cfg.graph);

    // The output image: exactly the resource compile() finds the output name in.
    const std::string expected = compiledResourceOf(plan, cfg.graph.output);
    std::set<std::string> imported;
    for (const auto& r : cfg.graph.resources)
      if (r.imported) {
        imported.insert(r.name);
        EXPECT_FALSE(r.importedHasContent) << r.name << "\n" << text;
      }
    EXPECT_EQ(imported, expected.empty() ? std::set<std::string>{} : std::set<std::string>{expected}) << text;
    (expected.empty() ? outputsUnresolved : outputsImported) += 1;

    // Slot formats: the resource a message names is the one compile() puts the bound name in.
    for (const auto& d : diags) {
      if (d.code != DiagCode::format_not_allowed) continue;
      ++formatMessages;
      const std::string owner = compiledResourceOf(plan, d.resource);
      ASSERT_FALSE(owner.empty()) << formatDiagnostic(d) << "\n" << text;
      const std::string named =
          d.resource == owner ? "of resource '" + owner + "'" : "(a version of resource '" + owner + "')";
      EXPECT_NE(d.message.find(named), std::string::npos) << formatDiagnostic(d) << "\n" << text;
    }
  }
  // The random configs reach every case above many times.
  EXPECT_GT(formatMessages, 500u);
  EXPECT_GT(outputsImported, 500u);
  EXPECT_GT(outputsUnresolved, 500u);
}

}  // namespace
}  // namespace rgraph
