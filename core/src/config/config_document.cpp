// ConfigDocument: reading and parsing a pipeline config, and mapping JSON
// pointers back to file positions. The checks against the pass registry live
// in config_build.cpp.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>

#include "config_impl.h"

namespace rgraph {
namespace {

// nlohmann's own DOM builder, except that a parse error records where and
// why instead of throwing (number overflow, for instance, would otherwise
// arrive as an out_of_range exception without a position).
class DomBuilder : public nlohmann::detail::json_sax_dom_parser<Json> {
 public:
  explicit DomBuilder(Json& root) : json_sax_dom_parser<Json>(root, false) {}

  // Shadows the base's parse_error: sax_parse calls it on the static type.
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& lastToken, const Exception& ex) {
    failed = true;
    message = ex.what();
    errorOffset = position - std::min(position, tokenLength(message, lastToken));
    return false;
  }

  bool failed = false;
  std::size_t errorOffset = 0;  // of the first byte of the offending token
  std::string message;

 private:
  // The position the library reports is just past the last character read.
  // For an unexpected number, string or literal, point at its first
  // character instead of its last. The token text is only reliable for
  // strings and numbers (the lexer resets it for those); literals have fixed
  // lengths; anything else is one character or a lexer error at that spot.
  static std::size_t tokenLength(const std::string& message, const std::string& token) {
    if (message.find("unexpected number literal") != std::string::npos ||
        message.find("unexpected string literal") != std::string::npos ||
        message.find("number overflow") != std::string::npos)
      return std::max<std::size_t>(1, token.size());
    if (message.find("unexpected true literal") != std::string::npos) return 4;
    if (message.find("unexpected false literal") != std::string::npos) return 5;
    if (message.find("unexpected null literal") != std::string::npos) return 4;
    return 1;
  }
};

// "[json.exception.parse_error.101] parse error at line 1, column 5: syntax
// error while parsing ..." -> "syntax error while parsing ...": the position
// is printed by formatDiagnostic already.
std::string parserMessage(std::string m) {
  if (!m.empty() && m[0] == '[') {
    size_t end = m.find("] ");
    if (end != std::string::npos) m.erase(0, end + 2);
  }
  if (m.rfind("parse error", 0) == 0) {
    size_t colon = m.find(": ");
    if (colon != std::string::npos) m.erase(0, colon + 2);
  }
  // "; last read: '<token>'" repeats raw input (possibly invalid UTF-8, and
  // not always only the bad token): the position says where it is.
  size_t last = m.find("; last read: '");
  if (last != std::string::npos) {
    size_t expected = m.find("'; expected ", last);
    m.erase(last, expected == std::string::npos ? std::string::npos : expected + 1 - last);
  }
  return m;
}

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

  DomBuilder builder(impl.root);
  bool parsed = false;
  try {
    parsed = Json::sax_parse(text, &builder);
  } catch (const std::exception& e) {  // not expected: the builder does not throw
    builder.failed = true;
    builder.message = e.what();
  }
  if (!parsed || builder.failed) {
    diags.push_back(syntaxError(impl.map, impl.file, std::min(builder.errorOffset, text.size()),
                                builder.message.empty() ? "invalid JSON" : parserMessage(builder.message)));
    impl.root = Json();
    return doc;
  }

  // The library stops at a NUL byte as if the input ended there.
  if (size_t nul = text.find('\0'); nul != std::string::npos) {
    diags.push_back(syntaxError(impl.map, impl.file, nul, "unexpected NUL byte after the top-level value"));
    impl.root = Json();
    return doc;
  }

  size_t tooDeepAt = 0;
  if (!impl.map.scan(text, &tooDeepAt)) {
    diags.push_back(syntaxError(impl.map, impl.file, tooDeepAt,
                                "values nested deeper than " + std::to_string(config_detail::SourceMap::kMaxDepth) +
                                    " levels are not supported"));
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

}  // namespace rgraph
