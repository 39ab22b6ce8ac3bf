// Plugin files checked before dlopen (see rgraph/plugin_file_check.h for what
// and why). Every read is bounded by the buffer and every sum is overflow
// checked: the bytes are whatever was on disk (and what a fuzzer makes up).
// Work is linear in the size of the file.
#include "rgraph/plugin_file_check.h"

#include <elf.h>
#include <link.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace rgraph {
namespace {

// ---- the host, from the compiler's target (so an aarch64 build expects aarch64 plugins) ----
// ElfW (<link.h>): the ELF types of the host's class.
constexpr unsigned kHostClass = __ELF_NATIVE_CLASS == 64 ? ELFCLASS64 : ELFCLASS32;
using Ehdr = ElfW(Ehdr);
using Phdr = ElfW(Phdr);
using Dyn = ElfW(Dyn);
using Sym = ElfW(Sym);
using Rela = ElfW(Rela);
using Rel = ElfW(Rel);
// ELF{32,64}_R_SYM / _R_TYPE; ST_TYPE is the same in both classes.
constexpr uint64_t relSym(uint64_t info) { return kHostClass == ELFCLASS64 ? ELF64_R_SYM(info) : ELF32_R_SYM(info); }
constexpr uint64_t relType(uint64_t info) { return kHostClass == ELFCLASS64 ? ELF64_R_TYPE(info) : ELF32_R_TYPE(info); }
constexpr uint64_t symType(unsigned char info) { return ELF64_ST_TYPE(info); }
constexpr uint64_t kWord = sizeof(ElfW(Addr));  // an address in the image (GOT entry, RELR word, init_array entry)
static_assert(kWord == sizeof(void*), "the ELF class must match the pointer size");
constexpr unsigned kHostData = __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ ? ELFDATA2LSB : ELFDATA2MSB;

#if defined(__x86_64__)
constexpr unsigned kHostMachine = EM_X86_64;
#elif defined(__aarch64__)
constexpr unsigned kHostMachine = EM_AARCH64;
#elif defined(__i386__)
constexpr unsigned kHostMachine = EM_386;
#elif defined(__arm__)
constexpr unsigned kHostMachine = EM_ARM;
#elif defined(__riscv)
constexpr unsigned kHostMachine = EM_RISCV;
#elif defined(__powerpc64__)
constexpr unsigned kHostMachine = EM_PPC64;
#elif defined(__powerpc__)
constexpr unsigned kHostMachine = EM_PPC;
#elif defined(__s390__)
constexpr unsigned kHostMachine = EM_S390;
#elif defined(__loongarch__)
constexpr unsigned kHostMachine = 258;  // EM_LOONGARCH
#elif defined(__mips__)
constexpr unsigned kHostMachine = EM_MIPS;
#else
#error "plugin_file_check.cpp: add this architecture's ELF e_machine (<elf.h>) to the list"
#endif

// Largest file read into memory for the check; real plugins are far smaller.
constexpr uint64_t kMaxFileBytes = uint64_t(1) << 30;

std::string machineName(unsigned m) {
  // clang-format off
  static const std::pair<unsigned, const char*> kNames[] = {
      {EM_X86_64, "x86-64"}, {EM_AARCH64, "AArch64 (arm64)"}, {EM_386, "i386 (32-bit x86)"}, {EM_ARM, "32-bit ARM"},
      {EM_RISCV, "RISC-V"}, {EM_PPC64, "PowerPC64"}, {EM_PPC, "PowerPC"}, {EM_S390, "IBM S/390"}, {258, "LoongArch"},
      {EM_MIPS, "MIPS"}, {EM_SPARCV9, "SPARC v9"}, {EM_IA_64, "IA-64"}, {EM_NONE, "no machine"}};
  // clang-format on
  for (const auto& [id, name] : kNames)
    if (id == m) return name;
  return "machine " + std::to_string(m);
}

std::string hex(uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%llx", static_cast<unsigned long long>(v));
  return buf;
}

std::string num(uint64_t v) { return std::to_string(v); }

// The first bytes of a file that is not ELF, as text when they are text.
std::string preview(const unsigned char* d, uint64_t n) {
  const uint64_t len = std::min<uint64_t>(n, 16);
  bool text = true;
  for (uint64_t i = 0; i < len; ++i)
    text &= (d[i] >= 0x20 && d[i] < 0x7f) || d[i] == '\n' || d[i] == '\t' || d[i] == '\r';
  std::string out;
  if (text) {
    out = "\"";
    for (uint64_t i = 0; i < len; ++i)
      out += d[i] == '\n'   ? std::string("\\n")
             : d[i] == '\t' ? "\\t"
             : d[i] == '\r' ? "\\r"
                            : std::string(1, char(d[i]));
    return out + (n > len ? "...\"" : "\"");
  }
  out = "bytes";
  char b[4];
  for (uint64_t i = 0; i < len; ++i) {
    std::snprintf(b, sizeof b, " %02x", d[i]);
    out += b;
  }
  return out + (n > len ? " ..." : "");
}

bool powerOfTwo(uint64_t v) { return v != 0 && (v & (v - 1)) == 0; }

struct Load {
  size_t index;  // in the program header table (for messages)
  uint64_t offset, filesz, vaddr, memsz;
  uint32_t flags;
};

std::string segmentName(size_t i, uint32_t type) {
  // clang-format off
  static const std::pair<uint32_t, const char*> kTypes[] = {
      {PT_LOAD, "PT_LOAD"}, {PT_DYNAMIC, "PT_DYNAMIC"}, {PT_TLS, "PT_TLS"}, {PT_NOTE, "PT_NOTE"},
      {PT_GNU_PROPERTY, "PT_GNU_PROPERTY"}, {PT_GNU_EH_FRAME, "PT_GNU_EH_FRAME"}, {PT_GNU_RELRO, "PT_GNU_RELRO"},
      {PT_PHDR, "PT_PHDR"}};
  // clang-format on
  const char* name = "?";
  for (const auto& [t, n] : kTypes)
    if (t == type) name = n;
  return "segment " + num(i) + " (" + name + ")";
}

class ImageChecker {
 public:
  ImageChecker(const unsigned char* data, uint64_t size) : d_(data), n_(size) {}

  std::string run() {
    using Step = std::string (ImageChecker::*)();
    for (Step step : {&ImageChecker::header, &ImageChecker::segments, &ImageChecker::dynamicEntries,
                      &ImageChecker::tables, &ImageChecker::hashTables, &ImageChecker::versions, &ImageChecker::symbols,
                      &ImageChecker::relocations, &ImageChecker::sectionHeaders})
      if (std::string e = (this->*step)(); !e.empty()) return e;
    return {};
  }

 private:
  template <class T>
  T at(uint64_t off) const {  // callers have checked off + sizeof(T) <= n_
    T v;
    std::memcpy(&v, d_ + off, sizeof v);
    return v;
  }
  bool inFile(uint64_t off, uint64_t len) const { return off <= n_ && len <= n_ - off; }
  std::string pastEnd(const std::string& what, uint64_t off, uint64_t len) const {
    const std::string end = off > UINT64_MAX - len ? "past byte 2^64" : "at byte " + num(off + len);
    return what + " ends " + end + " but the file has " + num(n_) + " bytes (truncated?)";
  }

  // The loaded segment whose memory holds [vaddr, vaddr + len), or null.
  const Load* loadFor(uint64_t vaddr, uint64_t len) const {
    auto it =
        std::upper_bound(loads_.begin(), loads_.end(), vaddr, [](uint64_t v, const Load& l) { return v < l.vaddr; });
    if (it == loads_.begin()) return nullptr;
    const Load& l = *--it;
    const uint64_t rel = vaddr - l.vaddr;
    return rel <= l.memsz && len <= l.memsz - rel ? &l : nullptr;
  }
  // The file offset of [vaddr, vaddr + len) when a segment maps it from the file.
  std::optional<uint64_t> fileOffset(uint64_t vaddr, uint64_t len) const {
    const Load* l = loadFor(vaddr, 0);
    if (!l) return std::nullopt;
    const uint64_t rel = vaddr - l->vaddr;
    if (rel > l->filesz || len > l->filesz - rel) return std::nullopt;
    return l->offset + rel;
  }
  // How many bytes from vaddr to the end of its segment's file data.
  uint64_t fileBytesFrom(uint64_t vaddr) const {
    const Load* l = loadFor(vaddr, 0);
    if (!l || vaddr - l->vaddr > l->filesz) return 0;
    return l->filesz - (vaddr - l->vaddr);
  }
  std::optional<uint64_t> dyn(int64_t tag) const {
    auto it = dynLast_.find(tag);
    return it == dynLast_.end() ? std::nullopt : std::optional<uint64_t>(it->second);
  }
  // A table the dynamic section points at: its file offset in `off`, or what is wrong.
  std::string table(const std::string& what, uint64_t vaddr, uint64_t len, uint64_t& off) const {
    if (auto o = fileOffset(vaddr, len)) {
      off = *o;
      return {};
    }
    return what + " at address " + hex(vaddr) + " (" + num(len) +
           " bytes) is not inside the file data of a loaded segment";
  }
  std::string stringAt(const std::string& what, uint64_t strOffset) const {
    if (strOffset < strsz_) return {};
    return what + " names string " + num(strOffset) + " but the string table (DT_STRTAB) has " + num(strsz_) + " bytes";
  }
  const char* str(uint64_t strOffset) const {  // NUL-terminated: the table's last byte is NUL (checked)
    return reinterpret_cast<const char*>(d_ + strtabOff_ + strOffset);
  }

  std::string header();
  std::string segments();
  std::string otherSegment(size_t i, const Phdr& p);
  std::string notes(size_t i, const Phdr& p, uint64_t off);
  std::string dynamicEntries();
  std::string tables();
  std::string hashTables();
  std::string sysvHash(uint64_t vaddr);
  std::string gnuHash(uint64_t vaddr);
  std::string versions();
  std::string versionNeeds(uint64_t vaddr);
  std::string versionDefs(uint64_t vaddr);
  std::string symbols();
  std::string relocations();
  std::string relocationTable(const char* name, uint64_t vaddr, uint64_t size, bool rela);
  std::string relocationTarget(const std::string& what, uint64_t vaddr) const;
  std::string relrTable(uint64_t vaddr, uint64_t size);
  std::string sectionHeaders();

  const unsigned char* d_;
  uint64_t n_;
  Ehdr eh_{};
  std::vector<Phdr> ph_;
  std::vector<Load> loads_;        // ascending addresses (checked)
  std::optional<size_t> dynamic_;  // index of PT_DYNAMIC in ph_
  std::vector<std::pair<int64_t, uint64_t>> dynEntries_;
  std::unordered_map<int64_t, uint64_t> dynLast_;  // as the loader reads them: the last entry of a tag wins
  uint64_t strtabOff_ = 0, strsz_ = 0;
  uint64_t symtab_ = 0, symtabOff_ = 0;
  uint64_t symBound_ = 0;     // entries that fit between DT_SYMTAB and its segment's end
  uint64_t symCount_ = 0;     // entries the hash tables reach (0 without hash tables)
  unsigned versionHigh_ = 0;  // highest version index defined or needed
  bool textrel_ = false;
};

std::string ImageChecker::header() {
  if (n_ == 0) return "the file is empty (0 bytes)";
  if (n_ < SELFMAG && std::memcmp(d_, ELFMAG, n_) == 0)
    return pastEnd("the ELF identification (16 bytes)", 0, EI_NIDENT);
  if (n_ < SELFMAG || std::memcmp(d_, ELFMAG, SELFMAG) != 0)
    return "not an ELF shared library: it starts with " + preview(d_, n_) + ", not the ELF magic \\x7fELF";
  if (n_ < EI_NIDENT) return pastEnd("the ELF identification (16 bytes)", 0, EI_NIDENT);
  const unsigned cls = d_[EI_CLASS], data = d_[EI_DATA];
  const std::string hostBits = kHostClass == ELFCLASS64 ? "64-bit" : "32-bit";
  if (cls != kHostClass) {
    if (cls == ELFCLASS32 || cls == ELFCLASS64)
      return std::string("a ") + (cls == ELFCLASS32 ? "32-bit" : "64-bit") + " ELF file, but this rgraph is " +
             hostBits;
    return "unknown ELF class " + num(cls) + " (byte 4; expected " + num(kHostClass) + ", " + hostBits + ")";
  }
  if (data != kHostData) {
    const std::string host = kHostData == ELFDATA2LSB ? "little-endian" : "big-endian";
    if (data == ELFDATA2LSB || data == ELFDATA2MSB)
      return std::string("a ") + (data == ELFDATA2LSB ? "little-endian" : "big-endian") +
             " ELF file, but this machine is " + host;
    return "unknown ELF data encoding " + num(data) + " (byte 5; expected " + num(kHostData) + ", " + host + ")";
  }
  if (d_[EI_VERSION] != EV_CURRENT) return "unknown ELF version " + num(d_[EI_VERSION]) + " (byte 6; expected 1)";
  if (n_ < sizeof(Ehdr)) return pastEnd("the ELF header (" + num(sizeof(Ehdr)) + " bytes)", 0, sizeof(Ehdr));
  eh_ = at<Ehdr>(0);
  switch (eh_.e_type) {
    case ET_DYN:
      break;
    case ET_EXEC:
      return "an executable (ET_EXEC), not a shared library (build the plugin with -shared)";
    case ET_REL:
      return "an object file (ET_REL, a .o), not a shared library (link it with -shared)";
    case ET_CORE:
      return "a core dump (ET_CORE), not a shared library";
    default:
      return "ELF type " + num(eh_.e_type) + ", not a shared library (ET_DYN)";
  }
  if (eh_.e_machine != kHostMachine)
    return "built for " + machineName(eh_.e_machine) + " (e_machine " + num(eh_.e_machine) +
           "), but this rgraph runs on " + machineName(kHostMachine) + " (e_machine " + num(kHostMachine) + ")";
  if (eh_.e_version != EV_CURRENT) return "unknown ELF version " + num(eh_.e_version) + " in e_version (expected 1)";
  if (eh_.e_phentsize != sizeof(Phdr))
    return "program header entries are " + num(eh_.e_phentsize) + " bytes (e_phentsize), expected " + num(sizeof(Phdr));
  if (eh_.e_phoff == 0 || eh_.e_phnum == 0)
    return "no program headers (e_phoff " + num(eh_.e_phoff) + ", e_phnum " + num(eh_.e_phnum) + "): nothing to load";
  if (eh_.e_phnum == PN_XNUM) return "65535 or more program headers (e_phnum PN_XNUM): refused";
  const uint64_t len = uint64_t(eh_.e_phnum) * sizeof(Phdr);
  if (!inFile(eh_.e_phoff, len))
    return pastEnd("the program header table (" + num(eh_.e_phnum) + " entries at byte " + num(eh_.e_phoff) + ")",
                   eh_.e_phoff, len);
  ph_.resize(eh_.e_phnum);
  for (size_t i = 0; i < ph_.size(); ++i) ph_[i] = at<Phdr>(eh_.e_phoff + i * sizeof(Phdr));
  return {};
}

// PT_LOAD first: every other segment is checked against the loaded memory.
std::string ImageChecker::segments() {
  for (size_t i = 0; i < ph_.size(); ++i) {
    const Phdr& p = ph_[i];
    if (p.p_type != PT_LOAD) continue;
    const std::string what = segmentName(i, p.p_type);
    if (!inFile(p.p_offset, p.p_filesz)) return pastEnd(what, p.p_offset, p.p_filesz);
    if (p.p_filesz > p.p_memsz)
      return what + ": its file size " + num(p.p_filesz) + " is larger than its memory size " + num(p.p_memsz);
    if (p.p_vaddr > UINT64_MAX - p.p_memsz)
      return what + ": address " + hex(p.p_vaddr) + " + size " + hex(p.p_memsz) + " overflows";
    if (!loads_.empty() && p.p_vaddr < loads_.back().vaddr + loads_.back().memsz)
      return what + " at address " + hex(p.p_vaddr) + " overlaps or comes before segment " + num(loads_.back().index) +
             " (which ends at " + hex(loads_.back().vaddr + loads_.back().memsz) +
             "); loaded segments must be in ascending order";
    loads_.push_back({i, p.p_offset, p.p_filesz, p.p_vaddr, p.p_memsz, p.p_flags});
  }
  if (loads_.empty()) return "no PT_LOAD segment: nothing to load";
  for (size_t i = 0; i < ph_.size(); ++i)
    if (std::string e = otherSegment(i, ph_[i]); !e.empty()) return e;
  if (!dynamic_) return "no PT_DYNAMIC segment: not a shared library";
  return {};
}

std::string ImageChecker::otherSegment(size_t i, const Phdr& p) {
  // clang-format off
  switch (p.p_type) {
    case PT_DYNAMIC: case PT_TLS: case PT_NOTE: case PT_GNU_PROPERTY: case PT_GNU_EH_FRAME: case PT_GNU_RELRO:
    case PT_PHDR: break;
    default: return {};  // not read by the loader (PT_LOAD: checked above)
  }
  // clang-format on
  const std::string what = segmentName(i, p.p_type);
  if (p.p_filesz > 0 && !inFile(p.p_offset, p.p_filesz)) return pastEnd(what, p.p_offset, p.p_filesz);
  if (p.p_filesz > p.p_memsz)
    return what + ": its file size " + num(p.p_filesz) + " is larger than its memory size " + num(p.p_memsz);
  // The loader reads these through the mapped image: they must lie in one
  // loaded segment, the ones it reads bytes of in that segment's file data.
  const bool readsBytes = p.p_type == PT_DYNAMIC || p.p_type == PT_NOTE || p.p_type == PT_GNU_PROPERTY;
  const uint64_t len = p.p_type == PT_TLS ? p.p_filesz : p.p_memsz;  // TLS: the initial image
  std::optional<uint64_t> off = fileOffset(p.p_vaddr, len);
  if (readsBytes ? !off : !loadFor(p.p_vaddr, len))
    return what + " at address " + hex(p.p_vaddr) + " (" + num(len) + " bytes) is not inside " +
           (readsBytes ? "the file data of a loaded segment" : "a loaded segment");
  if (p.p_type == PT_TLS && p.p_align > 1 && !powerOfTwo(p.p_align))
    return what + ": alignment " + num(p.p_align) + " is not a power of two";
  if (p.p_type == PT_DYNAMIC) dynamic_ = i;
  if (p.p_type == PT_NOTE || p.p_type == PT_GNU_PROPERTY) return notes(i, p, *off);
  return {};
}

// Notes: a 12-byte header, the name, then the description and the next note,
// each starting at the segment's alignment (4, or 8 for 64-bit property
// notes). Every note must end inside the segment: the loader reads GNU
// property notes through the mapped image trusting their sizes.
std::string ImageChecker::notes(size_t i, const Phdr& p, uint64_t off) {
  const uint64_t align = p.p_align == 8 ? 8 : 4, size = p.p_memsz;
  auto up = [align](uint64_t v) { return (v + align - 1) & ~(align - 1); };
  uint64_t pos = 0;
  for (size_t k = 0; size >= sizeof(Elf64_Nhdr) && pos <= size - sizeof(Elf64_Nhdr); ++k) {
    const auto nh = at<Elf64_Nhdr>(off + pos);                // Elf32_Nhdr and Elf64_Nhdr are the same three words
    const uint64_t desc = up(pos + sizeof nh + nh.n_namesz);  // no overflow: each term < 2^33
    if (desc + nh.n_descsz > size)
      return segmentName(i, p.p_type) + ": note " + num(k) + " (name " + num(nh.n_namesz) + " bytes, description " +
             num(nh.n_descsz) + " bytes) runs past the segment's end";
    pos = up(desc + nh.n_descsz);
  }
  return {};
}

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

// The loader never reads section headers, but the linker writes them last:
// a file cut after its segments still shows here.
std::string ImageChecker::sectionHeaders() {
  if (eh_.e_shoff == 0) return {};
  const uint64_t len = uint64_t(std::max<unsigned>(eh_.e_shnum, 1)) * eh_.e_shentsize;
  if (!inFile(eh_.e_shoff, len))
    return pastEnd("the section header table (" + num(eh_.e_shnum) + " entries at byte " + num(eh_.e_shoff) + ")",
                   eh_.e_shoff, len);
  return {};
}

}  // namespace

std::string checkPluginImage(const unsigned char* data, std::size_t size) {
  if (!data) size = 0;
  static const unsigned char none = 0;
  return ImageChecker(data ? data : &none, size).run();
}

std::string checkPluginFile(const std::string& path) {
  if (path.find('\0') != std::string::npos) return "the path contains a NUL byte";
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) return std::string("cannot open the file: ") + std::strerror(errno);
  std::vector<unsigned char> bytes;
  unsigned char buf[1 << 16];
  for (;;) {
    const size_t got = std::fread(buf, 1, sizeof buf, f.get());
    bytes.insert(bytes.end(), buf, buf + got);
    if (bytes.size() > kMaxFileBytes) return "the file is larger than 1 GiB: not read as a plugin";
    if (got < sizeof buf) break;
  }
  if (std::ferror(f.get())) return std::string("cannot read the file: ") + std::strerror(errno);
  return checkPluginImage(bytes.data(), bytes.size());
}

}  // namespace rgraph
