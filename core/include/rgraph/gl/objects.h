// Move-only RAII wrappers for GL objects (created with DSA: glCreate*), with a
// process-wide live-object counter per kind so tests can prove nothing leaks.
// GL names are uint32_t and enums unsigned here, so this header needs no GL include.
#pragma once

#include <cstdint>
#include <utility>

namespace rgraph::gl {

enum class ObjectKind : uint8_t { texture, framebuffer, buffer, program, shader, vertex_array, query, sampler, count_ };

const char* objectKindName(ObjectKind k);
// Objects of this kind created through these wrappers and not yet deleted.
int64_t liveObjects(ObjectKind k);
// Sum over all kinds.
int64_t liveObjectsTotal();
// Objects of this kind created through these wrappers since the process
// started (never decreases), and the sum over all kinds: a frame that creates
// nothing leaves createdObjectsTotal() unchanged.
int64_t createdObjects(ObjectKind k);
int64_t createdObjectsTotal();

namespace detail {
void countCreated(ObjectKind k);
void destroy(ObjectKind k, uint32_t id);  // deletes the GL object and counts it
}  // namespace detail

template <ObjectKind K>
class Object {
 public:
  Object() = default;
  // Adopts an existing GL name (counted as live).
  explicit Object(uint32_t adopt) : id_(adopt) {
    if (id_) detail::countCreated(K);
  }
  ~Object() { reset(); }
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  Object(Object&& o) noexcept : id_(std::exchange(o.id_, 0u)) {}
  Object& operator=(Object&& o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, 0u);
    }
    return *this;
  }

  uint32_t id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_) detail::destroy(K, std::exchange(id_, 0u));
  }
  static constexpr ObjectKind kind = K;

 private:
  uint32_t id_ = 0;
};

using Texture = Object<ObjectKind::texture>;
using Framebuffer = Object<ObjectKind::framebuffer>;
using Buffer = Object<ObjectKind::buffer>;
using Program = Object<ObjectKind::program>;
using Shader = Object<ObjectKind::shader>;
using VertexArray = Object<ObjectKind::vertex_array>;
using Query = Object<ObjectKind::query>;
using Sampler = Object<ObjectKind::sampler>;

// Creation (DSA). target/type/stage are GL enums.
Texture createTexture(unsigned target);
Framebuffer createFramebuffer();
Buffer createBuffer();
Program createProgram();
Shader createShader(unsigned stage);
VertexArray createVertexArray();
Query createQuery(unsigned target);
Sampler createSampler();

}  // namespace rgraph::gl
