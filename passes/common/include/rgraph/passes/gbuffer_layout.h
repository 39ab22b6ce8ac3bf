// The G-buffer layouts: the one table of what each layout stores, in which
// formats, at how many bytes per pixel and under which shader define. The
// geometry pass (what it must write), the G-buffer readers (what they need
// bound and compile with: lighting_options.h, the ssao plugin) and rgraph bench
// (the targets its pipelines declare) read it instead of restating layouts.
// Its GLSL side is shaders/include/gbuffer.glsl and shaders/gbuffer.frag.
// docs/writing-a-pass.md's G-buffer tables are generated from it
// (rgraph_doc_tables; the ctest docs.generated_tables fails when they differ).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rgraph/pass.h"
#include "rgraph/pass_check.h"

namespace rgraph::gbuffer {

// One colour target of a layout. A layout's targets are in the geometry
// pass's slot order, which is gbuffer.frag's output location order.
struct Target {
  std::string slot;    // the geometry pass's output slot, the readers' input slot
  Format format;       // the format rgraph bench declares (geometry accepts others)
  std::string stores;  // what gbuffer.frag writes there
  // Written only for scenes that need it: the geometry pass and its readers
  // have a boolean parameter named as the slot (emissive, reflectance), on in
  // the shipped pipelines and turned off with the slot unbound by scene
  // adaptation when no drawn material needs it (lighting::adaptGBuffer).
  bool optional = false;
};

struct Layout {
  std::string name;             // the value of the passes' "layout" param
  std::string define;           // GBUFFER_* define of gbuffer.frag and include/gbuffer_read.glsl
  std::string summary;          // a short note in the geometry pass's param description ("": none)
  std::vector<Target> targets;  // colour targets, slot order
  Format depth;                 // the depth format rgraph bench declares
  uint32_t normalComponents;    // components the normal target needs at least
  bool positionFromDepth;       // no position target: readers rebuild position from depth
  std::string depthStores;      // what the depth target holds for a reader (docs/writing-a-pass.md's table)

  const Target* target(std::string_view slot) const;
  bool writes(std::string_view slot) const { return target(slot) != nullptr; }
  // The targets' and the depth's bytes per pixel, one sample each, without
  // the optional targets (what a scene with none of their features gets).
  uint32_t bytesPerPixel() const;
  // What the optional target of `slot` adds per pixel (0: the layout has none).
  uint32_t optionalBytesPerPixel(std::string_view slot) const;
  // Where a reader gets the position: "position", or "depth" to rebuild it.
  std::string positionSlot() const { return positionFromDepth ? "depth" : "position"; }
  // The slots a reader of this layout needs bound, in the order their errors
  // are reported: normal, albedo, positionSlot(), and material when the layout
  // writes one and the material is not constant.
  std::vector<std::string> readerSlots(bool constantMaterial) const;
  // Whether a pass with these params writes (geometry) or reads (lighting)
  // `slot`: the layout has it, material unless constant_material, an optional
  // target when its parameter is on.
  bool uses(std::string_view slot, const ParamSet& params) const;
};

// The optional targets' slots, in slot order (emissive, reflectance): each is
// also a boolean parameter of the geometry pass and its readers.
std::vector<std::string> optionalSlots();

// The target any layout adds when asked, after its own targets and the
// velocity target: "object_id", what gbuffer.frag writes there for picking
// (Renderer::requestPick). Unlike the optional targets above, the scene
// never asks for it: a pipeline does (the geometry pass's boolean parameter
// "object_id", with the slot bound) or the embedding program does
// (RendererOptions::picking adds both). Absent otherwise: no texture, no
// attachment, no shader output.
const Target& objectIdTarget();

inline constexpr std::string_view kDefaultLayout = "pbr";

// Every layout, in the order the "layout" params list them.
const std::vector<Layout>& layouts();
// The layout called `name`; the default layout for a name the table lacks
// (params are checked against names() before any pass reads them).
const Layout& find(std::string_view name);
// The layout of a pass's "layout" param (default: kDefaultLayout).
const Layout& of(const ParamSet& params);
// Layout names in table order (the "layout" params' choices).
std::vector<std::string> names();
// "learnopengl, pbr (4x rgba16f), ...": names joined by ", ", each with its
// summary in parentheses when withSummaries.
std::string nameList(bool withSummaries);
// Every colour slot any layout writes, in slot order (position, normal,
// albedo, material): the geometry pass's colour slots.
std::vector<std::string> colorSlots();

// Rule (PassTypeDesc::rules) of a G-buffer reader: its "layout" is the layout
// the G-buffer it reads was written with. The writer is the pass that wrote
// the version a colour slot or "depth" reads, when it has a "layout" param
// and wrote it through the slot of the same name (as geometry does). Two
// layouts store different things in the same slots (compact: an octahedral
// normal, no position), so a reader of another layout would decode nonsense;
// the error, at the reader's "layout", names both passes and where the
// writer's layout is set.
PassRule sameLayoutAsWriterRule();

}  // namespace rgraph::gbuffer
