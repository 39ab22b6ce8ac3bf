// parseJsonValue (rgraph/json_value.h): the config files' parser, bound and messages.
#include "rgraph/json_value.h"

#include "json_text.h"

namespace rgraph {

std::optional<JsonValueError> parseJsonValue(const std::string& text, nlohmann::ordered_json& value,
                                             size_t enclosingDepth) {
  const size_t bound = config_detail::SourceMap::kMaxDepth;
  std::optional<config_detail::JsonSyntaxError> error =
      config_detail::parseJsonText(text, value, enclosingDepth < bound ? bound - enclosingDepth : 0);
  if (!error) return std::nullopt;
  return JsonValueError{error->offset, std::move(error->message)};
}

}  // namespace rgraph
