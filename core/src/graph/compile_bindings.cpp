// The graph compiler, step 4: reads resolved, binding checks (formats,
// attachments, feedback loops, blits) and the RAW/WAR edges between
// enabled passes. See compile.cpp for the outline.
#include <string>
#include <vector>

#include "compile_internal.h"
#include "rgraph/format_sets.h"

namespace rgraph::graph_detail {

// Per pass: resolve reads, bind resources, collect edges, and check the
// bindings (all passes, enabled or not: a config is either valid or not).
void Compiler::resolve() {
  edges_.reserve(static_cast<size_t>(nUses_) * 2);
  struct Att {
    uint32_t flat;
    int res;
  };
  std::vector<Att> attachments, sampledReads, blitSrc, blitDst;
  for (uint32_t p = 0; p < nPass_; ++p) {
    attachments.clear();
    sampledReads.clear();
    blitSrc.clear();
    blitDst.clear();
    const bool on = passFlags_[p] & kEnabled;
    const int pi = static_cast<int>(p);
    BoundUse* bound = plan_.bindings[p].data();
    for (uint32_t f = useBegin_[p]; f < useBegin_[p + 1]; ++f, ++bound) {
      Use& u = u_[f];
      const int v = u.writeVer >= 0 ? u.writeVer : u.readVer;
      if (v >= 0 && vers_[v].reachable) u.res = vers_[v].res;
      if (u.res >= 0) bound->resource = ResourceIndex(static_cast<uint32_t>(u.res));
      if (u.readVer >= 0 && !vers_[u.readVer].reachable) u.readVer = -1;  // a naming loop, reported already
      if (on && u.readVer >= 0) dependency(u, f, pi);
      if (u.res >= 0) checkUse(u, f, attachments, sampledReads, blitSrc, blitDst);
    }
    if (attachments.empty() && blitSrc.empty()) continue;
    // Feedback loops: one resource as an attachment and as a texture read.
    for (const Att& s : sampledReads)
      for (const Att& a : attachments)
        if (s.res == a.res) {
          useDiag(DiagCode::feedback_loop,
                  slotLabel(s.flat) + " reads " + boundName(s.flat) + " while " + slotLabel(a.flat) + " binds " +
                      boundName(a.flat) +
                      " as an attachment of the same pass; reading a texture while rendering into it is a feedback "
                      "loop (copy it first, or read an earlier version in another pass)",
                  s.flat, boundVersion(s.flat), false);
          break;
        }
    // Attachments of one framebuffer: one size and one sample count.
    const Att* base = nullptr;
    for (const Att& a : attachments)
      if (r_[a.res].valid) {
        base = &a;
        break;
      }
    if (base) {
      const Res& b = r_[base->res];
      const Extent be = attachedExtent(base->res);
      for (const Att& a : attachments) {
        if (&a == base || !r_[a.res].valid) continue;
        const Res& rs = r_[a.res];
        const bool out = u_[a.flat].write;
        if (const Extent ae = attachedExtent(a.res); ae != be)
          useDiag(DiagCode::attachment_size_mismatch,
                  slotLabel(a.flat) + " (" + boundName(a.flat) + ") is " + extentString(ae) + " but " +
                      slotLabel(base->flat) + " (" + boundName(base->flat) + ") is " + extentString(be) +
                      "; all attachments of a pass must have the same size",
                  a.flat, boundVersion(a.flat), out);
        if (rs.samples != b.samples)
          useDiag(DiagCode::attachment_samples_mismatch,
                  slotLabel(a.flat) + " (" + boundName(a.flat) + ") has " + std::to_string(rs.samples) +
                      " samples but " + slotLabel(base->flat) + " (" + boundName(base->flat) + ") has " +
                      std::to_string(b.samples) + "; all attachments of a pass must have the same sample count",
                  a.flat, boundVersion(a.flat), out);
      }
    }
    // Depth blits need identical formats.
    for (const Att& s : blitSrc)
      for (const Att& t : blitDst) {
        const Format fs = r_[s.res].format, ft = r_[t.res].format;
        if (fs != ft && (isDepthFormat(fs) || isDepthFormat(ft)))
          useDiag(DiagCode::depth_blit_format_mismatch,
                  "blit from " + boundName(s.flat) + " (" + std::string(formatName(fs)) + ") to " +
                      boundName(t.flat) + " (" + std::string(formatName(ft)) +
                      "): blitting depth requires identical source and destination formats",
                  t.flat, boundVersion(t.flat), true);
      }
  }
}

// An enabled pass reading (or loading) a version: RAW and WAR edges, and the
// version must be written by an enabled pass or arrive with an import.
void Compiler::dependency(Use& u, uint32_t f, int p) {
  const int e = vers_[u.readVer].eff;
  const Version& ev = vers_[e];
  if (ev.succReal >= 0) {
    const int next = vers_[ev.succReal].writer;  // enabled by construction
    if (next != p) edges_.push_back({p, next});  // WAR
  }
  const int w = ev.writer;
  if (enabled(w)) {
    if (w != p) {
      u.rawFrom = w;
      edges_.push_back({w, p});  // RAW
    }
    return;
  }
  const Res& rs = r_[ev.res];
  if (e < static_cast<int>(nRes_) && rs.hasContent) return;
  if (w < 0 && ev.renamedWrite) return;  // its would-be writer is reported: "give the new version a new name"
  const std::string& in = u.ru->input;
  std::string msg = slotLabel(f) + (u.write ? " loads " : " reads ") + q(in);
  if (e != u.readVer) msg += " (the same contents as " + q(versionName(e)) + ", disabled passes pass it through)";
  if (w >= 0)
    msg += ", but its only writer, pass " + q(passName(w)) + ", is disabled";
  else if (rs.imported)
    msg += ", but no pass writes it and the imported resource " + q(resName_[ev.res]) + " arrives without content";
  else
    msg += ", but no pass writes it";
  useDiag(DiagCode::read_never_written, std::move(msg), f, in, false);
}

template <class Att>
void Compiler::checkUse(const Use& u, uint32_t f, std::vector<Att>& attachments, std::vector<Att>& sampledReads,
                        std::vector<Att>& blitSrc, std::vector<Att>& blitDst) {
  const int r = u.res;
  const Res& rs = r_[r];
  if (rs.kind == ResourceKind::buffer) {
    if (u.access != Access::storage_read && u.access != Access::storage_write)
      useDiag(DiagCode::access_format_mismatch,
              slotLabel(f) + " binds buffer " + boundName(f) + " as " + std::string(accessName(u.access)) +
                  "; buffers can only be bound as storage_read or storage_write",
              f, boundVersion(f), u.write);
    return;
  }
  switch (u.access) {
    case Access::color_attachment: {
      const FormatInfo& fi = formatInfo(rs.format);
      if (fi.isDepth)
        useDiag(DiagCode::access_format_mismatch,
                slotLabel(f) + " binds " + boundName(f) + " as a colour attachment, but its format " +
                    std::string(fi.name) + " is a depth format (bind it as depth_attachment)",
                f, boundVersion(f), u.write);
      else if (!fi.colorRenderable)
        useDiag(DiagCode::rgb_float_attachment,
                slotLabel(f) + " binds " + boundName(f) + " (format " + std::string(fi.name) +
                    ") as a colour attachment; three-channel float formats are not colour-renderable in "
                    "OpenGL 4.5: use " + (rs.format == Format::rgb32f ? "rgba32f" : "rgba16f") + " instead",
                f, boundVersion(f), u.write);
      attachments.push_back({f, r});
      break;
    }
    case Access::depth_attachment:
    case Access::depth_attachment_read:
      if (!isDepthFormat(rs.format))
        useDiag(DiagCode::access_format_mismatch,
                slotLabel(f) + " binds " + boundName(f) + " as a depth attachment, but its format " +
                    std::string(formatName(rs.format)) +
                    " is a colour format (use " + formatNameList(depthFormats()) + ")",
                f, boundVersion(f), u.write);
      attachments.push_back({f, r});
      break;
    case Access::sampled:
      if (rs.samples > 1 && !u.acceptsMultisample)
        useDiag(DiagCode::multisample_sampled,
                slotLabel(f) + " samples " + boundName(f) + ", which has " + std::to_string(rs.samples) +
                    " samples; resolve it first (blit it into a single-sample texture) or bind it to a slot "
                    "that accepts multisample textures",
                f, boundVersion(f), u.write);
      sampledReads.push_back({f, r});
      break;
    case Access::storage_read: sampledReads.push_back({f, r}); break;
    case Access::blit_src: blitSrc.push_back({f, r}); break;
    case Access::blit_dst: blitDst.push_back({f, r}); break;
    case Access::storage_write: break;
  }
}

}  // namespace rgraph::graph_detail
