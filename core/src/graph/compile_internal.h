// Internal to the graph compiler: one Compiler per compile(), its member
// functions split by step over these files (see the outline in compile.cpp):
//   compile.cpp            run(), diagnostics helpers, the plan's per-pass
//                          and per-resource results (finish);
//   compile_resources.cpp  resource descriptors, and the output (step 1 and
//                          the output checks);
//   compile_versions.cpp   the sweep over the passes, in-place writes and
//                          version chains (steps 2 and 3);
//   compile_bindings.cpp   reads resolved, binding checks, RAW/WAR edges
//                          (step 4);
//   compile_order.cpp      topological order, cycles, culling (steps 5, 6);
//   compile_alias.cpp      lifetimes and aliasing (step 7);
//   compile_history.cpp    history resources: checks (after the output),
//                          what culling follows, whole-frame lifetimes.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rgraph/graph.h"
#include "name_table.h"

namespace rgraph::graph_detail {

inline bool locationSet(const SourceLocation& l) { return l.line > 0 || !l.file.empty() || !l.path.empty(); }

inline std::string extentString(Extent e) { return std::to_string(e.width) + "x" + std::to_string(e.height); }

inline std::string q(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 2);
  out += '\'';
  out += s;
  out += '\'';
  return out;
}

// A lowered description (compile_subresources.cpp) compiles cells of the
// caller's textures as resources: `of` maps each to the caller's resource
// (its unit), `rep` each unit to its first cell, `mip` each cell to its first
// mip level (attachment sizes are those of the level).
struct CellUnits {
  std::vector<uint32_t> of, rep, mip;
};

class Compiler {
 public:
  Compiler(const GraphDesc& d, const CompileOptions& o, Plan& p, const CellUnits* units = nullptr)
      : d_(d), o_(o), plan_(p), units_(units) {}

  void run();

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
    uint32_t mips = 1, samples = 1, layers = 1;
    bool cube = false;
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
    // A pass's in-place write named this version as the one it produces and
    // was refused ("give the new version a new name"): that pass meant to
    // write it, so reading it unwritten is not reported again.
    bool renamedWrite = false;
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
                   std::string_view resource, const SourceLocation& where);
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
  std::string suggestion(std::string_view word);
  const std::string& passName(int p) const { return d_.passes[p].name; }
  // What a use binds, as messages name it: the version the config names,
  // with its resource when that differs: 'hdr_lit' (a version of 'hdr').
  std::string_view boundVersion(uint32_t f) const {
    const Use& u = u_[f];
    const std::string& n = u.write ? u.ru->output : u.ru->input;
    return n.empty() && u.res >= 0 ? resName_[u.res] : std::string_view(n);
  }
  // The size a resource is attached at: its mip level's, for a cell of a lowered description.
  Extent attachedExtent(int r) const {
    const uint32_t m = units_ ? units_->mip[r] : 0;
    const Extent e = r_[r].extent;
    return {std::max<uint32_t>(1, e.width >> m), std::max<uint32_t>(1, e.height >> m)};
  }
  std::string boundName(uint32_t f) const {
    const std::string_view n = boundVersion(f);
    if (u_[f].res < 0 || n == resName_[u_[f].res]) return q(n);
    return q(n) + " (a version of " + q(resName_[u_[f].res]) + ")";
  }

  // ------------------------------------------------------------ steps
  // compile_resources.cpp
  void resources();
  void output();
  void outputDescriptor();
  template <class Invalid>
  void shape(const ResourceDecl& rd, Extent e, Invalid& invalid);
  // compile_versions.cpp
  void sweep();
  void inPlaceWrite(uint32_t f);
  std::string unusedVersionName(const std::string& base) const;
  void firstWrite(uint32_t f, std::vector<uint32_t>& pending);
  void duplicateOfVersion(uint32_t f, int v);
  void chains();
  // compile_bindings.cpp
  void resolve();
  void dependency(Use& u, uint32_t f, int p);
  template <class Att>
  void checkUse(const Use& u, uint32_t f, std::vector<Att>& attachments, std::vector<Att>& sampledReads,
                std::vector<Att>& blitSrc, std::vector<Att>& blitDst);
  // compile_order.cpp
  void order();
  void reportCycles(const std::vector<uint32_t>& indeg);
  void cull();
  bool writesAfterOutput(uint32_t pass) const;
  void keepHistorySources(std::vector<uint32_t>& stack);
  // compile_alias.cpp
  void lifetimesAndAliasing();
  void peakLiveBytes(const std::vector<uint32_t>& used);  // Plan::peakLiveBytes, after lifetimesAndAliasing
  // compile_history.cpp
  void history();
  std::string descriptorString(uint32_t r) const;
  int historyWriterRead(uint32_t f) const;
  bool wholeFrame(uint32_t r);
  // compile.cpp
  void finish();

  const GraphDesc& d_;
  const CompileOptions& o_;
  Plan& plan_;
  const CellUnits* units_ = nullptr;
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
  // History resources (compile_history.cpp), per resource, -1 for none:
  std::vector<int> histSrc_;      // history H -> its source X (a valid declaration)
  std::vector<int> histWriter_;   // history H -> the enabled pass writing X's last version
  std::vector<int> keptHistory_;  // source X -> its history H
  std::vector<int> keptFor_;      // pass -> the history H it runs for alone (it feeds only the next frame)
  uint32_t historyCount_ = 0;     // resources declaring "history_of"
  int outputWriter_ = -1;
  int outputVer_ = -1;  // the version "output" names
  bool cyclic_ = false;
};

// compile(): lowers subresource bindings (compile_subresources.cpp) around the Compiler.
Plan compileSubresources(const GraphDesc& desc, const CompileOptions& options);

}  // namespace rgraph::graph_detail
