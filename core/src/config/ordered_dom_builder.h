// A SAX handler that builds an nlohmann::ordered_json document in linear time.
//
// nlohmann's own builder (json_sax_dom_parser) adds each object member with
// ordered_map::operator[], which first searches the members already there
// for the same key: an object of n members costs n^2/2 key comparisons (a
// config whose "resources" hold 50,000 entries spent seconds there, one with
// a million never finished). Here an object is searched linearly while it is
// small and through a hash index once it grows. A repeated key keeps its first
// place and its last value, as the library does.
//
// parse_error is left to the class deriving from this one (sax_parse calls it
// on the handler's static type).
#pragma once

#include <cstddef>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace rgraph::config_detail {

class OrderedDomBuilder {
 public:
  using Json = nlohmann::ordered_json;

  explicit OrderedDomBuilder(Json& root) : root_(root) {}

  bool null() { return add(Json(nullptr)); }
  bool boolean(bool v) { return add(Json(v)); }
  bool number_integer(Json::number_integer_t v) { return add(Json(v)); }
  bool number_unsigned(Json::number_unsigned_t v) { return add(Json(v)); }
  bool number_float(Json::number_float_t v, const Json::string_t& /*text*/) { return add(Json(v)); }
  bool string(Json::string_t& v) { return add(Json(std::move(v))); }
  bool binary(Json::binary_t& v) { return add(Json(std::move(v))); }

  bool start_object(std::size_t /*size unknown in text*/) { return open(true); }
  bool start_array(std::size_t /*size unknown in text*/) { return open(false); }
  bool end_array() {
    --depth_;
    return true;
  }
  // The members move into the object's ordered_map once, in file order.
  bool end_object() {
    Frame& f = frames_[--depth_];
    auto& object = static_cast<Json::object_t::Container&>(f.value->get_ref<Json::object_t&>());
    object.reserve(f.members.size());
    for (auto& [key, value] : f.members) object.emplace_back(std::move(key), std::move(value));
    f.members.clear();
    f.index.clear();
    return true;
  }

  bool key(Json::string_t& k) {
    Frame& f = frames_[depth_ - 1];
    auto& members = f.members;
    if (f.index.empty() && members.size() >= kIndexFrom)
      for (size_t i = 0; i < members.size(); ++i) f.index.emplace(members[i].first, i);
    if (!f.index.empty()) {
      auto [it, inserted] = f.index.try_emplace(k, members.size());
      if (!inserted) {
        member_ = &members[it->second].second;
        return true;
      }
    } else {
      for (auto& m : members) {
        if (m.first != k) continue;
        member_ = &m.second;
        return true;
      }
    }
    members.emplace_back(std::move(k), Json());
    member_ = &members.back().second;
    return true;
  }

 private:
  static constexpr size_t kIndexFrom = 16;  // members searched linearly below this

  // One open object or array. An object's members gather here first: an
  // ordered_map holds pair<const std::string, json>, which its vector copies
  // (whole subtrees) instead of moving when it grows, since that move may
  // throw. Frames are reused by depth, so siblings reuse their buffers.
  struct Frame {
    Json* value = nullptr;  // stays valid: its parent grows only after it is closed
    bool object = false;
    std::vector<std::pair<std::string, Json>> members;
    std::unordered_map<std::string, size_t> index;  // key -> member, for large objects
  };

  bool open(bool object) {
    Json* value = place(Json(object ? Json::value_t::object : Json::value_t::array));
    if (depth_ == frames_.size()) frames_.emplace_back();
    Frame& f = frames_[depth_++];
    f.value = value;
    f.object = object;
    return true;
  }
  bool add(Json&& v) {
    place(std::move(v));
    return true;
  }
  // Puts a new value where the document expects the next one.
  Json* place(Json&& v) {
    if (depth_ == 0) {
      root_ = std::move(v);
      return &root_;
    }
    Frame& f = frames_[depth_ - 1];
    if (!f.object) {
      auto& elements = f.value->get_ref<Json::array_t&>();
      elements.push_back(std::move(v));
      return &elements.back();
    }
    *member_ = std::move(v);
    return member_;
  }

  Json& root_;
  std::vector<Frame> frames_;  // frames_[0, depth_) are open
  size_t depth_ = 0;
  Json* member_ = nullptr;  // the member whose key came last
};

}  // namespace rgraph::config_detail
