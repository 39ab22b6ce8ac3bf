// The dynamic section's tables of a plugin image (see plugin_image_checker.h):
// every read bounded by the file, every sum overflow checked.
#include <algorithm>
#include <string_view>
#include <unordered_set>

#include "plugin_image_checker.h"

namespace rgraph::plugin_image {

std::string ImageChecker::dynamicEntries() {
  const Phdr& p = ph_[*dynamic_];
  const uint64_t off = *fileOffset(p.p_vaddr, p.p_memsz), count = p.p_memsz / sizeof(Dyn);
  for (uint64_t k = 0; k < count; ++k) {
    const Dyn e = at<Dyn>(off + k * sizeof(Dyn));
    if (e.d_tag == DT_NULL) return {};
    dynEntries_.emplace_back(int64_t(e.d_tag), uint64_t(e.d_un.d_val));
    dynLast_[int64_t(e.d_tag)] = uint64_t(e.d_un.d_val);
  }
  return "the dynamic section (" + segmentName(*dynamic_, PT_DYNAMIC) + ") has no DT_NULL terminator";
}

// Entry sizes the loader asserts on, the string and symbol tables, strings,
// and the address ranges of init/fini arrays and the GOT.
std::string ImageChecker::tables() {
  struct Ent {
    int64_t tag;
    const char* name;
    uint64_t size;
  };
  for (const Ent& e : {Ent{DT_RELAENT, "DT_RELAENT", sizeof(Rela)}, Ent{DT_RELENT, "DT_RELENT", sizeof(Rel)},
                       Ent{DT_RELRENT, "DT_RELRENT", kWord}, Ent{DT_SYMENT, "DT_SYMENT", sizeof(Sym)}})
    if (auto v = dyn(e.tag); v && *v != e.size)
      return std::string(e.name) + " is " + num(*v) + ", expected " + num(e.size);
  if (auto v = dyn(DT_PLTREL); v && *v != DT_REL && *v != DT_RELA)
    return "DT_PLTREL is " + num(*v) + ", expected DT_REL (17) or DT_RELA (7)";

  const auto strtab = dyn(DT_STRTAB), strsz = dyn(DT_STRSZ), symtab = dyn(DT_SYMTAB);
  if (!strtab || !strsz || !symtab)
    return "the dynamic section lacks DT_STRTAB, DT_STRSZ or DT_SYMTAB: no symbols to load";
  if (std::string e = table("the string table (DT_STRTAB)", *strtab, *strsz, strtabOff_); !e.empty()) return e;
  strsz_ = *strsz;
  if (strsz_ == 0 || d_[strtabOff_ + strsz_ - 1] != 0)
    return "the string table (DT_STRTAB) does not end with a NUL byte";
  symtab_ = *symtab;
  symBound_ = fileBytesFrom(symtab_) / sizeof(Sym);
  if (symBound_ == 0)
    return "the symbol table (DT_SYMTAB) at address " + hex(symtab_) +
           " is not inside the file data of a loaded segment";
  symtabOff_ = *fileOffset(symtab_, sizeof(Sym));

  for (const auto& [tag, value] : dynEntries_) {
    // clang-format off
    const char* name = tag == DT_NEEDED ? "DT_NEEDED" : tag == DT_SONAME ? "DT_SONAME" : tag == DT_RPATH ? "DT_RPATH"
                     : tag == DT_RUNPATH ? "DT_RUNPATH" : tag == DT_AUXILIARY ? "DT_AUXILIARY"
                     : tag == DT_FILTER ? "DT_FILTER" : nullptr;
    // clang-format on
    if (name)
      if (std::string e = stringAt(name, value); !e.empty()) return e;
  }
  struct Arr {
    int64_t tag, sizeTag;
    const char* name;
  };
  for (const Arr& a :
       {Arr{DT_INIT_ARRAY, DT_INIT_ARRAYSZ, "DT_INIT_ARRAY"}, Arr{DT_FINI_ARRAY, DT_FINI_ARRAYSZ, "DT_FINI_ARRAY"},
        Arr{DT_PREINIT_ARRAY, DT_PREINIT_ARRAYSZ, "DT_PREINIT_ARRAY"}}) {
    const auto addr = dyn(a.tag), size = dyn(a.sizeTag);
    if (!addr) continue;
    if (!size) return std::string(a.name) + " without its size (" + a.name + "SZ)";
    if (!loadFor(*addr, *size))
      return std::string(a.name) + " at address " + hex(*addr) + " (" + num(*size) +
             " bytes) is not inside a loaded segment";
  }
  for (int64_t tag : {DT_INIT, DT_FINI}) {
    const auto addr = dyn(tag);
    const Load* l = addr ? loadFor(*addr, 1) : nullptr;
    if (addr && (!l || !(l->flags & PF_X)))
      return std::string(tag == DT_INIT ? "DT_INIT" : "DT_FINI") + " at address " + hex(*addr) +
             " is not inside an executable segment";
  }
  if (auto got = dyn(DT_PLTGOT); got && !loadFor(*got, 3 * kWord))
    return "DT_PLTGOT at address " + hex(*got) + " is not inside a loaded segment";
  textrel_ = dyn(DT_TEXTREL).has_value() || (dyn(DT_FLAGS).value_or(0) & DF_TEXTREL);
  return {};
}

std::string ImageChecker::hashTables() {
  if (auto h = dyn(DT_HASH))
    if (std::string e = sysvHash(*h); !e.empty()) return e;
  if (auto h = dyn(DT_GNU_HASH))
    if (std::string e = gnuHash(*h); !e.empty()) return e;
  return {};
}

// DT_HASH: nbucket, nchain, buckets[nbucket], chains[nchain]; every entry a symbol index.
std::string ImageChecker::sysvHash(uint64_t vaddr) {
  uint64_t off = 0;
  if (std::string e = table("the hash table (DT_HASH)", vaddr, 8, off); !e.empty()) return e;
  const uint64_t nbucket = at<uint32_t>(off), nchain = at<uint32_t>(off + 4);
  if (nbucket == 0) return "the hash table (DT_HASH) has no buckets";
  if (std::string e = table("the hash table (DT_HASH)", vaddr, 8 + 4 * (nbucket + nchain), off); !e.empty()) return e;
  if (nchain > symBound_)
    return "the hash table (DT_HASH) counts " + num(nchain) + " symbols but the symbol table holds at most " +
           num(symBound_);
  for (uint64_t k = 0; k < nbucket + nchain; ++k)
    if (at<uint32_t>(off + 8 + 4 * k) >= nchain)
      return "the hash table (DT_HASH) names symbol " + num(at<uint32_t>(off + 8 + 4 * k)) + " of " + num(nchain);
  symCount_ = std::max(symCount_, nchain);
  return {};
}

// DT_GNU_HASH: nbuckets, symoffset, bloom words, bloom shift, bloom[],
// buckets[], then one chain word per symbol from symoffset on; a chain ends
// at a word with bit 0 set. The loader asserts that the bloom size is a power
// of two and divides by nbuckets.
std::string ImageChecker::gnuHash(uint64_t vaddr) {
  const std::string what = "the GNU hash table (DT_GNU_HASH)";
  uint64_t off = 0;
  if (std::string e = table(what, vaddr, 16, off); !e.empty()) return e;
  const uint64_t nbuckets = at<uint32_t>(off), symoffset = at<uint32_t>(off + 4), bloom = at<uint32_t>(off + 8);
  if (nbuckets == 0) return what + " has no buckets";
  if (!powerOfTwo(bloom)) return what + ": its bloom filter size " + num(bloom) + " is not a power of two";
  const uint64_t head = 16 + kWord * bloom + 4 * nbuckets;  // < 2^37: no overflow
  if (std::string e = table(what, vaddr, head, off); !e.empty()) return e;
  if (symoffset > symBound_)
    return what + " starts at symbol " + num(symoffset) + " but the symbol table holds at most " + num(symBound_);
  uint64_t maxBucket = 0;
  for (uint64_t k = 0; k < nbuckets; ++k) {
    const uint64_t b = at<uint32_t>(off + 16 + kWord * bloom + 4 * k);
    if (b != 0 && b < symoffset)
      return what + ": bucket " + num(k) + " names symbol " + num(b) + ", below its first symbol " + num(symoffset);
    maxBucket = std::max(maxBucket, b);
  }
  uint64_t count = symoffset;
  if (maxBucket != 0) {
    // The chains are consecutive: the one the highest bucket starts reaches furthest.
    const uint64_t chains = vaddr + head, words = fileBytesFrom(chains) / 4;
    const uint64_t chainsOff = words ? *fileOffset(chains, 0) : 0;
    uint64_t k = maxBucket - symoffset;
    while (k < words && !(at<uint32_t>(chainsOff + 4 * k) & 1)) ++k;
    if (k >= words) return what + ": the chain of symbol " + num(maxBucket) + " runs past the end of its segment";
    count = symoffset + k + 1;
  }
  if (count > symBound_)
    return what + " reaches symbol " + num(count - 1) + " but the symbol table holds at most " + num(symBound_);
  symCount_ = std::max(symCount_, count);
  return {};
}

std::string ImageChecker::versions() {
  if (auto v = dyn(DT_VERNEED))
    if (std::string e = versionNeeds(*v); !e.empty()) return e;
  if (auto v = dyn(DT_VERDEF))
    if (std::string e = versionDefs(*v); !e.empty()) return e;
  const auto versym = dyn(DT_VERSYM);
  if (!versym || versionHigh_ == 0) return {};  // the loader ignores DT_VERSYM without versions
  uint64_t off = 0;
  if (std::string e = table("the symbol versions (DT_VERSYM)", *versym, 2 * symCount_, off); !e.empty()) return e;
  for (uint64_t k = 0; k < symCount_; ++k)
    if (const unsigned ndx = at<uint16_t>(off + 2 * k) & 0x7fff; ndx > versionHigh_)
      return "symbol " + num(k) + " has version index " + num(ndx) + " but only " + num(versionHigh_) + " are defined";
  return {};
}

// The loader follows vn_next/vna_next (and vd_next) until 0, and looks each
// needed file up among the libraries loaded for DT_NEEDED (asserting it is
// there). Steps are capped so that a loop of links cannot run forever.
std::string ImageChecker::versionNeeds(uint64_t vaddr) {
  const std::string what = "the version needs (DT_VERNEED)";
  uint64_t steps = n_ / sizeof(Elf64_Vernaux) + 1, off = 0;
  std::unordered_set<std::string_view> needed;
  for (const auto& [tag, value] : dynEntries_)
    if (tag == DT_NEEDED) needed.insert(str(value));  // inside the table: checked in tables()
  for (uint64_t ent = vaddr;;) {
    if (std::string e = table(what, ent, sizeof(Elf64_Verneed), off); !e.empty()) return e;
    const auto vn = at<Elf64_Verneed>(off);  // the same layout in both classes
    if (std::string e = stringAt(what, vn.vn_file); !e.empty()) return e;
    if (!needed.count(str(vn.vn_file)))
      return what + " name '" + str(vn.vn_file) + "', which is not among the libraries it needs (DT_NEEDED)";
    for (uint64_t aux = ent + vn.vn_aux;;) {
      if (--steps == 0) return what + ": the chain of entries loops or is too long";
      if (std::string e = table(what, aux, sizeof(Elf64_Vernaux), off); !e.empty()) return e;
      const auto va = at<Elf64_Vernaux>(off);
      if (std::string e = stringAt(what, va.vna_name); !e.empty()) return e;
      versionHigh_ = std::max<unsigned>(versionHigh_, va.vna_other & 0x7fff);
      if (va.vna_next == 0) break;
      aux += va.vna_next;
    }
    if (vn.vn_next == 0) return {};
    ent += vn.vn_next;
  }
}

std::string ImageChecker::versionDefs(uint64_t vaddr) {
  const std::string what = "the version definitions (DT_VERDEF)";
  uint64_t steps = n_ / sizeof(Elf64_Verdaux) + 1, off = 0;
  for (uint64_t ent = vaddr;;) {
    if (--steps == 0) return what + ": the chain of entries loops or is too long";
    if (std::string e = table(what, ent, sizeof(Elf64_Verdef), off); !e.empty()) return e;
    const auto vd = at<Elf64_Verdef>(off);
    if (std::string e = table(what, ent + vd.vd_aux, sizeof(Elf64_Verdaux), off); !e.empty()) return e;
    if (std::string e = stringAt(what, at<Elf64_Verdaux>(off).vda_name); !e.empty()) return e;
    versionHigh_ = std::max<unsigned>(versionHigh_, vd.vd_ndx & 0x7fff);
    if (vd.vd_next == 0) return {};
    ent += vd.vd_next;
  }
}

// Symbols the hash tables reach: names inside the string table, defined
// functions inside executable segments (dlsym returns them and rgraph calls
// its entry points), defined objects inside loaded segments.
std::string ImageChecker::symbols() {
  for (uint64_t k = 1; k < symCount_; ++k) {
    const Sym s = at<Sym>(symtabOff_ + k * sizeof(Sym));
    const std::string what = "symbol " + num(k);
    if (std::string e = stringAt(what, s.st_name); !e.empty()) return e;
    if (s.st_shndx == SHN_UNDEF || s.st_shndx >= SHN_LORESERVE) continue;
    const uint64_t type = symType(s.st_info);
    if (type == STT_FUNC || type == STT_GNU_IFUNC) {
      const Load* l = loadFor(s.st_value, 1);
      if (!l || !(l->flags & PF_X))
        return what + " ('" + str(s.st_name) + "'), a function at " + hex(s.st_value) +
               ", is not inside an executable segment";
    } else if (type == STT_OBJECT && s.st_size > 0 && !loadFor(s.st_value, s.st_size)) {
      return what + " ('" + str(s.st_name) + "') at " + hex(s.st_value) + " (" + num(s.st_size) +
             " bytes) is not inside a loaded segment";
    }
  }
  return {};
}

std::string ImageChecker::relocations() {
  struct Tab {
    int64_t tag, sizeTag;
    const char* name;
    bool rela;
  };
  const bool pltRela = dyn(DT_PLTREL).value_or(DT_RELA) == DT_RELA;
  for (const Tab& t : {Tab{DT_RELA, DT_RELASZ, "DT_RELA", true}, Tab{DT_REL, DT_RELSZ, "DT_REL", false},
                       Tab{DT_JMPREL, DT_PLTRELSZ, "DT_JMPREL", pltRela}}) {
    const auto addr = dyn(t.tag), size = dyn(t.sizeTag);
    if (!addr) continue;
    if (!size) return std::string(t.name) + " without its size";
    if (t.tag == DT_JMPREL && !dyn(DT_PLTREL)) return "DT_JMPREL without DT_PLTREL";
    if (std::string e = relocationTable(t.name, *addr, *size, t.rela); !e.empty()) return e;
  }
  if (auto addr = dyn(DT_RELR)) {
    const auto size = dyn(DT_RELRSZ);
    if (!size) return "DT_RELR without its size (DT_RELRSZ)";
    return relrTable(*addr, *size);
  }
  return {};
}

// A relocation writes one word at its target: inside a writable segment
// (unless the object declares text relocations).
std::string ImageChecker::relocationTarget(const std::string& what, uint64_t vaddr) const {
  const Load* l = loadFor(vaddr, kWord);
  if (!l) return what + " writes to " + hex(vaddr) + ", outside every loaded segment";
  if (!(l->flags & PF_W) && !textrel_)
    return what + " writes to " + hex(vaddr) + ", inside read-only " + segmentName(l->index, PT_LOAD);
  return {};
}

std::string ImageChecker::relocationTable(const char* name, uint64_t vaddr, uint64_t size, bool rela) {
  const uint64_t ent = rela ? sizeof(Rela) : sizeof(Rel);
  if (size % ent != 0)
    return std::string(name) + ": size " + num(size) + " is not a multiple of its entry size " + num(ent);
  uint64_t off = 0;
  if (std::string e = table(std::string("the relocations (") + name + ")", vaddr, size, off); !e.empty()) return e;
  const auto versym = dyn(DT_VERSYM);
  for (uint64_t k = 0; k < size / ent; ++k) {
    const uint64_t at0 = off + k * ent;
    const uint64_t where = rela ? uint64_t(at<Rela>(at0).r_offset) : uint64_t(at<Rel>(at0).r_offset);
    const uint64_t info = rela ? uint64_t(at<Rela>(at0).r_info) : uint64_t(at<Rel>(at0).r_info);
    if (relType(info) == 0) continue;  // R_*_NONE: nothing is written
    const std::string what = std::string("relocation ") + num(k) + " of " + name;
    if (std::string e = relocationTarget(what, where); !e.empty()) return e;
    const uint64_t sym = relSym(info);
    if (sym == 0) continue;
    if (sym >= symBound_)
      return what + " names symbol " + num(sym) + " but the symbol table holds at most " + num(symBound_);
    if (std::string e = stringAt(what + " (symbol " + num(sym) + ")", at<Sym>(symtabOff_ + sym * sizeof(Sym)).st_name);
        !e.empty())
      return e;
    if (!versym) continue;
    // The loader indexes its version table with versym[sym] for every relocation with a symbol.
    uint64_t voff = 0;
    if (std::string e = table("the symbol versions (DT_VERSYM)", *versym + 2 * sym, 2, voff); !e.empty()) return e;
    if (const unsigned ndx = at<uint16_t>(voff) & 0x7fff; ndx > versionHigh_)
      return what + ": symbol " + num(sym) + " has version index " + num(ndx) + " but only " + num(versionHigh_) +
             " are defined";
  }
  return {};
}

// RELR: an even word is an address (relocate it, then the words after it);
// an odd word is a bitmap of the next (word bits - 1) words.
std::string ImageChecker::relrTable(uint64_t vaddr, uint64_t size) {
  if (size % kWord != 0) return "DT_RELR: size " + num(size) + " is not a multiple of " + num(kWord);
  uint64_t off = 0;
  if (std::string e = table("the relocations (DT_RELR)", vaddr, size, off); !e.empty()) return e;
  std::optional<uint64_t> where;
  for (uint64_t k = 0; k < size / kWord; ++k) {
    const uint64_t entry = kWord == 8 ? at<uint64_t>(off + k * kWord) : at<uint32_t>(off + k * kWord);
    const std::string what = "relocation word " + num(k) + " of DT_RELR";
    if ((entry & 1) == 0) {
      if (std::string e = relocationTarget(what, entry); !e.empty()) return e;
      where = entry + kWord;
      continue;
    }
    if (!where) return what + " is a bitmap with no address before it";
    for (uint64_t bit = 1; bit < kWord * 8; ++bit)
      if ((entry >> bit) & 1)
        if (std::string e = relocationTarget(what, *where + (bit - 1) * kWord); !e.empty()) return e;
    *where += (kWord * 8 - 1) * kWord;
  }
  return {};
}

}  // namespace rgraph::plugin_image
