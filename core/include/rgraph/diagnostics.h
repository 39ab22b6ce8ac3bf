// Diagnostics are values: the graph compiler and the config loader return
// them, and the caller decides how to print them. Nothing here throws or asserts.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rgraph {

enum class Severity { error, warning, note };

// Stable codes: tests and `rgraph validate --json` match on these.
enum class DiagCode {
  // graph
  unknown_resource,
  read_never_written,
  duplicate_writer,
  cycle,
  feedback_loop,
  attachment_size_mismatch,
  attachment_samples_mismatch,
  depth_blit_format_mismatch,
  rgb_float_attachment,
  multisample_sampled,
  no_output,
  output_never_written,
  duplicate_resource,
  invalid_resource,       // bad descriptor: zero size, bad mip count, depth with samples on a storage image...
  access_format_mismatch, // e.g. depth format bound as a colour attachment
  invalid_output,         // the output cannot be shown: multisampled, depth, a buffer, overwritten later
  output_size,            // warning: the output's own size is not the requested output size
  history_error,          // a history resource whose source is unknown, unwritten, not kept, or differs in size/format
  subresource_range,      // a mip, layer or face out of the texture's range, or a part of a buffer or history
  // config
  json_syntax,
  file_not_found,
  config_schema,          // wrong type / missing key / unknown key in the config itself
  unknown_pass_type,
  unknown_slot,
  missing_slot,
  unknown_param,
  param_type,
  param_range,
  format_not_allowed,
  duplicate_pass,
  // shaders / runtime
  shader_error,
  plugin_error,
  pass_check,             // a pass type's check hook refused its bindings or params (rgraph/pass_check.h)
  needs_scene,            // a pass that draws the scene in a pipeline run without one
  device_error,           // what only the GL device refuses (driver compile error, incomplete framebuffer)
};

std::string_view diagCodeName(DiagCode c);
std::string_view severityName(Severity s);

// Where a diagnostic points in the user's config. line/column are 1-based; 0 means unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
  std::string path;  // JSON pointer, e.g. /passes/2/inputs/albedo
  bool known() const { return line > 0; }
};

struct Diagnostic {
  DiagCode code{};
  Severity severity = Severity::error;
  std::string message;
  std::string pass;      // pass name, when the diagnostic concerns one
  std::string slot;      // slot name, when it concerns one
  std::string resource;  // resource (or version) name, when it concerns one
  SourceLocation where;
};

using Diagnostics = std::vector<Diagnostic>;

bool hasErrors(const Diagnostics& d);

// `FILE:LINE:COL: error: PATH: message` when the location is known
// (`FILE:LINE: ...` when the column is 0, as for shader messages),
// otherwise `error: message` prefixed with the pass/slot it concerns.
std::string formatDiagnostic(const Diagnostic& d);

// "Did you mean": the closest candidate by edit distance (<= max(2, len/3)),
// or "". Shared by the config loader, the compiler and the pass registry.
std::string closestMatch(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace rgraph
