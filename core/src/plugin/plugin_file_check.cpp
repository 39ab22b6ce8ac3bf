// Plugin files checked before dlopen (see rgraph/plugin_file_check.h for what
// and why). Every read is bounded by the buffer and every sum is overflow
// checked: the bytes are whatever was on disk (and what a fuzzer makes up).
// Work is linear in the size of the file.
// Here: the ELF header, the segments and the section header table, and
// the public functions; plugin_dynamic_check.cpp: the dynamic section's tables.
#include "rgraph/plugin_file_check.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "plugin_image_checker.h"

namespace rgraph {
namespace plugin_image {

std::string hex(uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%llx", static_cast<unsigned long long>(v));
  return buf;
}

std::string num(uint64_t v) { return std::to_string(v); }

bool powerOfTwo(uint64_t v) { return v != 0 && (v & (v - 1)) == 0; }

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

namespace {

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

}  // namespace

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

}  // namespace plugin_image

std::string checkPluginImage(const unsigned char* data, std::size_t size) {
  if (!data) size = 0;
  static const unsigned char none = 0;
  return plugin_image::ImageChecker(data ? data : &none, size).run();
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
    if (bytes.size() > plugin_image::kMaxFileBytes) return "the file is larger than 1 GiB: not read as a plugin";
    if (got < sizeof buf) break;
  }
  if (std::ferror(f.get())) return std::string("cannot read the file: ") + std::strerror(errno);
  return checkPluginImage(bytes.data(), bytes.size());
}

}  // namespace rgraph
