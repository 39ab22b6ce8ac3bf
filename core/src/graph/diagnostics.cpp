#include "rgraph/diagnostics.h"

#include <algorithm>
#include <vector>

namespace rgraph {

std::string_view diagCodeName(DiagCode c) {
  switch (c) {
    case DiagCode::unknown_resource: return "unknown_resource";
    case DiagCode::read_never_written: return "read_never_written";
    case DiagCode::duplicate_writer: return "duplicate_writer";
    case DiagCode::cycle: return "cycle";
    case DiagCode::feedback_loop: return "feedback_loop";
    case DiagCode::attachment_size_mismatch: return "attachment_size_mismatch";
    case DiagCode::attachment_samples_mismatch: return "attachment_samples_mismatch";
    case DiagCode::depth_blit_format_mismatch: return "depth_blit_format_mismatch";
    case DiagCode::rgb_float_attachment: return "rgb_float_attachment";
    case DiagCode::multisample_sampled: return "multisample_sampled";
    case DiagCode::no_output: return "no_output";
    case DiagCode::output_never_written: return "output_never_written";
    case DiagCode::duplicate_resource: return "duplicate_resource";
    case DiagCode::invalid_resource: return "invalid_resource";
    case DiagCode::access_format_mismatch: return "access_format_mismatch";
    case DiagCode::invalid_output: return "invalid_output";
    case DiagCode::output_size: return "output_size";
    case DiagCode::history_error:
      return "history_error";
    case DiagCode::subresource_range:
      return "subresource_range";
    case DiagCode::json_syntax: return "json_syntax";
    case DiagCode::file_not_found: return "file_not_found";
    case DiagCode::config_schema: return "config_schema";
    case DiagCode::unknown_pass_type: return "unknown_pass_type";
    case DiagCode::unknown_slot: return "unknown_slot";
    case DiagCode::missing_slot: return "missing_slot";
    case DiagCode::unknown_param: return "unknown_param";
    case DiagCode::param_type: return "param_type";
    case DiagCode::param_range: return "param_range";
    case DiagCode::format_not_allowed: return "format_not_allowed";
    case DiagCode::duplicate_pass: return "duplicate_pass";
    case DiagCode::shader_error: return "shader_error";
    case DiagCode::plugin_error: return "plugin_error";
    case DiagCode::pass_check: return "pass_check";
    case DiagCode::needs_scene: return "needs_scene";
    case DiagCode::device_error: return "device_error";
  }
  return "unknown";
}

std::string_view severityName(Severity s) {
  switch (s) {
    case Severity::error: return "error";
    case Severity::warning: return "warning";
    case Severity::note: return "note";
  }
  return "error";
}

bool hasErrors(const Diagnostics& d) {
  return std::any_of(d.begin(), d.end(), [](const Diagnostic& x) { return x.severity == Severity::error; });
}

std::string formatDiagnostic(const Diagnostic& d) {
  std::string out;
  if (!d.where.file.empty()) {
    out += d.where.file;
    if (d.where.line > 0) out += ":" + std::to_string(d.where.line);
    if (d.where.line > 0 && d.where.column > 0) out += ":" + std::to_string(d.where.column);  // shader messages: no column
    out += ": ";
  }
  out += severityName(d.severity);
  out += ": ";
  if (!d.where.path.empty()) {
    out += d.where.path + ": ";
  } else if (!d.pass.empty()) {
    out += "pass '" + d.pass + "'";
    if (!d.slot.empty()) out += " slot '" + d.slot + "'";
    out += ": ";
  }
  out += d.message;
  return out;
}

namespace {
size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t sub = prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, sub});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}
}  // namespace

std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates) {
  size_t limit = std::max<size_t>(2, word.size() / 3);
  std::string best;
  size_t bestDistance = limit + 1;
  for (const auto& c : candidates) {
    size_t d = editDistance(word, c);
    if (d < bestDistance) {
      bestDistance = d;
      best = c;
    }
  }
  return best;
}

}  // namespace rgraph
