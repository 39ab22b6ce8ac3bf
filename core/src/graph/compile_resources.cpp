// The graph compiler, step 1 and the output: resource descriptors (names,
// resolved extents, limits) and the version "output" names, with what the
// output image must be. See compile.cpp for the outline.
#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>

#include "compile_internal.h"

namespace rgraph::graph_detail {

namespace {

uint32_t fullMipCount(Extent e) {
  uint32_t n = 1;
  for (uint32_t m = std::max(e.width, e.height); m > 1; m >>= 1) ++n;
  return n;
}

}  // namespace

void Compiler::resources() {
  size_t uses = 0;
  for (const PassDecl& p : d_.passes) uses += p.uses.size();
  nUses_ = static_cast<uint32_t>(uses);
  names_.reserve(static_cast<size_t>(nRes_) + nUses_ / 2 + 16);
  r_.resize(nRes_);
  resName_.resize(nRes_);
  vers_.reserve(static_cast<size_t>(nRes_) + nUses_);
  vers_.resize(nRes_);
  for (uint32_t r = 0; r < nRes_; ++r) {
    const ResourceDecl& rd = d_.resources[r];
    Res& rs = r_[r];
    resName_[r] = rd.name;
    rs.kind = rd.kind;
    rs.imported = rd.imported;
    // A history resource's version 0 (the previous frame) is readable too,
    // even when its declaration is wrong (no second error at its readers).
    rs.hasContent = (rd.imported && rd.importedHasContent) || !rd.historyOf.empty();
    if (rd.name.empty()) {
      diag(DiagCode::invalid_resource, "resource #" + std::to_string(r) + " has an empty name", {}, {}, {},
           rd.where);
      rs.valid = false;
    } else if (int first = names_.insert(rd.name, static_cast<int>(r)); first >= 0) {
      const ResourceDecl& fd = d_.resources[first];
      std::string msg = "resource " + q(rd.name) + " is declared twice";
      if (fd.where.line > 0)
        msg += " (first declared at " + (fd.where.file.empty() ? std::string("line ") : fd.where.file + ":") +
               std::to_string(fd.where.line) + ")";
      diag(DiagCode::duplicate_resource, std::move(msg), {}, {}, rd.name, rd.where);
      rs.valid = false;
    }
    if (rd.kind == ResourceKind::buffer) {
      rs.bytes = rd.bufferBytes;
      if (rd.bufferBytes == 0) {
        diag(DiagCode::invalid_resource, "buffer " + q(rd.name) + " has a size of 0 bytes", {}, {}, rd.name,
             rd.where);
        rs.valid = false;
      }
      continue;
    }
    const TextureDesc& td = rd.texture;
    rs.format = td.format;
    rs.samples = td.samples;
    bool bad = false;
    auto invalid = [&](std::string msg) {
      diag(DiagCode::invalid_resource, std::move(msg), {}, {}, rd.name, rd.where);
      bad = true;
    };
    if (td.size.kind == SizeSpec::Kind::absolute && (td.size.width == 0 || td.size.height == 0))
      invalid("texture " + q(rd.name) + " has size " + std::to_string(td.size.width) + "x" +
              std::to_string(td.size.height) + "; width and height must be at least 1");
    if (td.size.kind == SizeSpec::Kind::scale && (!(td.size.scale > 0.0f) || !std::isfinite(td.size.scale)))
      invalid("texture " + q(rd.name) + " has scale " + std::to_string(td.size.scale) +
              "; the scale relative to the output must be greater than 0");
    const Extent e = resolveSize(td.size, o_.output);
    rs.extent = e;
    if (!bad && (e.width == 0 || e.height == 0))
      invalid("texture " + q(rd.name) + " resolves to size " + extentString(e) + " (output size " +
              extentString(o_.output) + ")");
    else if (!bad && o_.maxTextureSize > 0 && std::max(e.width, e.height) > o_.maxTextureSize)
      invalid("texture " + q(rd.name) + " is " + extentString(e) +
              (td.size.kind == SizeSpec::Kind::absolute ? std::string()
                                                        : " (at output size " + extentString(o_.output) + ")") +
              ", larger than " + std::to_string(o_.maxTextureSize) + " pixels per side, " +
              (o_.maxTextureSizeOrigin.empty()
                   ? std::string("the GL_MAX_TEXTURE_SIZE every OpenGL 4.5 device reaches")
                   : o_.maxTextureSizeOrigin));
    if (td.samples != 1 && td.samples != 2 && td.samples != 4 && td.samples != 8)
      invalid("texture " + q(rd.name) + " has " + std::to_string(td.samples) +
              " samples; the sample count must be 1, 2, 4 or 8");
    else if (td.samples > 1 && td.mips != 1)
      invalid("texture " + q(rd.name) + " is multisampled (" + std::to_string(td.samples) +
              " samples) and must have exactly 1 mip level, not " +
              (td.mips == 0 ? std::string("a full chain") : std::to_string(td.mips)));
    const uint32_t full = fullMipCount(e);
    if (td.mips > full && e.width > 0 && e.height > 0)
      invalid("texture " + q(rd.name) + " asks for " + std::to_string(td.mips) + " mip levels, but a " +
              extentString(e) + " texture has at most " + std::to_string(full));
    rs.mips = td.mips == 0 ? full : std::min(td.mips, full);
    shape(rd, e, invalid);
    rs.layers = std::max<uint32_t>(td.layers, 1);
    rs.cube = td.cube;
    rs.bytes = textureBytes(td.format, e, td.mips, td.samples, arrayLayers(td));
    if (bad) rs.valid = false;
  }
}

// Arrays and cube maps: layer counts within what every OpenGL 4.5 device
// holds, cubes square, neither multisampled.
template <class Invalid>
void Compiler::shape(const ResourceDecl& rd, Extent e, Invalid& invalid) {
  const TextureDesc& td = rd.texture;
  // GL_MAX_ARRAY_TEXTURE_LAYERS is at least 2048 in OpenGL 4.5; a cube array counts six per cube.
  constexpr uint32_t kMaxLayers = 2048;
  if (td.layers == 0)
    invalid("texture " + q(rd.name) + " has 0 layers; an array texture has at least 1");
  else if (arrayLayers(td) > kMaxLayers || td.layers > kMaxLayers)
    invalid("texture " + q(rd.name) + " has " + std::to_string(td.layers) + (td.cube ? " cubes (" : " layers (") +
            std::to_string(uint64_t{td.layers} * (td.cube ? 6u : 1u)) +
            " array layers), more than the 2048 every OpenGL 4.5 device holds (GL_MAX_ARRAY_TEXTURE_LAYERS)");
  if (td.cube && e.width != e.height && e.width > 0)
    invalid("texture " + q(rd.name) + " is a cube map of " + extentString(e) + "; a cube map's faces are square");
  if (td.samples > 1 && (td.cube || td.layers > 1))
    invalid("texture " + q(rd.name) + " is multisampled (" + std::to_string(td.samples) + " samples) and " +
            (td.cube ? "a cube map" : "an array") + "; only single 2D textures may be multisampled");
}

void Compiler::output() {
  if (d_.output.empty()) {
    diag(DiagCode::no_output, "the graph names no output: set \"output\" to the resource that becomes the image",
         {}, {}, {}, d_.outputWhere);
    return;
  }
  int v = names_.find(d_.output);
  if (v < 0) {
    diag(DiagCode::unknown_resource,
         "output " + q(d_.output) + " is not a declared resource or a version written by any pass" +
             suggestion(d_.output),
         {}, {}, d_.output, d_.outputWhere);
    return;
  }
  if (!vers_[v].reachable) return;  // a naming loop, reported already
  // Exactly the version named: later versions of the resource are not part
  // of the image (culling drops their writers). When disabled passes pass it
  // through, the version they alias is the one actually written.
  outputVer_ = v;
  for (int c = vers_[v].child; c >= 0; c = vers_[c].child) vers_[c].afterOutput = true;
  const int e = vers_[v].eff;
  plan_.outputResource = ResourceIndex(static_cast<uint32_t>(vers_[v].res));
  plan_.outputVersion = versionName(e);
  outputDescriptor();
  const int w = vers_[e].writer;
  if (enabled(w)) {
    outputWriter_ = w;
    return;
  }
  if (w < 0 && vers_[e].renamedWrite) return;  // reported at its would-be writer
  std::string msg = "output " + q(d_.output);
  if (e != v) msg += " (the same contents as " + q(versionName(e)) + ", disabled passes pass it through)";
  msg += " is never written by an enabled pass";
  if (w >= 0) msg += ": its only writer, pass " + q(passName(w)) + ", is disabled";
  diag(DiagCode::output_never_written, std::move(msg), w >= 0 ? std::string_view(passName(w)) : "", {}, d_.output,
       d_.outputWhere);
}

// What the output resource must be for the caller to read it back as an image.
void Compiler::outputDescriptor() {
  const uint32_t r = plan_.outputResource.value();
  const Res& rs = r_[r];
  const std::string of = "output " + q(d_.output) +
                         (d_.output == resName_[r] ? std::string() : " (a version of " + q(resName_[r]) + ")");
  auto refuse = [&](const std::string& why) {
    diag(DiagCode::invalid_output, of + why, {}, {}, d_.output, d_.outputWhere);
  };
  if (rs.kind == ResourceKind::buffer) return refuse(" is a buffer; the output image must be a texture");
  if (!rs.valid) return;
  if (rs.samples > 1)
    refuse(" is multisampled (" + std::to_string(rs.samples) +
           " samples) and cannot be read back as an image: resolve it first (a blit pass into a single-sample "
           "texture) and name that texture as the output");
  if (isDepthFormat(rs.format))
    refuse(" has the depth format " + std::string(formatName(rs.format)) +
           "; the output image must be a colour texture");
  if (rs.extent != o_.output) {
    const SizeSpec& size = d_.resources[r].texture.size;
    const char* why = size.kind == SizeSpec::Kind::absolute ? " (its fixed size)" : " (scaled from the output size)";
    Diagnostic& dg = diag(DiagCode::output_size,
                          of + " is " + extentString(rs.extent) + why + ", not the requested output size " +
                              extentString(o_.output) + ": the image is " + extentString(rs.extent) +
                              " (resources sized \"output\" are " + extentString(o_.output) + ")",
                          {}, {}, d_.output, d_.resources[r].where);
    dg.severity = Severity::warning;
  }
}

}  // namespace rgraph::graph_detail
