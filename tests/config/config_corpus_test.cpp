// The invalid-config corpus: tests/configs/invalid/NAME.json, each with its
// expected first diagnostic in NAME.expected (one line, as formatDiagnostic
// prints it, with the file written as its bare name).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "test_registry.h"

namespace rgraph {
namespace {

namespace fs = std::filesystem;

std::string invalidDir() { return test::configsDir() + "/invalid"; }

std::vector<std::string> corpusNames() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(invalidDir(), ec))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string trimLine(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

// Loads and checks one file the way the CLI does: the graph is compiled
// once the config builds cleanly (history errors are the compiler's).
Diagnostics check(const std::string& path) {
  Diagnostics diags;
  ConfigDocument doc = ConfigDocument::parseFile(path, diags);
  if (!doc.ok()) return diags;
  const PipelineConfig cfg = doc.build(test::testRegistry(), diags);
  if (hasErrors(diags)) return diags;
  const Plan plan = compile(cfg.graph);
  diags.insert(diags.end(), plan.diagnostics.begin(), plan.diagnostics.end());
  return diags;
}

// The diagnostic code each corpus file is about (its first error).
const std::map<std::string, DiagCode>& expectedCodes() {
  static const std::map<std::string, DiagCode> codes = {
      {"buffer_bytes_fractional", DiagCode::config_schema},
      {"buffer_bytes_negative_zero", DiagCode::config_schema},
      {"buffer_bytes_too_large", DiagCode::config_schema},
      {"clear_stencil_too_large", DiagCode::config_schema},
      {"clear_too_large", DiagCode::config_schema},
      {"mips_too_large", DiagCode::config_schema},
      {"param_float_too_large", DiagCode::param_range},
      {"param_int_too_large", DiagCode::param_range},
      {"param_int_unbounded_1e300", DiagCode::param_range},
      {"param_int_unbounded_too_large", DiagCode::param_range},
      {"param_vec_component_too_large", DiagCode::param_range},
      {"samples_huge", DiagCode::config_schema},
      {"shader_absolute", DiagCode::param_range},
      {"shader_escape", DiagCode::param_range},
      {"size_width_huge", DiagCode::config_schema},
      {"bad_clear", DiagCode::config_schema},
      {"bad_clear_element", DiagCode::config_schema},
      {"bad_imported", DiagCode::config_schema},
      {"bad_enum", DiagCode::param_range},
      {"bad_mips", DiagCode::config_schema},
      {"bad_layers", DiagCode::config_schema},
      {"bad_cube", DiagCode::config_schema},
      {"cube_not_square", DiagCode::invalid_resource},
      {"subresource_mip_out_of_range", DiagCode::subresource_range},
      {"subresource_two_writers_of_layer", DiagCode::duplicate_writer},
      {"subresource_bad_syntax", DiagCode::config_schema},
      {"subresource_load_other_part", DiagCode::config_schema},
      {"bad_resource_type", DiagCode::config_schema},
      {"bad_samples", DiagCode::config_schema},
      {"bad_scale", DiagCode::config_schema},
      {"bad_size", DiagCode::config_schema},
      {"bad_size_string", DiagCode::config_schema},
      {"bad_size_width", DiagCode::config_schema},
      {"bad_vec3", DiagCode::param_type},
      {"bad_version", DiagCode::config_schema},
      {"binding_not_string", DiagCode::config_schema},
      {"buffer_with_format", DiagCode::config_schema},
      {"buffer_without_bytes", DiagCode::config_schema},
      {"comment", DiagCode::json_syntax},
      {"duplicate_key", DiagCode::config_schema},
      {"duplicate_pass_name", DiagCode::duplicate_pass},
      {"empty", DiagCode::json_syntax},
      {"enabled_not_bool", DiagCode::config_schema},
      {"format_not_allowed", DiagCode::format_not_allowed},
      {"format_not_allowed_version", DiagCode::format_not_allowed},
      {"format_not_string", DiagCode::config_schema},
      {"history_format_mismatch", DiagCode::history_error},
      {"history_of_buffer", DiagCode::history_error},
      {"history_of_empty", DiagCode::config_schema},
      {"history_of_history", DiagCode::history_error},
      {"history_of_imported", DiagCode::history_error},
      {"history_of_not_string", DiagCode::config_schema},
      {"history_of_output", DiagCode::history_error},
      {"history_of_version", DiagCode::history_error},
      {"history_size_mismatch", DiagCode::history_error},
      {"history_unknown_source", DiagCode::history_error},
      {"history_unwritten_source", DiagCode::history_error},
      {"history_written_by_pass", DiagCode::history_error},
      {"input_slot_in_outputs", DiagCode::unknown_slot},
      {"jitter_not_integer", DiagCode::config_schema},
      {"jitter_one", DiagCode::config_schema},
      {"jitter_too_large", DiagCode::config_schema},
      {"missing_format", DiagCode::config_schema},
      {"missing_load_input", DiagCode::missing_slot},
      {"missing_name", DiagCode::config_schema},
      {"missing_outputs_object", DiagCode::missing_slot},
      {"missing_pass_type", DiagCode::config_schema},
      {"missing_passes", DiagCode::config_schema},
      {"missing_required_slot", DiagCode::missing_slot},
      {"number_overflow", DiagCode::json_syntax},
      {"output_not_string", DiagCode::config_schema},
      {"output_slot_in_inputs", DiagCode::unknown_slot},
      {"param_below_min", DiagCode::param_range},
      {"param_bool_type", DiagCode::param_type},
      {"param_not_integral", DiagCode::param_type},
      {"param_out_of_range", DiagCode::param_range},
      {"param_wrong_type", DiagCode::param_type},
      {"params_not_object", DiagCode::config_schema},
      {"pass_jitter_not_bool", DiagCode::config_schema},
      {"passes_not_array", DiagCode::config_schema},
      {"plugin_not_string", DiagCode::config_schema},
      {"python_literal", DiagCode::json_syntax},
      {"resources_not_object", DiagCode::config_schema},
      {"single_quotes", DiagCode::json_syntax},
      {"syntax_error", DiagCode::json_syntax},
      {"too_deep", DiagCode::json_syntax},
      {"top_level_array", DiagCode::config_schema},
      {"trailing_comma", DiagCode::json_syntax},
      {"truncated", DiagCode::json_syntax},
      {"unknown_format", DiagCode::config_schema},
      {"unknown_param", DiagCode::unknown_param},
      {"unknown_pass_key", DiagCode::config_schema},
      {"unknown_pass_type", DiagCode::unknown_pass_type},
      {"unknown_resource_key", DiagCode::config_schema},
      {"unknown_slot", DiagCode::unknown_slot},
      {"unknown_top_level_key", DiagCode::config_schema},
      {"vec3_component_range", DiagCode::param_range},
      {"version_string", DiagCode::config_schema},
  };
  return codes;
}

class InvalidConfig : public ::testing::TestWithParam<std::string> {};

TEST_P(InvalidConfig, FirstErrorMatchesExpected) {
  const std::string name = GetParam();
  const std::string path = invalidDir() + "/" + name + ".json";
  const std::string expectedPath = invalidDir() + "/" + name + ".expected";
  ASSERT_TRUE(fs::exists(expectedPath)) << "missing " << expectedPath;
  std::string expected = trimLine(test::readFile(expectedPath));

  Diagnostics diags = check(path);
  ASSERT_TRUE(hasErrors(diags)) << name << " was accepted";
  const Diagnostic& first = diags.front();
  std::string line = formatDiagnostic(first);
  const std::string prefix = invalidDir() + "/";
  ASSERT_EQ(line.rfind(prefix, 0), 0u) << line;
  EXPECT_EQ(line.substr(prefix.size()), expected);

  auto code = expectedCodes().find(name);
  if (code != expectedCodes().end())
    EXPECT_EQ(diagCodeName(first.code), diagCodeName(code->second)) << line;
  else
    ADD_FAILURE() << "add " << name << " to expectedCodes()";

  // Every diagnostic, not only the first, is located in this file.
  for (const Diagnostic& d : diags) {
    EXPECT_EQ(d.where.file, path) << formatDiagnostic(d);
    EXPECT_GT(d.where.line, 0) << formatDiagnostic(d);
    EXPECT_GT(d.where.column, 0) << formatDiagnostic(d);
  }
}

std::string testName(const ::testing::TestParamInfo<std::string>& info) {
  std::string s = info.param;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Corpus, InvalidConfig, ::testing::ValuesIn(corpusNames()), testName);

TEST(InvalidCorpus, IsCompleteAndPaired) {
  std::vector<std::string> names = corpusNames();
  EXPECT_GE(names.size(), 40u);
  for (const auto& [name, code] : expectedCodes())
    EXPECT_TRUE(std::find(names.begin(), names.end(), name) != names.end()) << name << ".json is missing";
  for (const auto& entry : fs::directory_iterator(invalidDir())) {
    if (entry.path().extension() != ".expected") continue;
    EXPECT_TRUE(fs::exists(fs::path(entry.path()).replace_extension(".json"))) << entry.path() << " has no .json";
    std::string text = test::readFile(entry.path().string());
    EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << entry.path() << " must hold exactly one line";
  }
}

}  // namespace
}  // namespace rgraph
