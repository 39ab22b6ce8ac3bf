// ConfigDocument::build: checks a parsed pipeline config against the schema
// and the pass declarations, and builds the GraphDesc. Every problem becomes a
// diagnostic with file, line, column and JSON path; checking goes on after an
// error so that one run reports as much as possible. Graph-level checks
// (unknown resource names, read-before-write, cycles...) belong to compile().
//
// The Builder (config_builder.h) is split by subject: this file holds the top
// level and the checks across resources and passes (slot formats, on the
// versions as the compiler resolves them).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "config_builder.h"

namespace rgraph::config_detail {

namespace {

const std::vector<std::string> kTopLevelKeys = {"version", "description", "plugins", "resources",
                                                "passes",  "output",      "jitter"};

// Every version name of the compiled plan -> its resource (views of the
// plan's strings: the plan must outlive the map).
VersionResources versionResources(const Plan& plan) {
  VersionResources out;
  for (size_t r = 0; r < plan.resources.size(); ++r)
    for (const std::string& v : plan.resources[r].versions) out.emplace(v, r);
  return out;
}

}  // namespace

PipelineConfig Builder::run() {
  size_t firstNew = diags_.size();
  config_.file = doc_.file();
  if (!root_.is_object()) {
    error(DiagCode::config_schema, doc_.locate(""), "the top level must be an object, got " + jsonTypeName(root_));
  } else {
    checkTopLevel();
  }
  reportDuplicateKeys();
  // Diagnostics in the order a reader meets them in the file.
  std::stable_sort(diags_.begin() + static_cast<std::ptrdiff_t>(firstNew), diags_.end(),
                   [](const Diagnostic& a, const Diagnostic& b) {
                     if (a.where.line != b.where.line) return a.where.line < b.where.line;
                     return a.where.column < b.where.column;
                   });
  return std::move(config_);
}

// Unknown members of an object are errors pointing at the key. Returns the
// keys suggested instead ("did you mean"): a missing key that was suggested
// is not reported again, the typo explains it.
std::set<std::string> Builder::checkKeys(const Json& object, const std::string& pointer,
                                         const std::vector<std::string>& allowed, const std::string& what) {
  std::set<std::string> suggested;
  for (auto it = object.begin(); it != object.end(); ++it) {
    if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
    std::string best = closestMatch(it.key(), allowed);
    std::string message = "unknown " + what + " '" + it.key() + "'";
    if (best.empty())
      message += "; expected one of " + quotedList(allowed);
    else
      message += " (did you mean '" + best + "'?)";
    error(DiagCode::config_schema, keyAt(pointer + "/" + escapePointerToken(it.key())), message);
    if (!best.empty() && !object.contains(best)) suggested.insert(best);
  }
  return suggested;
}

void Builder::reportDuplicateKeys() {
  const auto& pointers = map_.duplicateKeys();
  for (size_t i = 0; i < pointers.size(); ++i) {
    config_detail::LineColumn lc = map_.position(map_.duplicateKeyOffsets()[i]);
    std::string token = pointers[i].substr(pointers[i].rfind('/') + 1), key;
    for (size_t c = 0; c < token.size(); ++c) {  // undo the pointer escapes ~1 and ~0
      if (token[c] == '~' && c + 1 < token.size())
        key += token[++c] == '1' ? '/' : '~';
      else
        key += token[c];
    }
    error(DiagCode::config_schema, {doc_.file(), lc.line, lc.column, pointers[i]},
          "key '" + key + "' appears more than once in this object");
  }
}

// ------------------------------------------------------------ top level

void Builder::checkTopLevel() {
  std::set<std::string> typos = checkKeys(root_, "", kTopLevelKeys, "top-level key");
  auto missing = [&](const char* key, const std::string& what) {
    if (typos.count(key)) return;
    error(DiagCode::config_schema, at(""), std::string("missing required key '") + key + "' (" + what + ")");
  };

  if (auto it = root_.find("version"); it == root_.end()) {
    missing("version", "the format version, 1");
  } else {
    IntegerValue v = readInteger(*it);
    if (v.status == IntegerValue::Status::not_a_number)
      typeError("/version", "an integer", *it);
    else if (v.status != IntegerValue::Status::ok || v.value != 1)
      error(DiagCode::config_schema, at("/version"),
            "unsupported version " + describeValue(*it) + ": this rgraph reads version 1");
    else
      config_.version = 1;
  }

  if (auto it = root_.find("description"); it != root_.end() && !it->is_string())
    typeError("/description", "a string", *it);

  if (auto it = root_.find("plugins"); it != root_.end()) {
    if (!it->is_array()) {
      typeError("/plugins", "an array of plugin names or paths", *it);
    } else {
      for (size_t i = 0; i < it->size(); ++i) {
        const Json& p = (*it)[i];
        if (p.is_string() && !p.get<std::string>().empty())
          config_.plugins.push_back(p.get<std::string>());
        else if (p.is_string())
          error(DiagCode::config_schema, at("/plugins/" + std::to_string(i)), "empty plugin name");
        else
          typeError("/plugins/" + std::to_string(i), "a plugin name or path (string)", p);
      }
    }
  }

  // Sub-pixel camera jitter: Halton(2,3) phases. One phase would be a fixed
  // offset, not jitter; more than 64 converge no better in a 8-16 frame history.
  if (auto it = root_.find("jitter"); it != root_.end()) {
    int64_t n = 0;
    if (readInteger(*it).status == IntegerValue::Status::not_a_number)
      typeError("/jitter", "an integer (0: off, or 2 to 64 Halton phases)", *it);
    else if (std::string why = integerInRange(*it, "jitter", 0, 64, n, "phases", " (0: off)"); !why.empty())
      error(DiagCode::config_schema, at("/jitter"), why);
    else if (n == 1)
      error(DiagCode::config_schema, at("/jitter"),
            "jitter 1 is a fixed offset, not jitter: use 0 (off) or 2 to 64 Halton phases (8 or 16 are usual)");
    else
      config_.jitterPhases = static_cast<uint32_t>(n);
  }

  if (auto it = root_.find("resources"); it == root_.end())
    missing("resources", "an object of resource declarations");
  else if (!it->is_object())
    typeError("/resources", "an object of resource declarations", *it);
  else
    checkResources(*it);

  if (auto it = root_.find("passes"); it == root_.end())
    missing("passes", "an array of passes");
  else if (!it->is_array())
    typeError("/passes", "an array of passes", *it);
  else
    checkPasses(*it);

  GraphDesc& g = config_.graph;
  bool outputNamed = false;
  if (auto it = root_.find("output"); it == root_.end()) {
    missing("output", "the name of the resource that becomes the output image");
  } else if (!it->is_string()) {
    typeError("/output", "a resource name (string)", *it);
  } else {
    g.output = it->get<std::string>();
    g.outputWhere = at("/output");
    outputNamed = true;
  }

  // Version names resolve as the compiler resolves them (one resolution
  // for the loader and the graph): compile() on the graph built so far, its
  // diagnostics left to the caller's compile(). The loader needs the answer
  // before that compile, for the slot formats and the output image. Names it
  // cannot resolve (unknown, naming loops) are left to compile() as well.
  CompileOptions options;
  options.alias = false;  // only the version chains are read
  const Plan plan = compile(g, options);
  const VersionResources versions = versionResources(plan);
  checkFormats(versions);
  // The output image is the caller's: imported, never aliased, no content
  // before the first write.
  if (auto r = versions.find(g.output); outputNamed && r != versions.end()) {
    g.resources[r->second].imported = true;
    g.resources[r->second].importedHasContent = false;
  }
}

// ------------------------------------------------------------ formats

void Builder::checkFormats(const VersionResources& versions) {
  const GraphDesc& g = config_.graph;
  for (size_t i = 0; i < passInfo_.size(); ++i) {
    const PassInfo& info = passInfo_[i];
    if (!info.type) continue;
    for (const SlotDecl& slot : info.type->slots) {
      if (slot.formats.empty()) continue;
      std::vector<const Binding*> bound;
      if (auto in = info.inputs.find(slot.name); in != info.inputs.end()) bound.push_back(&in->second);
      if (auto out = info.outputs.find(slot.name); out != info.outputs.end()) bound.push_back(&out->second);
      for (const Binding* b : bound) {
        auto r = versions.find(b->name);
        if (r == versions.end() || !formatOk_[r->second]) continue;
        const ResourceDecl& res = g.resources[r->second];
        if (res.kind != ResourceKind::texture) continue;
        if (std::find(slot.formats.begin(), slot.formats.end(), res.texture.format) != slot.formats.end()) continue;
        std::vector<std::string> accepted;
        for (Format f : slot.formats) accepted.emplace_back(formatName(f));
        std::string of = b->name == res.name ? "resource '" + res.name + "'"
                                             : "'" + b->name + "' (a version of resource '" + res.name + "')";
        Diagnostic& d = error(DiagCode::format_not_allowed, at(b->pointer),
                              "slot '" + slot.name + "' of " + info.label + " does not accept format " +
                                  std::string(formatName(res.texture.format)) + " of " + of + "; it accepts " +
                                  quotedList(accepted));
        d.pass = g.passes[i].name;
        d.slot = slot.name;
        d.resource = b->name;
        break;  // one report per slot
      }
    }
  }
}

}  // namespace rgraph::config_detail

namespace rgraph {

PipelineConfig ConfigDocument::build(const PassRegistry& registry, Diagnostics& diags) const {
  if (!ok()) {
    PipelineConfig empty;
    empty.file = file();
    return empty;
  }
  return config_detail::Builder(*this, impl_->root, impl_->map, registry, diags).run();
}

}  // namespace rgraph
