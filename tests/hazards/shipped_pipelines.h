// The shipped pipelines (pipelines/*.json) by name, sorted, and a test name
// made of a string (letters and digits kept, the rest '_').
#pragma once

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

namespace hazardtest {

inline std::vector<std::string> shippedPipelines() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(std::string(RGRAPH_SOURCE_DIR) + "/pipelines"))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

inline std::string testName(std::string n) {
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

}  // namespace hazardtest
