// The ELF image check behind rgraph/plugin_file_check.h, internal to it:
// the host's ELF types and the checker class whose steps two files define
// (plugin_file_check.cpp: the file header, segments and section headers, and
// the public functions; plugin_dynamic_check.cpp: what the dynamic section
// points at, i.e. string, symbol, hash and version tables and relocations).
#pragma once

#include <elf.h>
#include <link.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace rgraph::plugin_image {

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
#error "plugin_image_checker.h: add this architecture's ELF e_machine (<elf.h>) to the list"
#endif

std::string hex(uint64_t v);
std::string num(uint64_t v);
bool powerOfTwo(uint64_t v);

struct Load {
  size_t index;  // in the program header table (for messages)
  uint64_t offset, filesz, vaddr, memsz;
  uint32_t flags;
};

std::string segmentName(size_t i, uint32_t type);

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

}  // namespace rgraph::plugin_image
