// The graph compiler: validation, versions, ordering, culling, lifetimes and
// aliasing. Pure C++ (no GL). See rgraph/graph.h for the contract.
//
// Outline (every step is linear in the size of the description, apart from the
// heap in the topological sort and the per-descriptor heaps in aliasing; the
// description is large and scattered, so it is swept once and everything after
// works on compact arrays):
//  1. resources: names, resolved extents, descriptor checks.
//  2. one sweep over the passes builds 32-byte use records, emits Plan::passes
//     and Plan::bindings, and registers every write. Versions: the first
//     version of resource R is node R; every in-place write (a writing use with
//     an input) is a node named by its output whose parent is the node its
//     input names. Names resolve through one open-addressing table (no string
//     copies, no allocation per name).
//  3. a DFS from every resource gives each version its resource, its chain
//     successor, and its *effective* version: a disabled pass's in-place write
//     is a pass-through, so its output means the same contents as its input.
//  4. per pass: reads resolved, binding checks, and the edges between enabled
//     passes: RAW (writer of the effective version read -> reader) and WAR
//     (reader of version k -> writer of the next real version).
//  5. Kahn with a min-heap on declaration index (ties keep declaration order);
//     leftovers are cycles, reported as "cycle: a -> b -> a".
//  6. culling: backwards over RAW edges from the writer of the output's final
//     version and from side-effect passes (WAR edges order, they never keep alive).
//  7. lifetimes over the execution order, then greedy aliasing by first use.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <queue>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "rgraph/graph.h"
#include "name_table.h"
#include "rgraph/registry.h"  // closestMatch

namespace rgraph {
namespace {

using graph_detail::NameTable;
using graph_detail::prefetch;

bool locationSet(const SourceLocation& l) { return l.line > 0 || !l.file.empty() || !l.path.empty(); }

uint32_t fullMipCount(Extent e) {
  uint32_t n = 1;
  for (uint32_t m = std::max(e.width, e.height); m > 1; m >>= 1) ++n;
  return n;
}

std::string extentString(Extent e) { return std::to_string(e.width) + "x" + std::to_string(e.height); }

std::string q(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 2);
  out += '\'';
  out += s;
  out += '\'';
  return out;
}

// Aliasing pools: resources may share a physical only with identical keys.
struct PoolKey {
  ResourceKind kind;
  Format format;
  uint32_t width, height, mips, samples;
  uint64_t bytes;  // buffers
  bool operator==(const PoolKey& o) const {
    return kind == o.kind && format == o.format && width == o.width && height == o.height && mips == o.mips &&
           samples == o.samples && bytes == o.bytes;
  }
};
struct PoolKeyHash {
  size_t operator()(const PoolKey& k) const {
    uint64_t h = static_cast<uint64_t>(k.kind) * 0x9E3779B97F4A7C15ull;
    auto mix = [&](uint64_t v) { h = (h ^ v) * 0xBF58476D1CE4E5B9ull; h ^= h >> 31; };
    mix(static_cast<uint64_t>(k.format));
    mix(k.width);
    mix(k.height);
    mix((uint64_t{k.mips} << 32) | k.samples);
    mix(k.bytes);
    return static_cast<size_t>(h);
  }
};

class Compiler {
 public:
  Compiler(const GraphDesc& d, const CompileOptions& o, Plan& p) : d_(d), o_(o), plan_(p) {}

  void run() {
    plan_.output = o_.output;
    nRes_ = static_cast<uint32_t>(d_.resources.size());
    nPass_ = static_cast<uint32_t>(d_.passes.size());
    resources();
    sweep();
    chains();
    resolve();
    output();
    order();
    if (!cyclic_) {
      cull();
      lifetimesAndAliasing();
    }
    finish();
  }

 private:
  // Compact per-use record (flat index over all passes' uses), 32 bytes.
  struct Use {
    const ResourceUse* ru = nullptr;
    uint32_t pass = 0;
    int readVer = -1;   // version read, or loaded by an in-place write
    int writeVer = -1;  // version written
    int res = -1;       // resource touched
    int rawFrom = -1;   // enabled pass this enabled use reads from (RAW edge rawFrom -> pass)
    Access access = Access::sampled;
    bool write = false;
    bool acceptsMultisample = false;
  };
  struct Res {
    Extent extent;
    uint64_t bytes = 0;
    uint32_t mips = 1, samples = 1;
    int first = -1, last = -1, physical = -1;
    Format format = Format::rgba8;
    ResourceKind kind = ResourceKind::texture;
    bool imported = false, hasContent = false, valid = true;
  };
  struct Version {
    int res = -1;
    int writer = -1;    // pass writing it (-1: nobody, or external for imported resources)
    int child = -1;     // chain successor (the first pass, in declaration order, deriving from it)
    int eff = -1;       // effective version (skips pass-throughs of disabled passes)
    int succReal = -1;  // next non-pass-through version in the chain
    int childHead = -1, childTail = -1, sibling = -1;  // derivations, in declaration order
    bool passThrough = false;
    bool reachable = false;  // part of a chain rooted at a resource
    bool alive = true;       // an in-place write whose output name was accepted
    bool afterOutput = false;  // a later version of the output's resource than the output
  };
  enum : uint8_t { kEnabled = 1, kSideEffect = 2 };

  // ------------------------------------------------------------ helpers
  bool enabled(int pass) const { return pass >= 0 && (passFlags_[pass] & kEnabled); }
  const ResourceUse& use(uint32_t flat) const { return *u_[flat].ru; }
  std::string_view versionName(int v) const {
    std::string_view n;
    if (names_.name(v, n)) return n;  // compact copy; the description is large and cold
    return v < static_cast<int>(nRes_) ? resName_[v] : std::string_view(u_[defUse_[v - nRes_]].ru->output);
  }
  // Location of a use: the input or output side, falling back to the pass.
  const SourceLocation& useWhere(uint32_t flat, bool outputSide) const {
    const ResourceUse& u = use(flat);
    const SourceLocation& l = outputSide ? u.outputWhere : u.inputWhere;
    if (locationSet(l)) return l;
    const SourceLocation& other = outputSide ? u.inputWhere : u.outputWhere;
    if (locationSet(other)) return other;
    return d_.passes[u_[flat].pass].where;
  }
  std::string slotLabel(uint32_t flat) const {
    const ResourceUse& u = use(flat);
    std::string s = isWriteAccess(u.access) ? "output " : "input ";
    s += u.slot.empty() ? std::string("(unnamed)") : q(u.slot);
    return s;
  }
  Diagnostic& diag(DiagCode code, std::string message, std::string_view pass, std::string_view slot,
                   std::string_view resource, const SourceLocation& where) {
    Diagnostic dg;
    dg.code = code;
    dg.severity = Severity::error;
    dg.message = std::move(message);
    dg.pass = pass;
    dg.slot = slot;
    dg.resource = resource;
    dg.where = where;
    plan_.diagnostics.push_back(std::move(dg));
    return plan_.diagnostics.back();
  }
  Diagnostic& useDiag(DiagCode code, std::string message, uint32_t flat, std::string_view resource,
                      bool outputSide) {
    return diag(code, std::move(message), d_.passes[u_[flat].pass].name, use(flat).slot, resource,
                useWhere(flat, outputSide));
  }
  // "did you mean" compares the word with every name: with an unknown name in
  // each of n passes that is n^2 comparisons (50,000 typos in a generated
  // config took minutes). The comparisons are budgeted per compile; once
  // spent, the remaining messages come without a suggestion.
  static constexpr size_t kSuggestionBudget = 4'000'000;  // name comparisons, about 0.3 s
  std::string suggestion(std::string_view word) {
    if (candidates_.empty()) {
      candidates_.reserve(nRes_ + defUse_.size());
      for (const auto& r : d_.resources) candidates_.push_back(r.name);
      for (int f : defUse_) candidates_.push_back(u_[f].ru->output);
    }
    if (candidates_.size() > kSuggestionBudget - suggestionWork_) return {};
    suggestionWork_ += candidates_.size();
    std::string best = closestMatch(word, candidates_);
    if (best.empty() || best == word) return {};
    return " (did you mean " + q(best) + "?)";
  }
  const std::string& passName(int p) const { return d_.passes[p].name; }
  // What a use binds, as messages name it: the version the config names,
  // with its resource when that differs: 'hdr_lit' (a version of 'hdr').
  std::string_view boundVersion(uint32_t f) const {
    const Use& u = u_[f];
    const std::string& n = u.write ? u.ru->output : u.ru->input;
    return n.empty() && u.res >= 0 ? resName_[u.res] : std::string_view(n);
  }
  std::string boundName(uint32_t f) const {
    const std::string_view n = boundVersion(f);
    if (u_[f].res < 0 || n == resName_[u_[f].res]) return q(n);
    return q(n) + " (a version of " + q(resName_[u_[f].res]) + ")";
  }

  // ------------------------------------------------------------ steps
  void resources() {
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
      rs.hasContent = rd.imported && rd.importedHasContent;
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
      rs.bytes = textureBytes(td.format, e, td.mips, td.samples);
      if (bad) rs.valid = false;
    }
  }

  // The one full pass over the description's passes and uses: compact use
  // records, Plan::passes and Plan::bindings, and every write registered.
  void sweep() {
    useBegin_.resize(nPass_ + 1);
    passFlags_.resize(nPass_);
    u_.resize(nUses_);
    defUse_.reserve(nUses_ / 2 + 1);
    plan_.passes.resize(nPass_);
    plan_.bindings.resize(nPass_);
    std::vector<uint32_t> pendingFresh;  // first-version writes of names not (yet) known
    std::vector<uint32_t> pendingReads;  // reads of names not (yet) known
    uint32_t f = 0;
    for (uint32_t p = 0; p < nPass_; ++p) {
      const PassDecl& pd = d_.passes[p];
      // Each pass's uses live in their own allocation somewhere in the heap:
      // fetch the next pass's while this one is processed.
      if (p + 2 < nPass_) {
        const auto& next = d_.passes[p + 2].uses;
        const size_t n = std::min<size_t>(next.size(), 4);
        for (size_t i = 0; i < n; ++i) {
          const char* at = reinterpret_cast<const char*>(next.data() + i);
          prefetch(at);
          prefetch(at + 64);
        }
      }
      useBegin_[p] = f;
      passFlags_[p] = (pd.enabled ? kEnabled : 0) | (pd.sideEffect ? kSideEffect : 0);
      PlannedPass& pp = plan_.passes[p];
      pp.decl = p;
      pp.name = pd.name;
      pp.type = pd.type;
      auto& bound = plan_.bindings[p];
      bound.reserve(pd.uses.size());
      for (const ResourceUse& ru : pd.uses) {
        Use& u = u_[f];
        u.ru = &ru;
        u.pass = p;
        u.access = ru.access;
        u.write = isWriteAccess(ru.access);
        u.acceptsMultisample = ru.acceptsMultisample;
        if (!u.write) {
          bound.push_back(BoundUse{ru.slot, ru.access, -1, ru.input, std::string(), false});
          // A name maps to the first id inserted under it, forever: resolving
          // now (while the use is hot) gives what resolving later would.
          if (ru.input.empty())
            useDiag(DiagCode::unknown_resource, slotLabel(f) + " reads no resource (its input is empty)", f, {},
                    false);
          else if ((u.readVer = names_.find(ru.input)) < 0)
            pendingReads.push_back(f);
        } else {
          bound.push_back(BoundUse{ru.slot, ru.access, -1, ru.input, ru.output, ru.input.empty()});
          if (!ru.input.empty())
            inPlaceWrite(f);
          else
            firstWrite(f, pendingFresh);
        }
        ++f;
      }
    }
    useBegin_[nPass_] = f;
    for (uint32_t g : pendingReads) {
      const std::string& in = use(g).input;
      if ((u_[g].readVer = names_.find(in)) < 0)
        useDiag(DiagCode::unknown_resource,
                slotLabel(g) + " reads " + q(in) + ", which is not a declared resource or a version written by any pass" +
                    suggestion(in),
                g, in, false);
    }
    for (uint32_t g : pendingFresh) {
      const std::string& out = use(g).output;
      const int v = names_.find(out);
      if (v >= 0)
        duplicateOfVersion(g, v);
      else
        useDiag(DiagCode::unknown_resource,
                slotLabel(g) + " writes " + q(out) + ", which is not a declared resource" + suggestion(out) +
                    "; a write without an input must name a declared resource",
                g, out, true);
    }
  }

  // An in-place write ("def"): version nRes_ + i, named by its output, so that a
  // read or a load may name a version produced by a later-declared pass.
  void inPlaceWrite(uint32_t f) {
    Use& u = u_[f];
    const ResourceUse& ru = *u.ru;
    const int v = static_cast<int>(nRes_ + defUse_.size());
    defUse_.push_back(static_cast<int>(f));
    Version& ver = vers_.emplace_back();
    ver.writer = static_cast<int>(u.pass);
    if (ru.output.empty()) {
      ver.alive = false;
      useDiag(DiagCode::unknown_resource,
              slotLabel(f) + " loads " + q(ru.input) + " but names no version to produce (set its output name)", f,
              ru.input, true);
      return;
    }
    if (const int existing = names_.insert(ru.output, v); existing >= 0) {
      vers_[v].alive = false;
      std::string msg = slotLabel(f) + " names " + q(ru.output) + " as the version it produces, but " +
                        q(ru.output) + " is already ";
      if (existing < static_cast<int>(nRes_))
        msg += "a declared resource (its first version)";
      else
        msg += "a version written by pass " + q(passName(vers_[existing].writer));
      msg += "; give the new version a new name";
      useDiag(DiagCode::duplicate_writer, std::move(msg), f, ru.output, true);
      return;
    }
    u.writeVer = v;
    defParent_.resize(defUse_.size(), -1);
    defParent_.back() = names_.find(ru.input);  // -1: unknown so far, looked up again later
  }

  // A write without input: the first version of a declared resource.
  void firstWrite(uint32_t f, std::vector<uint32_t>& pending) {
    Use& u = u_[f];
    const std::string& out = u.ru->output;
    if (out.empty()) {
      useDiag(DiagCode::unknown_resource, slotLabel(f) + " writes no resource (its output is empty)", f, {}, true);
      return;
    }
    const int v = names_.find(out);
    if (v < 0) {
      pending.push_back(f);  // unknown, or the output of a later in-place write
      return;
    }
    if (v >= static_cast<int>(nRes_)) {
      duplicateOfVersion(f, v);
      return;
    }
    Version& ver = vers_[v];
    if (ver.writer >= 0) {
      useDiag(DiagCode::duplicate_writer,
              slotLabel(f) + " writes " + q(out) + ", which pass " + q(passName(ver.writer)) +
                  " already writes; every version is written by exactly one pass (to modify it, load it as the "
                  "input and name a new version)",
              f, out, true);
      return;
    }
    ver.writer = static_cast<int>(u.pass);
    u.writeVer = v;
  }

  void duplicateOfVersion(uint32_t f, int v) {
    const std::string& out = use(f).output;
    useDiag(DiagCode::duplicate_writer,
            slotLabel(f) + " writes " + q(out) + ", which is a version already written by pass " +
                q(passName(vers_[v].writer)) +
                "; a write without an input must name a declared resource and writes its first version",
            f, out, true);
  }

  // Parents of in-place writes, then the version chains.
  void chains() {
    const uint32_t nDefs = static_cast<uint32_t>(defUse_.size());
    // The first deriving pass (declaration order) owns the chain successor,
    // later ones are duplicate writers.
    for (uint32_t i = 0; i < nDefs; ++i) {
      const int v = static_cast<int>(nRes_ + i);
      if (!vers_[v].alive) continue;
      const uint32_t f = defUse_[i];
      Use& u = u_[f];
      const std::string& in = u.ru->input;
      const int parent = i < defParent_.size() && defParent_[i] >= 0 ? defParent_[i] : names_.find(in);
      if (parent < 0) {
        useDiag(DiagCode::unknown_resource,
                slotLabel(f) + " loads " + q(in) + ", which is not a declared resource or a version written by any pass" +
                    suggestion(in),
                f, in, false);
        continue;
      }
      u.readVer = parent;
      Version& pv = vers_[parent];
      if (pv.childHead >= 0) {
        const int firstChild = pv.childHead;
        useDiag(DiagCode::duplicate_writer,
                slotLabel(f) + " derives a new version from " + q(in) + ", but pass " +
                    q(passName(vers_[firstChild].writer)) + " already derives " + q(versionName(firstChild)) +
                    " from it; a version has one successor: load " + q(versionName(firstChild)) + " instead",
                f, in, false);
        vers_[pv.childTail].sibling = v;
      } else {
        pv.childHead = v;
      }
      pv.childTail = v;
    }
    // DFS from each resource's first version, preorder; each resource's
    // versions are contiguous in preorder_ (Plan::resources[r].versions).
    preorder_.reserve(vers_.size());
    resVersionsBegin_.resize(nRes_ + 1);
    std::vector<int> stack, tmp;
    for (uint32_t r = 0; r < nRes_; ++r) {
      resVersionsBegin_[r] = static_cast<uint32_t>(preorder_.size());
      Version& root = vers_[r];
      root.res = static_cast<int>(r);
      root.eff = static_cast<int>(r);
      root.reachable = true;
      if (root.childHead < 0) {  // the common case: no in-place writes
        preorder_.push_back(static_cast<int>(r));
        continue;
      }
      stack.push_back(static_cast<int>(r));
      while (!stack.empty()) {
        const int v = stack.back();
        stack.pop_back();
        preorder_.push_back(v);
        Version& ver = vers_[v];
        ver.child = ver.childHead;
        tmp.clear();
        for (int c = ver.childHead; c >= 0; c = vers_[c].sibling) {
          Version& cv = vers_[c];
          cv.res = ver.res;
          cv.reachable = true;
          cv.passThrough = !enabled(cv.writer);
          cv.eff = cv.passThrough ? ver.eff : c;
          tmp.push_back(c);
        }
        for (auto it = tmp.rbegin(); it != tmp.rend(); ++it) stack.push_back(*it);
      }
    }
    resVersionsBegin_[nRes_] = static_cast<uint32_t>(preorder_.size());
    for (auto it = preorder_.rbegin(); it != preorder_.rend(); ++it) {
      Version& ver = vers_[*it];
      if (ver.child < 0) continue;
      const Version& c = vers_[ver.child];
      ver.succReal = c.passThrough ? c.succReal : ver.child;
    }
    // In-place writes whose names loop back on themselves never reach a resource.
    for (uint32_t i = 0; i < nDefs; ++i) {
      const uint32_t f = defUse_[i];
      if (!vers_[nRes_ + i].alive || u_[f].readVer < 0 || vers_[nRes_ + i].reachable) continue;
      useDiag(DiagCode::read_never_written,
              slotLabel(f) + " loads " + q(use(f).input) + ", which is derived (through in-place writes) from " +
                  q(use(f).output) + " itself; no pass writes the first version of this chain",
              f, use(f).input, false);
    }
  }

  // Per pass: resolve reads, bind resources, collect edges, and check the
  // bindings (all passes, enabled or not: a config is either valid or not).
  void resolve() {
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
        bound->resource = u.res;
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
        for (const Att& a : attachments) {
          if (&a == base || !r_[a.res].valid) continue;
          const Res& rs = r_[a.res];
          const bool out = u_[a.flat].write;
          if (rs.extent != b.extent)
            useDiag(DiagCode::attachment_size_mismatch,
                    slotLabel(a.flat) + " (" + boundName(a.flat) + ") is " + extentString(rs.extent) + " but " +
                        slotLabel(base->flat) + " (" + boundName(base->flat) + ") is " + extentString(b.extent) +
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
  void dependency(Use& u, uint32_t f, int p) {
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
  void checkUse(const Use& u, uint32_t f, std::vector<Att>& attachments, std::vector<Att>& sampledReads,
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
                      " is a colour format (use depth24, depth32f, depth24_stencil8 or depth32f_stencil8)",
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

  void output() {
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
    plan_.outputResource = vers_[v].res;
    plan_.outputVersion = versionName(e);
    outputDescriptor();
    const int w = vers_[e].writer;
    if (enabled(w)) {
      outputWriter_ = w;
      return;
    }
    std::string msg = "output " + q(d_.output);
    if (e != v) msg += " (the same contents as " + q(versionName(e)) + ", disabled passes pass it through)";
    msg += " is never written by an enabled pass";
    if (w >= 0) msg += ": its only writer, pass " + q(passName(w)) + ", is disabled";
    diag(DiagCode::output_never_written, std::move(msg), w >= 0 ? std::string_view(passName(w)) : "", {}, d_.output,
         d_.outputWhere);
  }

  // What the output resource must be for the caller to read it back as an image.
  void outputDescriptor() {
    const int r = plan_.outputResource;
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

  void order() {
    std::vector<uint32_t> adjBegin(nPass_ + 1, 0), indeg(nPass_, 0);
    for (const auto& [a, b] : edges_) {
      ++adjBegin[a + 1];
      ++indeg[b];
    }
    for (uint32_t p = 0; p < nPass_; ++p) adjBegin[p + 1] += adjBegin[p];
    std::vector<uint32_t> adj(edges_.size());
    {
      std::vector<uint32_t> cursor(adjBegin.begin(), adjBegin.end() - 1);
      for (const auto& [a, b] : edges_) adj[cursor[a]++] = static_cast<uint32_t>(b);
    }
    std::vector<uint32_t> heapStore;
    heapStore.reserve(nPass_);
    std::priority_queue<uint32_t, std::vector<uint32_t>, std::greater<uint32_t>> ready(std::greater<uint32_t>(),
                                                                                     std::move(heapStore));
    uint32_t enabledCount = 0;
    for (uint32_t p = 0; p < nPass_; ++p)
      if (passFlags_[p] & kEnabled) {
        ++enabledCount;
        if (indeg[p] == 0) ready.push(p);
      }
    topo_.reserve(enabledCount);
    while (!ready.empty()) {
      const uint32_t p = ready.top();
      ready.pop();
      topo_.push_back(p);
      for (uint32_t i = adjBegin[p]; i < adjBegin[p + 1]; ++i)
        if (--indeg[adj[i]] == 0) ready.push(adj[i]);
    }
    if (topo_.size() < enabledCount) {
      cyclic_ = true;
      reportCycles(indeg);
    }
  }

  void reportCycles(const std::vector<uint32_t>& indeg) {
    // Every pass left over has a predecessor that is left over too: walking
    // backwards along the lowest-index such predecessor must close a cycle.
    std::vector<char> left(nPass_, 0);
    for (uint32_t p = 0; p < nPass_; ++p) left[p] = (passFlags_[p] & kEnabled) && indeg[p] > 0;
    std::vector<int> pred(nPass_, -1);
    for (const auto& [a, b] : edges_)
      if (left[a] && left[b] && (pred[b] < 0 || a < pred[b])) pred[b] = a;
    std::vector<int> walk(nPass_, 0), pos(nPass_, -1);
    std::vector<int> path;
    int walkId = 0;
    for (uint32_t s = 0; s < nPass_; ++s) {
      if (!left[s] || walk[s]) continue;
      ++walkId;
      path.clear();
      int cur = static_cast<int>(s);
      while (cur >= 0 && walk[cur] == 0) {
        walk[cur] = walkId;
        pos[cur] = static_cast<int>(path.size());
        path.push_back(cur);
        cur = pred[cur];
      }
      if (cur < 0 || walk[cur] != walkId) continue;  // joined an earlier walk: nothing new
      // path[pos[cur]..] walks backwards along the cycle; reverse it to run forwards.
      std::vector<int> cyc(path.begin() + pos[cur], path.end());
      std::reverse(cyc.begin(), cyc.end());
      std::rotate(cyc.begin(), std::min_element(cyc.begin(), cyc.end()), cyc.end());
      std::string msg = "cycle: ";
      for (int p : cyc) msg += passName(p) + " -> ";
      msg += passName(cyc.front());
      msg += " (each pass must run after the one before it: it reads a version that pass writes, or that pass "
             "overwrites a version it reads)";
      diag(DiagCode::cycle, std::move(msg), passName(cyc.front()), {}, {}, d_.passes[cyc.front()].where);
    }
  }

  void cull() {
    needed_.assign(nPass_, 0);
    std::vector<uint32_t> stack;
    stack.reserve(nPass_);
    auto mark = [&](int p) {
      if (enabled(p) && !needed_[p]) {
        needed_[p] = 1;
        stack.push_back(static_cast<uint32_t>(p));
      }
    };
    mark(outputWriter_);
    for (uint32_t p = 0; p < nPass_; ++p)
      if (passFlags_[p] & kSideEffect) mark(static_cast<int>(p));
    while (!stack.empty()) {
      const uint32_t p = stack.back();
      stack.pop_back();
      for (uint32_t f = useBegin_[p]; f < useBegin_[p + 1]; ++f) mark(u_[f].rawFrom);
    }
    plan_.order.reserve(topo_.size());
    for (uint32_t p : topo_)
      if (needed_[p]) plan_.order.push_back(p);
    // A pass kept for its side effect that writes a later version of the
    // output's resource would overwrite the image before the frame ends.
    if (outputVer_ < 0) return;
    for (int c = vers_[outputVer_].child; c >= 0; c = vers_[c].child) {
      const int w = vers_[c].writer;
      if (!enabled(w) || !needed_[w]) continue;
      diag(DiagCode::invalid_output,
           "output " + q(d_.output) + " is overwritten by pass " + q(passName(w)) +
               ", which writes the later version " + q(versionName(c)) + " and runs for its side effect; name " +
               q(versionName(c)) + " as the output, or write the side effect's result to another resource",
           passName(w), {}, d_.output, d_.outputWhere);
      break;
    }
  }

  // Buffers are pooled like textures: two buffers share one physical buffer when
  // their sizes are equal and their lifetimes do not overlap.
  void lifetimesAndAliasing() {
    std::vector<uint32_t> byFirst;
    byFirst.reserve(nRes_);
    for (uint32_t i = 0; i < plan_.order.size(); ++i) {
      const uint32_t p = plan_.order[i];
      for (uint32_t f = useBegin_[p]; f < useBegin_[p + 1]; ++f) {
        const int r = u_[f].res;
        if (r < 0) continue;
        Res& rs = r_[r];
        if (rs.first < 0) {
          rs.first = static_cast<int>(i);
          byFirst.push_back(static_cast<uint32_t>(r));
        }
        rs.last = static_cast<int>(i);
      }
    }
    struct Pool {
      std::priority_queue<std::pair<int, int>, std::vector<std::pair<int, int>>, std::greater<>> busy;  // (last, phys)
      std::priority_queue<int, std::vector<int>, std::greater<>> free;
    };
    std::vector<Pool> pools;
    std::unordered_map<PoolKey, int, PoolKeyHash> poolOf;
    plan_.physical.reserve(o_.alias ? byFirst.size() / 4 + 16 : byFirst.size());
    for (uint32_t r : byFirst) {
      Res& rs = r_[r];
      if (rs.imported || !rs.valid) continue;
      plan_.naiveBytes += rs.bytes;
      PoolKey key{rs.kind, Format::rgba8, 0, 0, 0, 0, 0};
      if (rs.kind == ResourceKind::texture)
        key = {rs.kind, rs.format, rs.extent.width, rs.extent.height, rs.mips, rs.samples, 0};
      else
        key.bytes = rs.bytes;
      int phys = -1;
      Pool* pool = nullptr;
      if (o_.alias) {
        auto [it, inserted] = poolOf.try_emplace(key, static_cast<int>(pools.size()));
        if (inserted) pools.emplace_back();
        pool = &pools[it->second];
        while (!pool->busy.empty() && pool->busy.top().first < rs.first) {
          pool->free.push(pool->busy.top().second);
          pool->busy.pop();
        }
        if (!pool->free.empty()) {
          phys = pool->free.top();
          pool->free.pop();
        }
      }
      if (phys < 0) {
        phys = static_cast<int>(plan_.physical.size());
        PhysicalTexture& pt = plan_.physical.emplace_back();
        pt.kind = rs.kind;
        pt.bytes = rs.bytes;
        if (rs.kind == ResourceKind::texture) {
          pt.format = rs.format;
          pt.extent = rs.extent;
          pt.mips = rs.mips;
          pt.samples = rs.samples;
        }
        plan_.allocatedBytes += pt.bytes;
      }
      plan_.physical[phys].resources.push_back(r);
      rs.physical = phys;
      if (pool) pool->busy.push({rs.last, phys});
    }
  }

  // Writes the per-pass and per-resource results into the plan.
  void finish() {
    for (uint32_t i = 0; i < plan_.order.size(); ++i) plan_.passes[plan_.order[i]].order = static_cast<int>(i);
    for (uint32_t p = 0; p < nPass_; ++p) {
      PlannedPass& pp = plan_.passes[p];
      if (!(passFlags_[p] & kEnabled)) {
        pp.culled = true;
        pp.reason = "disabled";
      } else if (!cyclic_ && !needed_[p]) {
        pp.culled = true;
        std::string outs, later;
        for (uint32_t f = useBegin_[p]; f < useBegin_[p + 1]; ++f) {
          if (!u_[f].write) continue;
          const int wv = u_[f].writeVer;
          const std::string_view out = wv >= 0 ? versionName(wv) : std::string_view(u_[f].ru->output);
          if (out.empty()) continue;
          if (!outs.empty()) outs += ", ";
          outs += out;
          if (wv >= 0 && vers_[wv].afterOutput) later = out;
        }
        if (!later.empty())
          pp.reason = "it writes " + q(later) + ", a later version of " + q(resName_[plan_.outputResource]) +
                      " than the output " + q(d_.output) + ", and nothing that reaches the output reads its outputs (" +
                      outs + ")";
        else
          pp.reason = outs.empty() ? "it writes nothing and has no side effect"
                                   : "its outputs (" + outs + ") are never read by a pass that reaches the output";
      }
    }
    plan_.resources.resize(nRes_);
    for (uint32_t r = 0; r < nRes_; ++r) {
      const Res& rs = r_[r];
      PlannedResource& pr = plan_.resources[r];
      pr.name = versionName(static_cast<int>(r));
      pr.kind = rs.kind;
      pr.imported = rs.imported;
      pr.extent = rs.extent;
      pr.bytes = rs.bytes;
      pr.firstPass = rs.first;
      pr.lastPass = rs.last;
      pr.physical = rs.physical;
      const uint32_t b = resVersionsBegin_[r], e = resVersionsBegin_[r + 1];
      pr.versions.reserve(e - b);
      for (uint32_t i = b; i < e; ++i) pr.versions.emplace_back(versionName(preorder_[i]));
    }
  }

  const GraphDesc& d_;
  const CompileOptions& o_;
  Plan& plan_;
  uint32_t nRes_ = 0, nPass_ = 0, nUses_ = 0;
  std::vector<uint32_t> useBegin_;
  std::vector<uint8_t> passFlags_;
  std::vector<Use> u_;
  std::vector<Res> r_;
  std::vector<std::string_view> resName_;
  std::vector<int> defUse_;     // in-place write i -> flat use; its version is nRes_ + i
  std::vector<int> defParent_;  // in-place write i -> the version its input names, -1 if not known yet
  std::vector<Version> vers_;
  std::vector<int> preorder_;
  std::vector<uint32_t> resVersionsBegin_;
  NameTable names_;
  std::vector<std::pair<int, int>> edges_;
  std::vector<uint32_t> topo_;
  std::vector<char> needed_;
  std::vector<std::string> candidates_;
  size_t suggestionWork_ = 0;  // names compared by suggestion() so far
  int outputWriter_ = -1;
  int outputVer_ = -1;  // the version "output" names
  bool cyclic_ = false;
};

}  // namespace

Plan compile(const GraphDesc& desc, const CompileOptions& options) {
  Plan plan;
  Compiler(desc, options, plan).run();
  return plan;
}

}  // namespace rgraph
