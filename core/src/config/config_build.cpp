// ConfigDocument::build: checks a parsed pipeline config against the schema
// and the pass declarations, and builds the GraphDesc. Every problem becomes a
// diagnostic with file, line, column and JSON path; checking goes on after an
// error so that one run reports as much as possible. Graph-level checks
// (unknown resource names, read-before-write, cycles...) belong to compile().
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "config_impl.h"
#include "config_values.h"
#include "rgraph/registry.h"

namespace rgraph {
namespace {

using config_detail::describeValue;
using config_detail::didYouMean;
using config_detail::escapePointerToken;
using config_detail::formatNumber;
using config_detail::IntegerValue;
using config_detail::integerInRange;
using config_detail::jsonTypeName;
using config_detail::quotedList;
using config_detail::readInteger;

// Local copies of the access helpers so that the loader does not depend on
// the graph compiler's sources.
bool writes(Access a) {
  switch (a) {
    case Access::color_attachment:
    case Access::depth_attachment:
    case Access::storage_write:
    case Access::blit_dst:
      return true;
    default:
      return false;
  }
}

std::string_view accessLabel(Access a) {
  switch (a) {
    case Access::color_attachment:
      return "color_attachment";
    case Access::depth_attachment:
      return "depth_attachment";
    case Access::depth_attachment_read:
      return "depth_attachment_read";
    case Access::sampled:
      return "sampled";
    case Access::storage_read:
      return "storage_read";
    case Access::storage_write:
      return "storage_write";
    case Access::blit_src:
      return "blit_src";
    case Access::blit_dst:
      return "blit_dst";
  }
  return "unknown";
}

const std::vector<std::string> kTopLevelKeys = {"version", "description", "plugins", "resources", "passes", "output"};
const std::vector<std::string> kResourceKeys = {"type", "format", "size",         "samples",
                                                "mips", "clear",  "buffer_bytes", "description"};
const std::vector<std::string> kPassKeys = {"name",        "type",   "description", "enabled",
                                            "side_effect", "inputs", "outputs",     "params"};

// One "inputs"/"outputs" entry that holds a usable name.
struct Binding {
  std::string name;
  std::string pointer;  // of the string value
};

struct PassInfo {
  std::string pointer;  // "/passes/3"
  std::string label;    // "pass 'lighting' (type deferred_lighting)"
  const PassTypeDesc* type = nullptr;
  bool hasInputs = false, hasOutputs = false;
  std::map<std::string, Binding> inputs, outputs;  // slot -> binding (string values only)
  // Every key present, even with a rejected value: such a slot counts as
  // bound, so that a bad value is not also reported as a missing slot.
  std::set<std::string> inputKeys, outputKeys;
  // Typos already reported with a suggestion ("outputz" for "outputs", slot
  // "colour" for "color"): what they were meant to bind is not also missing.
  bool inputsTypo = false, outputsTypo = false;
  std::set<std::string> slotTypos;
};

class Builder {
 public:
  Builder(const ConfigDocument& doc, const Json& root, const config_detail::SourceMap& map,
          const PassRegistry& registry, Diagnostics& diags)
      : doc_(doc), root_(root), map_(map), registry_(registry), diags_(diags) {}

  PipelineConfig run() {
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

 private:
  Diagnostic& error(DiagCode code, SourceLocation where, std::string message) {
    Diagnostic d;
    d.code = code;
    d.message = std::move(message);
    d.where = std::move(where);
    diags_.push_back(std::move(d));
    return diags_.back();
  }
  SourceLocation at(const std::string& pointer) const { return doc_.locate(pointer); }
  SourceLocation keyAt(const std::string& pointer) const { return doc_.locateKey(pointer); }

  void typeError(const std::string& pointer, const std::string& expected, const Json& got) {
    error(DiagCode::config_schema, at(pointer), "expected " + expected + ", got " + jsonTypeName(got));
  }

  // Unknown members of an object are errors pointing at the key. Returns the
  // keys suggested instead ("did you mean"): a missing key that was suggested
  // is not reported again, the typo explains it.
  std::set<std::string> checkKeys(const Json& object, const std::string& pointer,
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

  void reportDuplicateKeys() {
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

  void checkTopLevel() {
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

    resolveVersions();
    checkFormats();

    if (auto it = root_.find("output"); it == root_.end()) {
      missing("output", "the name of the resource that becomes the output image");
    } else if (!it->is_string()) {
      typeError("/output", "a resource name (string)", *it);
    } else {
      GraphDesc& g = config_.graph;
      g.output = it->get<std::string>();
      g.outputWhere = at("/output");
      // The output image is the caller's: imported, never aliased, no content
      // before the first write. Unknown names are left to compile().
      if (auto r = versions_.find(g.output); r != versions_.end()) {
        g.resources[r->second].imported = true;
        g.resources[r->second].importedHasContent = false;
      }
    }
  }

  // ------------------------------------------------------------ resources

  void checkResources(const Json& resources) {
    for (auto it = resources.begin(); it != resources.end(); ++it) {
      const std::string& name = it.key();
      std::string pointer = "/resources/" + escapePointerToken(name);
      ResourceDecl r;
      r.name = name;
      r.where = at(pointer);
      bool formatOk = false;
      if (name.empty()) error(DiagCode::config_schema, keyAt(pointer), "a resource name must not be empty");
      if (!it->is_object()) {
        error(DiagCode::config_schema, at(pointer),
              "resource '" + name + "': expected an object, got " + jsonTypeName(*it))
            .resource = name;
      } else {
        formatOk = checkResource(*it, pointer, r);
      }
      versions_[name] = config_.graph.resources.size();
      formatOk_.push_back(formatOk);
      config_.graph.resources.push_back(std::move(r));
    }
  }

  // Returns whether the resource has a valid texture format.
  bool checkResource(const Json& res, const std::string& pointer, ResourceDecl& r) {
    std::set<std::string> typos = checkKeys(res, pointer, kResourceKeys, "resource key");
    auto member = [&](const char* key) -> const Json* {
      auto it = res.find(key);
      return it == res.end() ? nullptr : &*it;
    };
    auto sub = [&](const char* key) { return pointer + "/" + key; };

    if (const Json* type = member("type")) {
      if (!type->is_string()) {
        typeError(sub("type"), "\"texture\" or \"buffer\"", *type);
      } else if (*type == "buffer") {
        r.kind = ResourceKind::buffer;
      } else if (*type != "texture") {
        error(DiagCode::config_schema, at(sub("type")),
              "unknown resource type '" + type->get<std::string>() + "'" +
                  didYouMean(type->get<std::string>(), {"texture", "buffer"}) + "; expected 'texture' or 'buffer'");
      }
      // Which keys apply depends on the type: without one, stop here.
      if (!type->is_string() || (*type != "texture" && *type != "buffer")) return false;
    }
    if (const Json* d = member("description"); d && !d->is_string()) typeError(sub("description"), "a string", *d);

    if (r.kind == ResourceKind::buffer) {
      for (const char* key : {"format", "size", "samples", "mips", "clear"})
        if (member(key))
          error(DiagCode::config_schema, keyAt(sub(key)),
                std::string("'") + key + "' does not apply to buffer resources")
              .resource = r.name;
      const Json* bytes = member("buffer_bytes");
      if (!bytes) {
        if (!typos.count("buffer_bytes"))
          error(DiagCode::config_schema, at(pointer), "buffer resource '" + r.name + "' needs \"buffer_bytes\"")
              .resource = r.name;
      } else {
        // GL buffer sizes are signed 64-bit (GLsizeiptr).
        int64_t n = 0;
        if (readInteger(*bytes).status == IntegerValue::Status::not_a_number)
          typeError(sub("buffer_bytes"), "an integer", *bytes);
        else if (std::string why = integerInRange(*bytes, "buffer_bytes", 1, std::numeric_limits<int64_t>::max(), n,
                                                  "bytes (the largest size OpenGL can address)");
                 !why.empty())
          error(DiagCode::config_schema, at(sub("buffer_bytes")), why);
        else
          r.bufferBytes = static_cast<uint64_t>(n);
      }
      return false;
    }

    if (member("buffer_bytes"))
      error(DiagCode::config_schema, keyAt(sub("buffer_bytes")),
            "'buffer_bytes' applies only to buffers (add \"type\": \"buffer\")");

    bool formatOk = false;
    TextureDesc& t = r.texture;
    if (const Json* format = member("format"); !format) {
      if (!typos.count("format"))
        error(DiagCode::config_schema, at(pointer), "resource '" + r.name + "' has no \"format\"").resource = r.name;
    } else if (!format->is_string()) {
      typeError(sub("format"), "a format name (string)", *format);
    } else if (auto f = parseFormat(format->get<std::string>())) {
      t.format = *f;
      formatOk = true;
    } else {
      std::vector<std::string> names;
      for (Format each : allFormats()) names.emplace_back(formatName(each));
      std::string name = format->get<std::string>();
      std::string hint = didYouMean(name, names);
      error(DiagCode::config_schema, at(sub("format")),
            "unknown format '" + name + "'" + (hint.empty() ? "; known formats: " + quotedList(names) : hint))
          .resource = r.name;
    }

    if (const Json* size = member("size")) checkSize(*size, sub("size"), t.size);

    if (const Json* samples = member("samples")) {
      IntegerValue v = readInteger(*samples);
      if (v.status == IntegerValue::Status::not_a_number)
        typeError(sub("samples"), "an integer (1, 2, 4 or 8)", *samples);
      else if (v.status != IntegerValue::Status::ok || (v.value != 1 && v.value != 2 && v.value != 4 && v.value != 8))
        error(DiagCode::config_schema, at(sub("samples")),
              "samples must be 1, 2, 4 or 8, got " + describeValue(*samples));
      else
        t.samples = static_cast<uint32_t>(v.value);
    }

    if (const Json* mips = member("mips")) {
      int64_t n = 0;
      if (readInteger(*mips).status == IntegerValue::Status::not_a_number)
        typeError(sub("mips"), "an integer", *mips);
      else if (std::string why = integerInRange(*mips, "mips", 0, 32, n, {}, " (0: a full mip chain)"); !why.empty())
        error(DiagCode::config_schema, at(sub("mips")), why);
      else
        t.mips = static_cast<uint32_t>(n);
    }

    if (const Json* clear = member("clear")) checkClear(*clear, sub("clear"), formatOk, t);
    return formatOk;
  }

  // Clear values become floats (and a stencil value an integer): 1e300 must not
  // turn into infinity, nor a stencil of 1e30 into an undefined conversion.
  void checkClear(const Json& clear, const std::string& pointer, bool formatOk, TextureDesc& t) {
    auto value = [&](const Json& v, const std::string& at_, size_t index) {
      if (!v.is_number()) {
        typeError(at_, "a number", v);
        return false;
      }
      if (formatOk && index == 1 && formatInfo(t.format).hasStencil) {
        int64_t n = 0;
        if (std::string why = integerInRange(v, "the stencil clear value", 0, 255, n); !why.empty()) {
          error(DiagCode::config_schema, at(at_), why);
          return false;
        }
      }
      if (std::string why = config_detail::floatProblem(v.get<double>()); !why.empty()) {
        error(DiagCode::config_schema, at(at_), "clear value " + why);
        return false;
      }
      return true;
    };
    if (clear.is_number()) {
      if (value(clear, pointer, 0)) t.clear = std::vector<float>{clear.get<float>()};
    } else if (clear.is_array()) {
      if (clear.empty() || clear.size() > 4) {
        error(DiagCode::config_schema, at(pointer),
              "clear must be a number or an array of 1 to 4 numbers, got an array of " + std::to_string(clear.size()));
        return;
      }
      std::vector<float> values;
      bool ok = true;
      for (size_t i = 0; i < clear.size(); ++i) {
        if (value(clear[i], pointer + "/" + std::to_string(i), i))
          values.push_back(clear[i].get<float>());
        else
          ok = false;
      }
      if (ok) t.clear = std::move(values);
    } else {
      typeError(pointer, "a number or an array of 1 to 4 numbers", clear);
    }
  }

  void checkSize(const Json& size, const std::string& pointer, SizeSpec& out) {
    const std::string expected = "\"output\", [width, height] or {\"scale\": s}";
    if (size.is_string()) {
      if (size == "output")
        out = SizeSpec::output();
      else
        error(DiagCode::config_schema, at(pointer), "expected " + expected + ", got " + describeValue(size));
    } else if (size.is_array()) {
      if (size.size() != 2) {
        error(DiagCode::config_schema, at(pointer),
              "expected [width, height], got an array of " + std::to_string(size.size()));
        return;
      }
      uint32_t wh[2] = {0, 0};
      bool ok = true;
      for (size_t i = 0; i < 2; ++i) {
        std::string elem = pointer + "/" + std::to_string(i);
        const char* what = i == 0 ? "width" : "height";
        // The schema's bound; compile() holds sizes to the texture size limit
        // (16384, --max-texture-size, or the device's).
        int64_t n = 0;
        if (readInteger(size[i]).status == IntegerValue::Status::not_a_number) {
          typeError(elem, std::string("an integer ") + what, size[i]);
          ok = false;
        } else if (std::string why = integerInRange(size[i], what, 1, 65536, n, "pixels"); !why.empty()) {
          error(DiagCode::config_schema, at(elem), why);
          ok = false;
        } else {
          wh[i] = static_cast<uint32_t>(n);
        }
      }
      if (ok) out = SizeSpec::absolute(wh[0], wh[1]);
    } else if (size.is_object()) {
      checkKeys(size, pointer, {"scale"}, "size key");
      auto it = size.find("scale");
      if (it == size.end()) {
        error(DiagCode::config_schema, at(pointer), "a relative size needs \"scale\", e.g. {\"scale\": 0.5}");
      } else if (!it->is_number()) {
        typeError(pointer + "/scale", "a number", *it);
      } else if (double s = it->get<double>(); !(s > 0.0 && s <= 16.0)) {
        error(DiagCode::config_schema, at(pointer + "/scale"),
              "scale must be greater than 0 and at most 16, got " + formatNumber(s));
      } else {
        out = SizeSpec::relative(static_cast<float>(s));
      }
    } else {
      typeError(pointer, expected, size);
    }
  }

  // ------------------------------------------------------------ passes

  void checkPasses(const Json& passes) {
    std::map<std::string, std::string> names;  // pass name -> pointer of its first "name"
    for (size_t i = 0; i < passes.size(); ++i) {
      const Json& pass = passes[i];
      PassInfo info;
      info.pointer = "/passes/" + std::to_string(i);
      PassDecl decl;
      decl.where = at(info.pointer);
      ParamSet params;
      if (!pass.is_object()) {
        typeError(info.pointer, "a pass object", pass);
      } else {
        checkPass(pass, info, names, decl, params);
      }
      config_.graph.passes.push_back(std::move(decl));
      config_.params.push_back(std::move(params));
      passInfo_.push_back(std::move(info));
    }
  }

  void checkPass(const Json& pass, PassInfo& info, std::map<std::string, std::string>& names, PassDecl& decl,
                 ParamSet& params) {
    const std::string& p = info.pointer;
    std::set<std::string> typos = checkKeys(pass, p, kPassKeys, "pass key");
    info.inputsTypo = typos.count("inputs") != 0;
    info.outputsTypo = typos.count("outputs") != 0;
    auto member = [&](const char* key) -> const Json* {
      auto it = pass.find(key);
      return it == pass.end() ? nullptr : &*it;
    };

    if (const Json* name = member("name"); !name) {
      if (!typos.count("name")) error(DiagCode::config_schema, at(p), "missing required key 'name'");
    } else if (!name->is_string()) {
      typeError(p + "/name", "a pass name (string)", *name);
    } else if (name->get<std::string>().empty()) {
      error(DiagCode::config_schema, at(p + "/name"), "a pass name must not be empty");
    } else {
      decl.name = name->get<std::string>();
      auto [it, inserted] = names.emplace(decl.name, p + "/name");
      if (!inserted) {
        SourceLocation first = at(it->second);
        error(DiagCode::duplicate_pass, at(p + "/name"),
              "pass name '" + decl.name + "' is already used (first at line " + std::to_string(first.line) + ")")
            .pass = decl.name;
      }
    }
    std::string display = decl.name.empty() ? "#" + p.substr(p.rfind('/') + 1) : "'" + decl.name + "'";

    if (const Json* type = member("type"); !type) {
      if (!typos.count("type"))
        error(DiagCode::config_schema, at(p), "missing required key 'type' (the pass type)").pass = decl.name;
    } else if (!type->is_string()) {
      typeError(p + "/type", "a pass type name (string)", *type);
    } else {
      decl.type = type->get<std::string>();
      info.type = registry_.find(decl.type);
      if (!info.type) {
        std::string best = registry_.suggest(decl.type);
        error(DiagCode::unknown_pass_type, at(p + "/type"),
              "unknown pass type '" + decl.type + "'" + (best.empty() ? "" : " (did you mean '" + best + "'?)"))
            .pass = decl.name;
      }
    }
    info.label = "pass " + display + (decl.type.empty() ? "" : " (type " + decl.type + ")");

    if (const Json* d = member("description"); d && !d->is_string()) typeError(p + "/description", "a string", *d);
    if (const Json* enabled = member("enabled")) {
      if (enabled->is_boolean())
        decl.enabled = enabled->get<bool>();
      else
        typeError(p + "/enabled", "true or false", *enabled);
    }
    bool sideEffect = false;
    if (const Json* se = member("side_effect")) {
      if (se->is_boolean())
        sideEffect = se->get<bool>();
      else
        typeError(p + "/side_effect", "true or false", *se);
    }
    decl.sideEffect = sideEffect || (info.type && info.type->sideEffect);

    readBindings(member("inputs"), p + "/inputs", info, decl.name, true);
    readBindings(member("outputs"), p + "/outputs", info, decl.name, false);
    if (info.type) checkSlots(info, decl);

    if (info.type) params = defaultParams(info.type->params);
    if (const Json* ps = member("params")) {
      if (!ps->is_object())
        typeError(p + "/params", "an object of parameter values", *ps);
      else if (info.type)
        checkParams(*ps, p + "/params", info, decl.name, params);
    }
  }

  // Reads "inputs" or "outputs": slot -> resource/version name.
  void readBindings(const Json* object, const std::string& pointer, PassInfo& info, const std::string& passName,
                    bool inputs) {
    if (!object) return;
    (inputs ? info.hasInputs : info.hasOutputs) = true;
    std::map<std::string, Binding>& out = inputs ? info.inputs : info.outputs;
    if (!object->is_object()) {
      typeError(pointer, std::string("an object mapping ") + (inputs ? "input" : "output") + " slots to names",
                *object);
      return;
    }
    for (auto it = object->begin(); it != object->end(); ++it) {
      (inputs ? info.inputKeys : info.outputKeys).insert(it.key());
      std::string valuePointer = pointer + "/" + escapePointerToken(it.key());
      if (!it->is_string()) {
        typeError(valuePointer, "a resource name (string)", *it);
      } else if (it->get<std::string>().empty()) {
        error(DiagCode::config_schema, at(valuePointer), "expected a resource name, got an empty string").pass =
            passName;
      } else {
        out[it.key()] = {it->get<std::string>(), valuePointer};
      }
      if (info.type) checkSlotName(it.key(), valuePointer, inputs, info, passName);
    }
  }

  void checkSlotName(const std::string& slot, const std::string& pointer, bool inInputs, PassInfo& info,
                     const std::string& passName) {
    const PassTypeDesc& type = *info.type;
    const SlotDecl* decl = type.findSlot(slot);
    if (!decl) {
      std::vector<std::string> names;
      for (const auto& s : type.slots) names.push_back(s.name);
      std::string best = closestMatch(slot, names);
      std::string hint = " (did you mean '" + best + "'?)";
      if (best.empty())
        hint = names.empty() ? "; it has no slots" : "; its slots are " + quotedList(names);
      else
        info.slotTypos.insert(best);
      Diagnostic& d = error(DiagCode::unknown_slot, keyAt(pointer),
                            info.label + " has no " + (inInputs ? "input" : "output") + " slot '" + slot + "'" + hint);
      d.pass = passName;
      d.slot = slot;
      return;
    }
    bool writing = writes(decl->access);
    if (inInputs && writing && decl->load == SlotDecl::Load::never) {
      Diagnostic& d =
          error(DiagCode::unknown_slot, keyAt(pointer),
                "slot '" + slot + "' of " + info.label + " is output-only (" + std::string(accessLabel(decl->access)) +
                    ", it cannot load a previous version): bind it under \"outputs\"");
      d.pass = passName;
      d.slot = slot;
    } else if (!inInputs && !writing) {
      Diagnostic& d = error(DiagCode::unknown_slot, keyAt(pointer),
                            "slot '" + slot + "' of " + info.label + " is an input (" +
                                std::string(accessLabel(decl->access)) + "): bind it under \"inputs\"");
      d.pass = passName;
      d.slot = slot;
    }
  }

  // Required slots and the ResourceUses, in slot-declaration order.
  void checkSlots(const PassInfo& info, PassDecl& decl) {
    const std::string& p = info.pointer;
    std::string inputsAt = info.hasInputs ? p + "/inputs" : p;
    std::string outputsAt = info.hasOutputs ? p + "/outputs" : p;
    // `input`: the binding is missing from "inputs" (else from "outputs").
    auto missing = [&](bool input, const std::string& message, const std::string& slot) {
      if (info.slotTypos.count(slot)) return;
      if (input ? !info.hasInputs && info.inputsTypo : !info.hasOutputs && info.outputsTypo) return;
      Diagnostic& d = error(DiagCode::missing_slot, at(input ? inputsAt : outputsAt), message);
      d.pass = decl.name;
      d.slot = slot;
    };
    for (const SlotDecl& slot : info.type->slots) {
      bool writing = writes(slot.access);
      auto in = info.inputs.find(slot.name);
      auto out = info.outputs.find(slot.name);
      bool mayLoad = writing && slot.load != SlotDecl::Load::never;
      // A slot bound under the wrong object (already reported by
      // checkSlotName) counts as bound, so it is not also reported missing.
      bool inBound = info.inputKeys.count(slot.name) != 0 || (!writing && info.outputKeys.count(slot.name) != 0);
      bool outBound = info.outputKeys.count(slot.name) != 0 || (writing && !mayLoad && info.inputKeys.count(slot.name));

      if (!writing) {
        if (slot.required && !inBound)
          missing(true, "input '" + slot.name + "' of " + info.label + " is required but not bound", slot.name);
        if (in != info.inputs.end()) {
          ResourceUse use;
          use.slot = slot.name;
          use.access = slot.access;
          use.input = in->second.name;
          use.inputWhere = at(in->second.pointer);
          use.acceptsMultisample = slot.acceptsMultisample;
          decl.uses.push_back(std::move(use));
        }
        continue;
      }

      if (slot.required && !outBound)
        missing(false, "output '" + slot.name + "' of " + info.label + " is required but not bound", slot.name);
      if (slot.load == SlotDecl::Load::required && !inBound && (slot.required || outBound))
        missing(true,
                "input '" + slot.name + "' of " + info.label +
                    " is required but not bound: the pass loads the previous version of its output '" + slot.name + "'",
                slot.name);
      if (mayLoad && inBound && !outBound && !slot.required)
        missing(false,
                "output '" + slot.name + "' of " + info.label +
                    " is not bound but its input is: name the version the pass produces",
                slot.name);
      if (out != info.outputs.end()) {
        ResourceUse use;
        use.slot = slot.name;
        use.access = slot.access;
        use.output = out->second.name;
        use.outputWhere = at(out->second.pointer);
        if (mayLoad && in != info.inputs.end()) {
          use.input = in->second.name;
          use.inputWhere = at(in->second.pointer);
        }
        use.acceptsMultisample = slot.acceptsMultisample;
        decl.uses.push_back(std::move(use));
      }
    }
  }

  // ------------------------------------------------------------ params

  void checkParams(const Json& values, const std::string& pointer, const PassInfo& info, const std::string& passName,
                   ParamSet& params) {
    const PassTypeDesc& type = *info.type;
    for (auto it = values.begin(); it != values.end(); ++it) {
      std::string vp = pointer + "/" + escapePointerToken(it.key());
      const ParamDecl* decl = type.findParam(it.key());
      if (!decl) {
        std::vector<std::string> names;
        for (const auto& pd : type.params) names.push_back(pd.name);
        std::string hint = didYouMean(it.key(), names);
        if (hint.empty()) hint = names.empty() ? "; it has no parameters" : "; its parameters are " + quotedList(names);
        error(DiagCode::unknown_param, keyAt(vp), info.label + " has no parameter '" + it.key() + "'" + hint).pass =
            passName;
        continue;
      }
      if (auto v = checkParam(*decl, *it, vp, info, passName)) params.set(decl->name, std::move(*v));
    }
  }

  std::optional<ParamValue> checkParam(const ParamDecl& decl, const Json& v, const std::string& pointer,
                                       const PassInfo& info, const std::string& passName) {
    std::vector<config_detail::ValueProblem> problems;
    std::optional<ParamValue> value = config_detail::checkParamValue(decl, v, pointer, problems);
    for (const auto& p : problems)
      error(p.code, at(p.pointer), "parameter '" + decl.name + "' of " + info.label + ": " + p.message).pass = passName;
    return value;
  }

  // ------------------------------------------------------------ formats

  // Maps version names to resources by following, within the document, the
  // passes that load one name and produce another: a breadth-first walk from
  // the resources, linear however the passes are ordered (a chain declared
  // last to first took one sweep over all passes per link). Best effort:
  // names that cannot be resolved are left to compile().
  void resolveVersions() {
    std::unordered_map<std::string_view, std::vector<std::string_view>> produced;  // loaded name -> names made from it
    for (const PassInfo& info : passInfo_) {
      if (!info.type) continue;
      for (const auto& [slot, out] : info.outputs) {
        const SlotDecl* decl = info.type->findSlot(slot);
        if (!decl || !writes(decl->access)) continue;
        if (auto in = info.inputs.find(slot); in != info.inputs.end()) produced[in->second.name].push_back(out.name);
      }
    }
    std::vector<std::pair<std::string_view, size_t>> queue(versions_.begin(), versions_.end());
    for (size_t next = 0; next < queue.size(); ++next) {
      auto edges = produced.find(queue[next].first);
      if (edges == produced.end()) continue;
      for (std::string_view out : edges->second)
        if (versions_.emplace(std::string(out), queue[next].second).second) queue.emplace_back(out, queue[next].second);
    }
  }

  void checkFormats() {
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
          auto r = versions_.find(b->name);
          if (r == versions_.end() || !formatOk_[r->second]) continue;
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

  const ConfigDocument& doc_;
  const Json& root_;
  const config_detail::SourceMap& map_;
  const PassRegistry& registry_;
  Diagnostics& diags_;
  PipelineConfig config_;
  std::vector<PassInfo> passInfo_;          // parallel to config_.graph.passes
  std::map<std::string, size_t> versions_;  // resource or version name -> resource index
  std::vector<bool> formatOk_;              // parallel to config_.graph.resources
};

}  // namespace

PipelineConfig ConfigDocument::build(const PassRegistry& registry, Diagnostics& diags) const {
  if (!ok()) {
    PipelineConfig empty;
    empty.file = file();
    return empty;
  }
  return Builder(*this, impl_->root, impl_->map, registry, diags).run();
}

}  // namespace rgraph
