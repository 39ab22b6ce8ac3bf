// Internal to the config loader: the state behind ConfigDocument.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "rgraph/config.h"
#include "source_map.h"

namespace rgraph {

// ordered_json keeps members in file order, so diagnostics come out in the
// order a reader meets them.
using Json = nlohmann::ordered_json;

struct ConfigDocument::Impl {
  std::string file;
  bool ok = false;
  Json root;
  config_detail::SourceMap map;
};

}  // namespace rgraph
