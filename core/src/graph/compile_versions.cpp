// The graph compiler, steps 2 and 3: the one sweep over the passes (use
// records, Plan::passes and Plan::bindings, writes registered) and the
// version chains. See compile.cpp for the outline.
#include <algorithm>
#include <string>
#include <vector>

#include "compile_internal.h"

namespace rgraph::graph_detail {

// The one full pass over the description's passes and uses: compact use
// records, Plan::passes and Plan::bindings, and every write registered.
void Compiler::sweep() {
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
    pp.decl = PassIndex(p);
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
        bound.push_back(BoundUse{ru.slot, ru.access, ResourceIndex(), ru.input, std::string(), false});
        // A name maps to the first id inserted under it, forever: resolving
        // now (while the use is hot) gives what resolving later would.
        if (ru.input.empty())
          useDiag(DiagCode::unknown_resource, slotLabel(f) + " reads no resource (its input is empty)", f, {},
                  false);
        else if ((u.readVer = names_.find(ru.input)) < 0)
          pendingReads.push_back(f);
      } else {
        bound.push_back(BoundUse{ru.slot, ru.access, ResourceIndex(), ru.input, ru.output, ru.input.empty()});
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

// "NAME_2" (or _3, ...): a name no resource or binding of the graph uses.
std::string Compiler::unusedVersionName(const std::string& base) const {
  for (int i = 2;; ++i) {
    const std::string name = base + "_" + std::to_string(i);
    bool used = false;
    for (const auto& r : d_.resources) used = used || r.name == name;
    for (const auto& p : d_.passes)
      for (const auto& ru : p.uses) used = used || ru.input == name || ru.output == name;
    if (!used) return name;
  }
}

// An in-place write ("def"): version nRes_ + i, named by its output, so that a
// read or a load may name a version produced by a later-declared pass.
void Compiler::inPlaceWrite(uint32_t f) {
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
    vers_[existing].renamedWrite = true;
    std::string msg = slotLabel(f) + " names " + q(ru.output) + " as the version it produces, but " +
                      q(ru.output) + " is ";
    if (ru.output == ru.input)
      msg += "the version it loads: drawing over a version produces a new one";
    else if (existing < static_cast<int>(nRes_))
      msg += "already a declared resource (its first version)";
    else
      msg += "already a version written by pass " + q(passName(vers_[existing].writer));
    msg += "; give the new version a new name (e.g. " + q(unusedVersionName(ru.input.empty() ? ru.output : ru.input)) +
           ") and read that one after this pass";
    useDiag(DiagCode::duplicate_writer, std::move(msg), f, ru.output, true);
    return;
  }
  u.writeVer = v;
  defParent_.resize(defUse_.size(), -1);
  defParent_.back() = names_.find(ru.input);  // -1: unknown so far, looked up again later
}

// A write without input: the first version of a declared resource.
void Compiler::firstWrite(uint32_t f, std::vector<uint32_t>& pending) {
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

void Compiler::duplicateOfVersion(uint32_t f, int v) {
  const std::string& out = use(f).output;
  useDiag(DiagCode::duplicate_writer,
          slotLabel(f) + " writes " + q(out) + ", which is a version already written by pass " +
              q(passName(vers_[v].writer)) +
              "; a write without an input must name a declared resource and writes its first version",
          f, out, true);
}

// Parents of in-place writes, then the version chains.
void Compiler::chains() {
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

}  // namespace rgraph::graph_detail
