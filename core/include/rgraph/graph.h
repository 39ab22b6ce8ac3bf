// The render graph: a declarative description (GraphDesc) and its compiled
// plan (Plan). Compiling is pure C++: no GL context, no GL include.
//
// Contract (read this before writing a pass or a config):
//  * A *resource* is declared once (texture or buffer, transient or imported).
//  * Every write creates a new *version* of a resource. A version has a name:
//    the first written version of resource R is called R; a pass that modifies
//    a resource in place (blending into it, loading it as an attachment) binds
//    the version it reads and names the version it produces, e.g. reads "hdr",
//    writes "hdr_lit". Both names refer to the same physical memory.
//  * A version is written by exactly one pass. Read-after-write order follows
//    from names; write-after-read order follows from versions: the pass that
//    produces version k+1 runs after every reader of version k.
//  * compile() validates, orders passes topologically (ties keep declaration
//    order), culls passes that feed no output, write no caller's texture
//    (imported with content) and have no side effect (the output is one
//    version: writers of its later versions are culled too),
//    computes lifetimes over the order, and aliases transient textures whose
//    descriptors match and whose lifetimes do not overlap.
#pragma once

#include <cassert>
#include <compare>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rgraph/diagnostics.h"
#include "rgraph/format.h"

namespace rgraph {

// ---------------------------------------------------------------- resources

struct SizeSpec {
  enum class Kind { output, absolute, scale };
  Kind kind = Kind::output;
  uint32_t width = 0, height = 0;  // Kind::absolute
  float scale = 1.0f;              // Kind::scale: relative to the output size

  static SizeSpec output() { return {}; }
  static SizeSpec absolute(uint32_t w, uint32_t h) { return {Kind::absolute, w, h, 1.0f}; }
  static SizeSpec relative(float s) { return {Kind::scale, 0, 0, s}; }
};

struct Extent {
  uint32_t width = 0, height = 0;
  bool operator==(const Extent& o) const { return width == o.width && height == o.height; }
  bool operator!=(const Extent& o) const { return !(*this == o); }
};

// Resolve a size against the output extent (scale rounds, never below 1).
Extent resolveSize(const SizeSpec& s, Extent output);

// A texture's shape: a 2D image, or a 2D array (layers > 1), a cube map
// (cube, layers == 1) or a cube-map array (cube, layers cubes), each with a
// mip chain. A cube's faces are array layers in GL order +x, -x, +y, -y, +z,
// -z; cube k of a cube array is layers 6k .. 6k+5.
struct TextureDesc {
  Format format = Format::rgba8;
  SizeSpec size;
  uint32_t mips = 1;     // 0 means a full mip chain (config "mips": "full")
  uint32_t samples = 1;
  uint32_t layers = 1;   // array layers; cubes when `cube`
  bool cube = false;     // square; six faces per layer
  std::optional<std::vector<float>> clear;  // clear value applied by the first writer
};

// Mip levels of a texture of this descriptor at this extent (a full chain for mips 0).
uint32_t mipLevels(const TextureDesc& t, Extent e);
// Array layers a subresource index counts (6 per cube).
inline uint32_t arrayLayers(const TextureDesc& t) { return t.layers * (t.cube ? 6u : 1u); }

// A part of a texture that a slot binds: mip levels [mipBegin, mipBegin +
// mipCount) and array layers [layerBegin, layerBegin + layerCount). kAll
// counts to the last level or layer. Config syntax after a name (either part
// may be left out, ranges inclusive, `*` all): `hdr.mip[2]`, `bloom.mip[1..4]`,
// `shadow.layer[3]`, `shadow.layer[*]`, `env.face[+x]` (a cube's faces: +x -x
// +y -y +z -z), `env.mip[1].face[-z]`. An attachment bound to several layers
// is a layered attachment (the shader picks the layer with gl_Layer).
struct Subresource {
  static constexpr uint32_t kAll = UINT32_MAX;
  uint32_t mipBegin = 0, mipCount = kAll;
  uint32_t layerBegin = 0, layerCount = kAll;
  bool whole() const { return mipBegin == 0 && mipCount == kAll && layerBegin == 0 && layerCount == kAll; }
  bool operator==(const Subresource&) const = default;
};

// Splits "NAME(.mip[..])(.layer[..]|.face[..])" into the name and the
// subresource. A string with no ".mip[", ".layer[" or ".face[" is a plain
// name (whole). Returns an error message (empty when it parsed).
std::string parseSubresourceRef(std::string_view text, std::string& name, Subresource& sub);
// "bloom.mip[3]", "shadow.layer[0..3]", "env.face[+x]" (a face when `cube`
// and the range is one layer of the first cube); the bare name for whole().
std::string subresourceLabel(std::string_view name, const Subresource& sub, bool cube = false);

enum class ResourceKind { texture, buffer };

struct ResourceDecl {
  std::string name;
  ResourceKind kind = ResourceKind::texture;
  TextureDesc texture;          // kind == texture
  uint64_t bufferBytes = 0;     // kind == buffer
  bool imported = false;        // owned outside the graph (the output image, caller textures)
  // Imported resources usually arrive with content (version 0 is readable):
  // the caller's textures, whose writers are never culled (the caller sees
  // what they write). The output image does not.
  bool importedHasContent = true;
  // A history resource: non-empty names the resource whose content at the end
  // of the previous frame this one holds (config key "history_of"). Nobody
  // writes it; passes read it like any texture. Its source is kept across
  // frames; neither is ever aliased. The executor copies the source into it
  // after each frame and clears it (PassContext::historyValid false) on the
  // first frame, after a resize, a reload and a camera cut.
  std::string historyOf;
  SourceLocation historyWhere;  // the "history_of" value
  // A persistent resource (config key "persistent": true): its content
  // outlives the frame and stays valid until the executor is told otherwise
  // (rgraph/gl/executor.h, invalidatePersistent): the first frame after a
  // build or resize, or the scene's environment changed. A pass that writes
  // only persistent resources runs only while they are invalid (the IBL
  // pre-filter passes: steady frames skip them). Never aliased.
  bool persistent = false;
  SourceLocation where;
};

// ---------------------------------------------------------------- passes

enum class Access {
  color_attachment,        // write
  depth_attachment,        // write (depth/stencil test + write)
  depth_attachment_read,   // read-only depth/stencil test
  sampled,                 // read
  storage_read,            // read (image or buffer)
  storage_write,           // write (image or buffer)
  blit_src,                // read
  blit_dst,                // write
};

bool isWriteAccess(Access a);
bool isAttachmentAccess(Access a);
std::string_view accessName(Access a);

// One slot of a pass bound to resources.
//  * Reading access: `input` names the version read; `output` is empty.
//  * Writing access: `output` names the version produced. If `input` is set,
//    the pass loads that version (read-modify-write) and `output` is its
//    successor; if `input` is empty, `output` must name a declared resource
//    whose first version this pass writes (contents start cleared/undefined).
struct ResourceUse {
  std::string slot;
  Access access = Access::sampled;
  std::string input;
  std::string output;
  bool acceptsMultisample = false;  // sampled through sampler2DMS / resolved by the pass itself
  // The part of the texture the slot binds (input and output alike): whole
  // by default. Versions, order, culling and hazards are per subresource.
  Subresource sub;
  SourceLocation inputWhere, outputWhere;
};

struct PassDecl {
  std::string name;
  std::string type;
  std::vector<ResourceUse> uses;
  bool sideEffect = false;  // never culled (e.g. writes a file, reads back stats)
  bool enabled = true;      // disabled in-place passes become pass-throughs
  // false: the pass sees the camera without the pipeline's sub-pixel jitter
  // (config pass key "jitter": false; a UI overlay, for instance).
  bool jitter = true;
  SourceLocation where;
};

struct GraphDesc {
  std::vector<ResourceDecl> resources;
  std::vector<PassDecl> passes;
  // The version that becomes the output image. A resource's name is its first
  // version: naming "h_1" while a later pass writes "h_2" shows h_1, and the
  // passes that only produce later versions are culled.
  std::string output;
  SourceLocation outputWhere;
};

// ---------------------------------------------------------------- the plan

// An index into one of the plan's arrays, typed by that array: a
// ResourceIndex cannot subscript Plan::physical, and "none" is a named state
// (valid() is false) rather than -1. Nothing converts to or from an integer
// implicitly: build one with an explicit value, read it with value() (to
// subscript a vector) or through the Plan accessors below.
template <class Tag>
class PlanIndex {
 public:
  constexpr PlanIndex() = default;  // invalid
  constexpr explicit PlanIndex(uint32_t i) : value_(i) {}
  constexpr bool valid() const { return value_ != kInvalid; }
  constexpr uint32_t value() const {
    assert(valid());
    return value_;
  }
  // Invalid orders after every valid index.
  friend constexpr auto operator<=>(const PlanIndex&, const PlanIndex&) = default;

 private:
  static constexpr uint32_t kInvalid = UINT32_MAX;
  uint32_t value_ = kInvalid;
};
// Prints the value, or "none" (test failures, logs).
template <class Tag>
std::ostream& operator<<(std::ostream& os, PlanIndex<Tag> i);

using PassIndex = PlanIndex<struct PassIndexTag>;          // into Plan::passes / Plan::bindings (declaration order)
using StepIndex = PlanIndex<struct StepIndexTag>;          // a position in Plan::order (execution order)
using ResourceIndex = PlanIndex<struct ResourceIndexTag>;  // into Plan::resources (declaration order)
using PhysicalIndex = PlanIndex<struct PhysicalIndexTag>;  // into Plan::physical

struct CompileOptions {
  Extent output{1280, 720};
  bool alias = true;  // false: every transient gets its own physical texture
  // Largest width or height of a texture (0: no limit). 16384 is the
  // GL_MAX_TEXTURE_SIZE every OpenGL 4.5 implementation must reach; the
  // executor passes the device's own value.
  uint32_t maxTextureSize = 16384;
  // Where that limit comes from, as messages say it (e.g. "this device's
  // GL_MAX_TEXTURE_SIZE"); empty: the OpenGL 4.5 minimum.
  std::string maxTextureSizeOrigin = {};
  // Hazard modes (rgraph/hazards.h) that change the plan, each still valid:
  // nonzero: passes ready at once are taken in an order drawn from this seed
  // instead of declaration order (`reorder`); every edge is still respected.
  uint64_t reorderSeed = 0;
  // Aliasing takes the highest-numbered free texture of a pool instead of the
  // lowest (`alias-shuffle`); lifetimes still never overlap.
  bool reverseAliasing = false;
  // false: every enabled pass runs (`no-cull`), but those that write a later
  // version of the output's resource than the output (they would overwrite
  // the image).
  bool cull = true;
};

struct PlannedPass {
  PassIndex decl;             // index into GraphDesc::passes (and Plan::passes)
  std::string name, type;
  StepIndex order;            // position in execution order, invalid when culled
  bool culled = false;
  std::string reason;         // why culled ("disabled", ...), or "kept: ..." when it runs only for the next frame
};

struct PlannedResource {
  std::string name;
  ResourceKind kind = ResourceKind::texture;
  bool imported = false;
  Extent extent;              // resolved size (textures)
  uint64_t bytes = 0;         // memory it would need on its own
  StepIndex firstPass;        // execution-order index of first use, invalid when unused
  StepIndex lastPass;         // execution-order index of last use
  PhysicalIndex physical;     // invalid for imported and unused resources
  std::vector<std::string> versions;  // version names in write order
  // A history read by a pass that runs (else invalid): its source. Both own a physical, whole frame.
  ResourceIndex historyOf;
  // The source of such a live history: that history (invalid otherwise; nothing to copy then).
  ResourceIndex history;
  bool persistent = false;  // ResourceDecl::persistent: owns its physical for the whole frame
};

struct PhysicalTexture {
  ResourceKind kind = ResourceKind::texture;
  Format format = Format::rgba8;
  Extent extent;
  uint32_t mips = 1, samples = 1;  // mips resolved (never 0)
  uint32_t layers = 1;             // as TextureDesc::layers
  bool cube = false;
  uint64_t bytes = 0;
  std::vector<ResourceIndex> resources;  // the resources sharing it, in first-use order
};

// A resolved binding of one slot for the executor: which resource and which
// versions it touches.
struct BoundUse {
  std::string slot;
  Access access = Access::sampled;
  ResourceIndex resource;   // invalid only in a plan that is not ok
  std::string readVersion;  // empty for a fresh write
  std::string writeVersion; // empty for a read
  bool firstWrite = false;  // writes version 0: apply the resource's clear here
  // The part bound, resolved: counts are never kAll in an ok plan (whole
  // textures: every level and layer). Buffers: whole.
  Subresource sub;
};

// What a plan promises its readers (the executor, the memory barriers, the
// CLI's plan printer), so that they index without checking bounds:
//  * Always, ok or not: passes and bindings have one entry per GraphDesc
//    pass, resources one per GraphDesc resource, in declaration order;
//    passes[i].decl is i.
//  * When ok():
//    - every BoundUse::resource of every pass (culled or not) is valid;
//    - a resource is used by a pass that runs exactly when its firstPass and
//      lastPass are valid; every such resource is imported or has a valid
//      physical, which lists it; a resource with a physical is not imported
//      and is used;
//    - order holds each pass that runs once, and passes[order[s]].order is s;
//    - outputResource is valid, a texture, and used by a pass that runs (so
//      it is imported or has a physical).
// A plan that is not ok promises only the first point: readers that show
// errors (validate, dot) check valid() before they index.
// checkPlanContract() states the promise as code: compile() asserts it in
// debug builds, and the tests check it for every ok plan they make.
struct Plan {
  Extent output;
  std::vector<PlannedPass> passes;          // one per GraphDesc pass, declaration order
  std::vector<PassIndex> order;             // execution order (culled excluded)
  std::vector<PlannedResource> resources;   // one per GraphDesc resource, declaration order
  std::vector<PhysicalTexture> physical;
  std::vector<std::vector<BoundUse>> bindings;  // per pass (declaration order)
  ResourceIndex outputResource;
  std::string outputVersion;                // the version that becomes the image (see GraphDesc::output)
  uint64_t naiveBytes = 0;                  // every live transient on its own
  uint64_t allocatedBytes = 0;              // after aliasing
  // The most transient bytes live at one pass: the least any allocator needs,
  // one that aliases across formats and sizes (a GPU memory heap) included.
  // allocatedBytes - peakLiveBytes is what sharing only identical textures costs.
  uint64_t peakLiveBytes = 0;
  Diagnostics diagnostics;
  bool ok() const { return !hasErrors(diagnostics); }

  // Typed subscripts: an index of the wrong kind does not compile.
  const PlannedPass& pass(PassIndex i) const { return passes[i.value()]; }
  const std::vector<BoundUse>& uses(PassIndex i) const { return bindings[i.value()]; }
  PassIndex step(StepIndex s) const { return order[s.value()]; }
  const PlannedResource& resource(ResourceIndex i) const { return resources[i.value()]; }
  const PhysicalTexture& physicalTexture(PhysicalIndex i) const { return physical[i.value()]; }
};

// Validate and compile. Never throws for bad input: problems are diagnostics.
// When diagnostics contain errors, the plan's order/physical may be partial.
Plan compile(const GraphDesc& desc, const CompileOptions& options = {});

// The promise above, checked: empty when it holds (a plan that is not ok is
// held to its first point only), otherwise the first broken point.
std::string checkPlanContract(const Plan& plan);

// Size in bytes of a texture with this descriptor at this extent (mips, samples included).
uint64_t textureBytes(Format f, Extent e, uint32_t mips, uint32_t samples, uint32_t arrayLayers = 1);

// Graphviz DOT of a compiled graph: passes (boxes) and resource versions
// (ellipses), read/write edges, culled passes dashed grey, aliased resources
// sharing a physical texture in one colour and labelled "phys #N".
std::string toDot(const GraphDesc& desc, const Plan& plan);

}  // namespace rgraph
