// The config Builder: resource declarations (type, format, size, samples,
// mips, clear values, buffer size). See config_builder.h.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "config_builder.h"

namespace rgraph::config_detail {

namespace {

const std::vector<std::string> kResourceKeys = {"type",         "format",      "size",     "samples",
                                                "mips",         "layers",      "cube",     "clear",
                                                "buffer_bytes", "description", "imported", "history_of",
                                                "persistent"};

}  // namespace

void Builder::checkResources(const Json& resources) {
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
    formatOk_.push_back(formatOk);
    config_.graph.resources.push_back(std::move(r));
  }
  inheritHistoryDescriptors(resources);
}

// A history resource ("history_of") holds its source's previous content, so
// its descriptor is the source's: the keys it omits are copied from the
// source; the keys it gives must match (compile() says so when they do not,
// naming both descriptors).
void Builder::inheritHistoryDescriptors(const Json& resources) {
  auto& decls = config_.graph.resources;
  for (size_t i = 0; i < decls.size(); ++i) {
    ResourceDecl& h = decls[i];
    if (h.historyOf.empty() || h.kind != ResourceKind::texture) continue;
    const auto src =
        std::find_if(decls.begin(), decls.end(), [&](const ResourceDecl& d) { return d.name == h.historyOf; });
    if (src == decls.end() || src->kind != ResourceKind::texture) continue;  // compile() reports it
    const Json& object = resources[h.name];
    const size_t s = static_cast<size_t>(src - decls.begin());
    if (!object.contains("format")) {
      h.texture.format = src->texture.format;
      formatOk_[i] = formatOk_[s];
    }
    if (!object.contains("size")) h.texture.size = src->texture.size;
    if (!object.contains("samples")) h.texture.samples = src->texture.samples;
    if (!object.contains("mips")) h.texture.mips = src->texture.mips;
    if (!object.contains("layers")) h.texture.layers = src->texture.layers;
    if (!object.contains("cube")) h.texture.cube = src->texture.cube;
  }
}

// Returns whether the resource has a valid texture format.
bool Builder::checkResource(const Json& res, const std::string& pointer, ResourceDecl& r) {
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
  // The caller's own texture or buffer (rgraph/renderer.h importTexture): it
  // arrives with content, is never aliased, and its writers are never culled.
  if (const Json* imported = member("imported")) {
    if (imported->is_boolean())
      r.imported = imported->get<bool>();
    else
      typeError(sub("imported"), "true or false", *imported);
  }

  // Content kept across frames until invalidated (ResourceDecl::persistent).
  if (const Json* persistent = member("persistent")) {
    if (persistent->is_boolean())
      r.persistent = persistent->get<bool>();
    else
      typeError(sub("persistent"), "true or false", *persistent);
  }

  if (const Json* of = member("history_of")) {
    if (!of->is_string()) {
      typeError(sub("history_of"), "the name of the resource whose previous frame this one holds", *of);
    } else if (of->get<std::string>().empty()) {
      error(DiagCode::config_schema, at(sub("history_of")),
            "resource '" + r.name + "': \"history_of\" is empty; name the resource whose previous frame it holds")
          .resource = r.name;
    } else {
      r.historyOf = of->get<std::string>();
      r.historyWhere = at(sub("history_of"));
    }
  }

  if (r.kind == ResourceKind::buffer) {
    for (const char* key : {"format", "size", "samples", "mips", "layers", "cube", "clear"})
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
    if (!typos.count("format") && !member("history_of"))
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
    if (mips->is_string() && *mips == "full")
      t.mips = 0;
    else if (readInteger(*mips).status == IntegerValue::Status::not_a_number)
      typeError(sub("mips"), "an integer or \"full\"", *mips);
    else if (std::string why = integerInRange(*mips, "mips", 0, 32, n, {}, " (0 or \"full\": a full mip chain)");
             !why.empty())
      error(DiagCode::config_schema, at(sub("mips")), why);
    else
      t.mips = static_cast<uint32_t>(n);
  }

  // An array (layers > 1), a cube map ("cube": true) or a cube array (both:
  // "layers" counts cubes). compile() checks the limits against the size.
  if (const Json* layers = member("layers")) {
    int64_t n = 0;
    if (readInteger(*layers).status == IntegerValue::Status::not_a_number)
      typeError(sub("layers"), "an integer (array layers; cubes when \"cube\" is true)", *layers);
    else if (std::string why =
                 integerInRange(*layers, "layers", 1, 2048, n, {}, " (array layers, or cubes; OpenGL 4.5 guarantees 2048)");
             !why.empty())
      error(DiagCode::config_schema, at(sub("layers")), why);
    else
      t.layers = static_cast<uint32_t>(n);
  }
  if (const Json* cube = member("cube")) {
    if (cube->is_boolean())
      t.cube = cube->get<bool>();
    else
      typeError(sub("cube"), "true or false", *cube);
  }

  if (const Json* clear = member("clear")) checkClear(*clear, sub("clear"), formatOk, t);
  return formatOk;
}

// Clear values become floats (and a stencil value an integer): 1e300 must not
// turn into infinity, nor a stencil of 1e30 into an undefined conversion.
void Builder::checkClear(const Json& clear, const std::string& pointer, bool formatOk, TextureDesc& t) {
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

void Builder::checkSize(const Json& size, const std::string& pointer, SizeSpec& out) {
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

}  // namespace rgraph::config_detail
