// The graph compiler: history resources (ResourceDecl::historyOf). A history
// resource H of a source X holds X's content at the end of the previous
// frame; the executor copies X into H after each frame. So H has no writer in
// the graph (its version 0 is readable, like an imported texture's), a read
// of H orders nothing within the frame, and both X and H must own their
// textures for the whole frame: X's content must survive until the copy and
// H's from the copy until its readers run. See compile.cpp for the outline.
#include <string>
#include <vector>

#include "compile_internal.h"

namespace rgraph::graph_detail {

namespace {

std::string sizeString(const SizeSpec& s, Extent resolved) {
  switch (s.kind) {
    case SizeSpec::Kind::output:
      return "output size (" + extentString(resolved) + ")";
    case SizeSpec::Kind::absolute:
      return extentString(resolved);
    case SizeSpec::Kind::scale:
      break;
  }
  std::string scale = std::to_string(s.scale);
  scale.erase(scale.find_last_not_of('0') + 1);
  if (!scale.empty() && scale.back() == '.') scale.pop_back();
  return "scale " + scale + " (" + extentString(resolved) + ")";
}

bool sameSize(const SizeSpec& a, const SizeSpec& b) {
  if (a.kind != b.kind) return false;
  if (a.kind == SizeSpec::Kind::absolute) return a.width == b.width && a.height == b.height;
  return a.kind == SizeSpec::Kind::output || a.scale == b.scale;
}

}  // namespace

// "rgba16f, output size (1280x720), 1 sample, 1 mip level"
std::string Compiler::descriptorString(uint32_t r) const {
  const TextureDesc& t = d_.resources[r].texture;
  const Res& rs = r_[r];
  return std::string(formatName(t.format)) + ", " + sizeString(t.size, rs.extent) + ", " + std::to_string(t.samples) +
         (t.samples == 1 ? " sample, " : " samples, ") +
         (t.mips == 0 ? std::string("a full mip chain")
                      : std::to_string(t.mips) + (t.mips == 1 ? " mip level" : " mip levels")) +
         (t.cube ? (t.layers > 1 ? ", " + std::to_string(t.layers) + " cubes" : std::string(", a cube map"))
                 : (t.layers > 1 ? ", " + std::to_string(t.layers) + " layers" : std::string()));
}

// Runs after output() (it needs the output's resource and the version chains).
void Compiler::history() {
  histSrc_.assign(nRes_, -1);
  histWriter_.assign(nRes_, -1);
  keptHistory_.assign(nRes_, -1);
  const int outputRes = plan_.outputResource.valid() ? static_cast<int>(plan_.outputResource.value()) : -1;
  for (uint32_t h = 0; h < nRes_; ++h) {
    const ResourceDecl& hd = d_.resources[h];
    if (hd.historyOf.empty()) continue;
    ++historyCount_;
    const SourceLocation& where = locationSet(hd.historyWhere) ? hd.historyWhere : hd.where;
    const std::string self = "history resource " + q(hd.name);
    auto fail = [&](std::string msg, const SourceLocation& at) {
      diag(DiagCode::history_error, self + msg, {}, {}, hd.name, at);
    };
    const int s = names_.find(hd.historyOf);
    if (s < 0) {
      fail(
          ": \"history_of\" names " + q(hd.historyOf) + ", which is not a declared resource" + suggestion(hd.historyOf),
          where);
      continue;
    }
    if (s >= static_cast<int>(nRes_)) {
      const int res = vers_[s].res;
      fail(": \"history_of\" names " + q(hd.historyOf) + ", a version" +
               (res >= 0 ? " of resource " + q(resName_[res]) : std::string()) +
               ", not a resource; name the resource (the history holds its content at the end of the frame, "
               "after its last write)",
           where);
      continue;
    }
    const ResourceDecl& sd = d_.resources[s];
    if (!sd.historyOf.empty()) {
      fail(" is a history of " + q(sd.name) + ", itself a history resource (of " + q(sd.historyOf) +
               "); a history holds the previous frame of a resource the passes write: name that resource",
           where);
      continue;
    }
    if (hd.kind == ResourceKind::buffer || sd.kind == ResourceKind::buffer) {
      fail(std::string(hd.kind == ResourceKind::buffer ? " is a buffer"
                                                       : ": its source " + q(sd.name) + " is a buffer") +
               "; only textures keep a history across frames",
           hd.kind == ResourceKind::buffer ? hd.where : where);
      continue;
    }
    if (hd.imported && static_cast<int>(h) != outputRes) {
      fail(" is imported; a history resource belongs to the graph, which fills it (remove \"imported\")", hd.where);
      continue;
    }
    if (s == outputRes) {
      fail(" keeps the output image " + q(sd.name) +
               ", whose content belongs to the caller (presentation) once the frame ends: the graph cannot keep it "
               "for the next frame. Write the image into a texture of its own, keep that one's history, and "
               "copy it to the output",
           where);
      continue;
    }
    if (sd.imported) {
      fail(" keeps the imported resource " + q(sd.name) +
               ", whose content the caller owns between frames: the graph cannot promise it survives to the next "
               "frame. Keep the history of a resource the graph owns",
           where);
      continue;
    }
    if (r_[h].valid && r_[s].valid &&
        (hd.texture.format != sd.texture.format || !sameSize(hd.texture.size, sd.texture.size) ||
         hd.texture.samples != sd.texture.samples || hd.texture.mips != sd.texture.mips ||
         hd.texture.layers != sd.texture.layers || hd.texture.cube != sd.texture.cube)) {
      fail(" (" + descriptorString(h) + ") does not match its source " + q(sd.name) + " (" + descriptorString(s) +
               "); a history holds its source's previous content and must have the same format, size, samples, "
               "mips and layers (leave them out to take the source's)",
           hd.where);
      continue;
    }
    if (keptHistory_[s] >= 0) {
      fail(": " + q(sd.name) + " already has the history resource " +
               q(resName_[static_cast<uint32_t>(keptHistory_[s])]) + "; read that one",
           where);
      continue;
    }
    // What the executor copies is the source's content after its last write:
    // the last version of its chain written by an enabled pass.
    int last = s;
    for (int c = vers_[s].child; c >= 0; c = vers_[c].child) last = c;
    const int writer = vers_[vers_[last].eff].writer;
    if (!enabled(writer)) {
      fail(": no enabled pass writes its source " + q(sd.name) +
               (writer >= 0 ? std::string(" (its writers are disabled)") : std::string()) +
               ", so there is no previous frame to keep",
           where);
      continue;
    }
    keptHistory_[s] = static_cast<int>(h);
    histSrc_[h] = s;
    histWriter_[h] = writer;
  }
  if (historyCount_ == 0) return;
  // Passes never write a history resource: its content is the previous frame's.
  for (uint32_t f = 0; f < nUses_; ++f) {
    const Use& u = u_[f];
    if (!u.write || u.res < 0 || d_.resources[u.res].historyOf.empty()) continue;
    useDiag(DiagCode::history_error,
            slotLabel(f) + " writes " + boundName(f) + ", a history resource (of " + q(d_.resources[u.res].historyOf) +
                "); history resources are written by the executor, not by passes: it copies the source into it "
                "after each frame",
            f, boundVersion(f), true);
  }
}

// The source's writer of a history read by pass p, as cull() follows it: -1
// when the use is not a history read.
int Compiler::historyWriterRead(uint32_t f) const {
  const Use& u = u_[f];
  return !u.write && u.res >= 0 && historyCount_ > 0 ? histWriter_[u.res] : -1;
}

// A history H of X read by a pass that runs: both live for the whole frame and
// own their textures (X's content must survive the frame for the copy, H's
// from the start). Returns whether r is such a resource; sets its lifetime.
bool Compiler::wholeFrame(uint32_t r) {
  if (plan_.order.empty()) return false;
  // A persistent resource keeps its content across frames (ResourceDecl::persistent).
  if (d_.resources[r].persistent && r_[r].first >= 0) {
    r_[r].first = 0;
    r_[r].last = static_cast<int>(plan_.order.size()) - 1;
    return true;
  }
  if (historyCount_ == 0) return false;
  const int h = histSrc_[r] >= 0 ? static_cast<int>(r) : keptHistory_[r];
  if (h < 0 || r_[h].first < 0 || r_[histSrc_[h]].first < 0) return false;
  r_[r].first = 0;
  r_[r].last = static_cast<int>(plan_.order.size()) - 1;
  return true;
}

}  // namespace rgraph::graph_detail
