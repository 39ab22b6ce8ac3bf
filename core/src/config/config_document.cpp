// ConfigDocument: reading and parsing a pipeline config, and mapping JSON
// pointers back to file positions. The checks against the pass registry live
// in config_build*.cpp (see config_builder.h).
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>

#include "config_impl.h"
#include "json_text.h"

namespace rgraph {
namespace {

Diagnostic syntaxError(const config_detail::SourceMap& map, const std::string& file, size_t offset,
                       std::string message) {
  Diagnostic d;
  d.code = DiagCode::json_syntax;
  d.message = std::move(message);
  config_detail::LineColumn lc = map.position(offset);
  d.where = {file, lc.line, lc.column, ""};
  return d;
}

}  // namespace

ConfigDocument::ConfigDocument() : impl_(std::make_unique<Impl>()) {}
ConfigDocument::~ConfigDocument() = default;
ConfigDocument::ConfigDocument(ConfigDocument&&) noexcept = default;
ConfigDocument& ConfigDocument::operator=(ConfigDocument&&) noexcept = default;

ConfigDocument ConfigDocument::parseFile(const std::string& path, Diagnostics& diags) {
  auto fail = [&](int error) {
    Diagnostic d;
    d.code = DiagCode::file_not_found;
    d.message = "cannot read config file '" + path + "': " + std::strerror(error);
    d.where.file = path;
    diags.push_back(std::move(d));
    ConfigDocument doc;
    doc.impl_->file = path;
    return doc;
  };
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return fail(EISDIR);
  errno = 0;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return fail(errno ? errno : ENOENT);
  std::string text;
  char buffer[65536];
  size_t n;
  while ((n = std::fread(buffer, 1, sizeof buffer, f)) > 0) text.append(buffer, n);
  bool readError = std::ferror(f) != 0;
  int error = errno;
  std::fclose(f);
  if (readError) return fail(error ? error : EIO);
  return parseText(text, path, diags);
}

ConfigDocument ConfigDocument::parseText(const std::string& text, const std::string& file, Diagnostics& diags) {
  ConfigDocument doc;
  Impl& impl = *doc.impl_;
  impl.file = file;
  impl.map.indexLines(text);

  if (auto error = config_detail::parseJsonText(text, impl.root)) {
    diags.push_back(syntaxError(impl.map, impl.file, error->offset, std::move(error->message)));
    return doc;
  }

  size_t tooDeepAt = 0;
  if (!impl.map.scan(text, &tooDeepAt)) {
    diags.push_back(syntaxError(impl.map, impl.file, tooDeepAt,
                                config_detail::nestingTooDeepMessage()));
    impl.root = Json();
    return doc;
  }
  impl.ok = true;
  return doc;
}

bool ConfigDocument::ok() const { return impl_ && impl_->ok; }

const std::string& ConfigDocument::file() const {
  static const std::string empty;
  return impl_ ? impl_->file : empty;
}

namespace {
// (name, index in the "plugins" array) of every string entry.
std::vector<std::pair<std::string, size_t>> pluginEntries(const Json& root) {
  std::vector<std::pair<std::string, size_t>> out;
  if (!root.is_object()) return out;
  auto it = root.find("plugins");
  if (it == root.end() || !it->is_array()) return out;
  for (size_t i = 0; i < it->size(); ++i)
    if ((*it)[i].is_string()) out.emplace_back((*it)[i].get<std::string>(), i);
  return out;
}
}  // namespace

std::vector<std::string> ConfigDocument::plugins() const {
  std::vector<std::string> out;
  if (!ok()) return out;
  for (auto& [name, index] : pluginEntries(impl_->root)) out.push_back(name);
  return out;
}

SourceLocation ConfigDocument::pluginLocation(size_t index) const {
  if (!ok()) return {};
  auto entries = pluginEntries(impl_->root);
  if (index >= entries.size()) return locate("/plugins");
  return locate("/plugins/" + std::to_string(entries[index].second));
}

SourceLocation ConfigDocument::locate(const std::string& jsonPointer) const {
  if (!impl_) return {};
  std::string p = jsonPointer;
  for (;;) {
    size_t offset = impl_->map.valueOffset(p);
    if (offset != config_detail::SourceMap::npos) {
      config_detail::LineColumn lc = impl_->map.position(offset);
      return {impl_->file, lc.line, lc.column, p};
    }
    if (p.empty()) break;
    p = config_detail::parentPointer(p);
  }
  return {impl_->file, 0, 0, jsonPointer};
}

SourceLocation ConfigDocument::locateKey(const std::string& jsonPointer) const {
  if (!impl_) return {};
  size_t offset = impl_->map.keyOffset(jsonPointer);
  if (offset == config_detail::SourceMap::npos) return locate(jsonPointer);
  config_detail::LineColumn lc = impl_->map.position(offset);
  return {impl_->file, lc.line, lc.column, jsonPointer};
}

std::optional<std::string> ConfigDocument::stringAt(const std::string& jsonPointer) const {
  if (!ok()) return std::nullopt;
  try {
    const Json::json_pointer pointer(jsonPointer);
    if (!impl_->root.contains(pointer)) return std::nullopt;
    const Json& value = impl_->root.at(pointer);
    if (value.is_string()) return value.get<std::string>();
  } catch (const Json::exception&) {  // not a valid pointer
  }
  return std::nullopt;
}

}  // namespace rgraph
