// ParamEditor: pass parameters edited as JSON (key order kept), with ImGui
// widgets chosen from each pass type's parameter declarations.
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cstdint>
#include <fstream>
#include <sstream>

#include "rgraph/error.h"
#include "rgraph/json_value.h"
#include "rgraph/output_file.h"
#include "rgraph/registry.h"
#include "view_panels.h"

namespace rgraph::view {

using Json = nlohmann::ordered_json;

namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RuntimeError(path + ": cannot read the pipeline file");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A parameter's value sits under the document, "passes", the pass and its "params".
constexpr size_t kParamDepth = 4;

// The file's text with the loader's limits (rgraph/json_value.h) and its located message.
Json parseOrThrow(const std::string& text, const std::string& path, ConfigDocument& located) {
  Diagnostics diags;
  located = ConfigDocument::parseText(text, path, diags);
  Json doc;
  if (!located.ok() || parseJsonValue(text, doc))
    throw RuntimeError(diags.empty() ? path + ": error: not valid JSON" : formatDiagnostic(diags.front()));
  return doc;
}

// A string member, or `fallback` (the file may not be a valid pipeline:
// the renderer reports that, the editor must not throw on it).
std::string stringField(const Json& object, const char* key, const std::string& fallback = {}) {
  if (!object.is_object() || !object.contains(key) || !object[key].is_string()) return fallback;
  return object[key].get<std::string>();
}

// The pass's index in "passes", or -1.
long findPass(const Json& doc, const std::string& name) {
  if (!doc.contains("passes") || !doc["passes"].is_array()) return -1;
  const Json& passes = doc["passes"];
  for (size_t i = 0; i < passes.size(); ++i)
    if (stringField(passes[i], "name") == name) return long(i);
  return -1;
}

Json toJson(const ParamValue& v) {
  return std::visit([](const auto& x) { return Json(x); }, v);
}

std::string passNames(const Json& doc) {
  std::string out;
  if (doc.contains("passes") && doc["passes"].is_array())
    for (const Json& p : doc["passes"]) out += (out.empty() ? "" : ", ") + stringField(p, "name", "?");
  return out;
}

// One widget for one declared parameter; true (and `value` updated) on a change.
bool paramWidget(const ParamDecl& d, Json& value) {
  const char* label = d.name.c_str();
  const float lo = d.min ? float(*d.min) : 0.0f, hi = d.max ? float(*d.max) : 0.0f;
  bool changed = false;
  switch (d.type) {
    case ParamType::boolean: {
      bool b = value.is_boolean() ? value.get<bool>() : false;
      if ((changed = ImGui::Checkbox(label, &b))) value = b;
      break;
    }
    case ParamType::integer: {
      int i = value.is_number() ? value.get<int>() : 0;
      changed = d.min && d.max
                    ? ImGui::SliderInt(label, &i, int(lo), int(hi))
                    : ImGui::DragInt(label, &i, 0.2f, d.min ? int(lo) : INT32_MIN, d.max ? int(hi) : INT32_MAX);
      if (changed) value = std::clamp<int64_t>(i, d.min ? int64_t(lo) : INT32_MIN, d.max ? int64_t(hi) : INT32_MAX);
      break;
    }
    case ParamType::number: {
      float f = value.is_number() ? value.get<float>() : 0.0f;
      changed = d.min && d.max ? ImGui::SliderFloat(label, &f, lo, hi)
                               : ImGui::DragFloat(label, &f, 0.01f, d.min ? lo : -FLT_MAX, d.max ? hi : FLT_MAX);
      if (changed) value = double(std::clamp(f, d.min ? lo : -FLT_MAX, d.max ? hi : FLT_MAX));
      break;
    }
    case ParamType::enumeration: {
      const std::string current = value.is_string() ? value.get<std::string>() : std::string();
      if (ImGui::BeginCombo(label, current.c_str())) {
        for (const std::string& c : d.choices)
          if (ImGui::Selectable(c.c_str(), c == current) && c != current) value = c, changed = true;
        ImGui::EndCombo();
      }
      break;
    }
    case ParamType::vec3:
    case ParamType::vec4: {
      float v[4] = {0, 0, 0, 0};
      const size_t n = d.type == ParamType::vec3 ? 3 : 4;
      for (size_t i = 0; i < n && value.is_array() && i < value.size(); ++i)
        if (value[i].is_number()) v[i] = value[i].get<float>();  // a wrong type: the renderer reports it
      changed = n == 3 ? ImGui::DragFloat3(label, v, 0.01f, lo, hi) : ImGui::DragFloat4(label, v, 0.01f, lo, hi);
      if (changed) {
        value = Json::array();
        for (size_t i = 0; i < n; ++i)
          value.push_back(
              double(d.min || d.max ? std::clamp(v[i], d.min ? lo : -FLT_MAX, d.max ? hi : FLT_MAX) : v[i]));
      }
      break;
    }
    case ParamType::string:
    case ParamType::shader: {
      char buf[512] = {};
      const std::string s = value.is_string() ? value.get<std::string>() : std::string();
      s.copy(buf, sizeof(buf) - 1);
      if ((changed = ImGui::InputText(label, buf, sizeof(buf), ImGuiInputTextFlags_EnterReturnsTrue)))
        value = std::string(buf);
      break;
    }
  }
  if (!d.description.empty() && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", d.description.c_str());
  return changed;
}

}  // namespace

ParamEditor::ParamEditor(std::string pipelinePath) : path_(std::move(pipelinePath)) {
  text_ = readFile(path_);
  doc_ = parseOrThrow(text_, path_, file_);
}

bool ParamEditor::reread() {
  try {
    std::string text = readFile(path_);
    ConfigDocument located;
    doc_ = parseOrThrow(text, path_, located);
    file_ = std::move(located);
    text_ = std::move(text);
    modified_ = false;
    error_.clear();
    return true;
  } catch (const RuntimeError&) {
    return false;
  }
}

const std::string& ParamEditor::text() const { return text_; }

void ParamEditor::accept(const std::string& text) {
  Json doc;
  if (parseJsonValue(text, doc)) return;  // not text this editor made (the renderer would have refused it)
  doc_ = std::move(doc);
  text_ = text;
  modified_ = true;
  error_.clear();
}

void ParamEditor::reject(const std::string& message) { error_ = message; }

void ParamEditor::save(const std::string& path) {
  const std::string& to = path.empty() ? path_ : path;
  // Through a temporary file and a rename: a full disk leaves the user's file as it was, and says why.
  writeOutputFile(to, text_, "the pipeline file");
  if (path.empty()) modified_ = false;  // the watcher sees the write: the reload that follows rereads it
}

Diagnostics ParamEditor::inFile(const Diagnostics& diags) const {
  Diagnostics out;
  for (Diagnostic d : diags) {
    // The renderer names the pipeline file; places in the edited text are found again in the file's own text
    // (the same structure: an edit changes one value or adds it), the nearest parent when the file lacks it.
    if (d.where.file == path_ && !d.where.path.empty()) {
      const SourceLocation at = file_.locate(d.where.path);
      d.where.line = at.line;
      d.where.column = at.column;
    } else if (d.where.file == path_) {
      d.where.line = d.where.column = 0;  // a place in text the file does not have
    }
    out.push_back(std::move(d));
  }
  return out;
}

std::string ParamEditor::edited(size_t passIndex, const std::string& name, const Json& value) const {
  Json doc = doc_;
  Json& pass = doc["passes"][passIndex];
  if (!pass.contains("params") || !pass["params"].is_object()) pass["params"] = Json::object();
  pass["params"][name] = value;
  return doc.dump(2) + "\n";
}

std::optional<std::string> ParamEditor::withParam(const std::string& pass, const std::string& name,
                                                  const std::string& jsonValue, const PassRegistry& types,
                                                  std::string& error) {
  const long index = findPass(doc_, pass);
  if (index < 0) {
    error = path_ + ": no pass named '" + pass + "' (passes: " + passNames(doc_) + ")";
    return std::nullopt;
  }
  const std::string type = stringField(doc_["passes"][size_t(index)], "type");
  if (const PassTypeDesc* desc = types.find(type); desc && !desc->findParam(name)) {
    std::string names;
    for (const ParamDecl& d : desc->params) names += (names.empty() ? "" : ", ") + d.name;
    error = path_ + ": pass '" + pass + "' (type " + type + ") has no parameter '" + name +
            "' (parameters: " + (names.empty() ? "none" : names) + ")";
    return std::nullopt;
  }
  Json value;
  if (const std::optional<JsonValueError> bad = parseJsonValue(jsonValue, value, kParamDepth)) {
    error = "param " + pass + " " + name + ": the value '" + jsonValue.substr(0, 80) +
            (jsonValue.size() > 80 ? "...'" : "'") + " is not JSON the pipeline file can hold (column " +
            std::to_string(bad->offset + 1) + ": " + bad->message + ")";
    return std::nullopt;
  }
  return edited(size_t(index), name, value);
}

std::optional<std::string> ParamEditor::withParam(const std::string& pass, const std::string& name,
                                                  const std::string& jsonValue, std::string& error) {
  return withParam(pass, name, jsonValue, PassRegistry::builtins(), error);
}

std::optional<std::string> ParamEditor::draw(const Renderer& renderer) {
  std::optional<std::string> result;
  ImGui::TextUnformatted(path_.c_str());
  if (modified_) ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "%s", modifiedNote().c_str());
  if (ImGui::Button("Save")) {
    try {
      save();
    } catch (const RuntimeError& e) {
      error_ = e.what();
    }
  }
  ImGui::SameLine();
  char buf[512] = {};
  saveAsPath_.copy(buf, sizeof(buf) - 1);
  if (ImGui::InputText("##saveas", buf, sizeof(buf))) saveAsPath_ = buf;
  ImGui::SameLine();
  if (ImGui::Button("Save as") && !saveAsPath_.empty()) {
    try {
      save(saveAsPath_);
    } catch (const RuntimeError& e) {
      error_ = e.what();
    }
  }
  if (!error_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1.0f), "%s", error_.c_str());
  if (!doc_.contains("passes") || !doc_["passes"].is_array()) return result;
  const Json& passes = doc_["passes"];
  for (size_t i = 0; i < passes.size(); ++i) {
    const Json& pass = passes[i];
    const std::string name = stringField(pass, "name", "?"), type = stringField(pass, "type", "?");
    const PassTypeDesc* desc = renderer.passTypes().find(type);  // its own: built-ins and its plugins
    ImGui::PushID(int(i));
    if (ImGui::TreeNodeEx("pass", ImGuiTreeNodeFlags_DefaultOpen, "%s (%s)", name.c_str(), type.c_str())) {
      if (!desc)
        ImGui::TextDisabled("unknown pass type");
      else if (desc->params.empty())
        ImGui::TextDisabled("no parameters");
      for (const ParamDecl& d : desc ? desc->params : std::vector<ParamDecl>{}) {
        const bool written = pass.contains("params") && pass["params"].contains(d.name);
        Json value = written ? pass["params"][d.name] : toJson(d.defaultValue);
        if (paramWidget(d, value)) result = edited(i, d.name, value);
        if (!written) {
          ImGui::SameLine();
          ImGui::TextDisabled("(default)");
        }
      }
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
  return result;
}

}  // namespace rgraph::view
