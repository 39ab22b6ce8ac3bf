// The check of plugin files before dlopen (rgraph/plugin_file_check.h): real
// plugins pass; truncated copies, non-ELF files, other classes, byte orders
// and machines, and headers whose offsets point outside the file (or
// overflow) are refused with a message saying what is wrong.
#include "rgraph/plugin_file_check.h"

#include <gtest/gtest.h>
#include <link.h>  // ElfW: the host's ELF class

#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

using namespace rgraph;

namespace {

const std::string kPlugins = RGRAPH_PLUGIN_OUTPUT_DIR;
const std::string kFixtures = RGRAPH_PLUGIN_FIXTURE_DIR;

using Bytes = std::vector<unsigned char>;

Bytes readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The shipped bloom plugin, read once; every crafted case starts from it.
const Bytes& bloom() {
  static const Bytes bytes = readFile(kPlugins + "/librgraph_bloom.so");
  return bytes;
}

std::string check(const Bytes& b) { return checkPluginImage(b.data(), b.size()); }

template <class T>
T get(const Bytes& b, size_t off) {
  T v;
  std::memcpy(&v, b.data() + off, sizeof v);
  return v;
}
template <class T>
void put(Bytes& b, size_t off, const T& v) {
  std::memcpy(b.data() + off, &v, sizeof v);
}

ElfW(Ehdr) ehdr(const Bytes& b) { return get<ElfW(Ehdr)>(b, 0); }
size_t phdrOffset(const Bytes& b, size_t i) { return ehdr(b).e_phoff + i * sizeof(ElfW(Phdr)); }

// Index of the n-th program header of a type (n = 0: the first; -1: the last).
size_t findSegment(const Bytes& b, uint32_t type, int n = 0) {
  std::vector<size_t> found;
  for (size_t i = 0; i < ehdr(b).e_phnum; ++i)
    if (get<ElfW(Phdr)>(b, phdrOffset(b, i)).p_type == type) found.push_back(i);
  EXPECT_FALSE(found.empty()) << "no segment of type " << type;
  if (found.empty()) return 0;
  return n < 0 ? found.back() : found.at(size_t(n));
}

// File offset of the dynamic entry with this tag (0 when absent).
size_t findDynamic(const Bytes& b, int64_t tag) {
  const auto dyn = get<ElfW(Phdr)>(b, phdrOffset(b, findSegment(b, PT_DYNAMIC)));
  for (size_t off = dyn.p_offset; off + sizeof(ElfW(Dyn)) <= dyn.p_offset + dyn.p_filesz; off += sizeof(ElfW(Dyn))) {
    const auto e = get<ElfW(Dyn)>(b, off);
    if (e.d_tag == tag) return off;
    if (e.d_tag == DT_NULL) break;
  }
  return 0;
}

// File offset of an address in the image (through its PT_LOAD).
size_t fileOffsetOf(const Bytes& b, uint64_t vaddr) {
  for (size_t i = 0; i < ehdr(b).e_phnum; ++i) {
    const auto p = get<ElfW(Phdr)>(b, phdrOffset(b, i));
    if (p.p_type == PT_LOAD && vaddr >= p.p_vaddr && vaddr < p.p_vaddr + p.p_filesz)
      return p.p_offset + (vaddr - p.p_vaddr);
  }
  ADD_FAILURE() << "address " << vaddr << " not in the file";
  return 0;
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(PluginFileCheck, ShippedPluginsAndTestPluginsAreAccepted) {
  for (const std::string& path :
       {kPlugins + "/librgraph_bloom.so", kPlugins + "/librgraph_ssao.so", kFixtures + "/librgraph_fixture_good.so",
        kFixtures + "/librgraph_fixture_wrong_abi.so"}) {
    const Bytes b = readFile(path);
    ASSERT_GT(b.size(), 4096u) << path;
    EXPECT_EQ(check(b), "") << path;
    EXPECT_EQ(checkPluginFile(path), "") << path;
  }
}

// Any cut of the file is refused: inside a segment it is the segment that
// ends past the file; after the segments, the section header table.
TEST(PluginFileCheck, EveryTruncationOfAShippedPluginIsRefused) {
  for (const std::string name : {"bloom", "ssao"}) {
    const Bytes full = readFile(kPlugins + "/librgraph_" + name + ".so");
    ASSERT_GT(full.size(), 65536u) << name;
    size_t checked = 0;
    for (size_t cut = 0; cut < full.size(); cut += cut < 70000 ? 61 : 4099, ++checked) {
      const std::string why = checkPluginImage(full.data(), cut);
      ASSERT_FALSE(why.empty()) << name << " cut at " << cut;
      if (cut > 0) {
        EXPECT_TRUE(has(why, "(truncated?)")) << name << " cut at " << cut << ": " << why;
      }
    }
    EXPECT_GT(checked, 1000u);
    EXPECT_FALSE(checkPluginImage(full.data(), full.size() - 1).empty()) << name;
  }
}

TEST(PluginFileCheck, CutsAt4kTo64kNameTheSegmentAndTheFileSize) {
  for (size_t cut : {4096u, 32768u, 65536u}) {
    const std::string why = checkPluginImage(bloom().data(), cut);
    EXPECT_TRUE(has(why, "(PT_LOAD) ends at byte ")) << cut << ": " << why;
    EXPECT_TRUE(has(why, "but the file has " + std::to_string(cut) + " bytes (truncated?)")) << why;
  }
}

TEST(PluginFileCheck, EmptyTextAndShortFiles) {
  EXPECT_EQ(check({}), "the file is empty (0 bytes)");
  EXPECT_EQ(checkPluginImage(nullptr, 0), "the file is empty (0 bytes)");
  const std::string text = "this is not a library\n";
  EXPECT_EQ(checkPluginImage(reinterpret_cast<const unsigned char*>(text.data()), text.size()),
            "not an ELF shared library: it starts with \"this is not a li...\", not the ELF magic \\x7fELF");
  const Bytes zip = {'P', 'K', 3, 4, 20, 0};
  EXPECT_EQ(check(zip),
            "not an ELF shared library: it starts with bytes 50 4b 03 04 14 00, not the ELF magic \\x7fELF");
  EXPECT_TRUE(has(checkPluginImage(bloom().data(), 3), "(truncated?)"));
  EXPECT_TRUE(has(checkPluginImage(bloom().data(), 10),
                  "the ELF identification (16 bytes) ends at byte 16 but the file has 10 bytes"));
  EXPECT_TRUE(has(checkPluginImage(bloom().data(), 40), "the ELF header"));
}

TEST(PluginFileCheck, WrongMachineNamesBoth) {
  Bytes b = bloom();
  const uint16_t host = ehdr(b).e_machine;
  const uint16_t other = host == EM_X86_64 ? EM_AARCH64 : EM_X86_64;
  put<uint16_t>(b, offsetof(ElfW(Ehdr), e_machine), other);
  const std::string why = check(b);
  EXPECT_TRUE(has(why, "built for " + std::string(other == EM_AARCH64 ? "AArch64" : "x86-64"))) << why;
  EXPECT_TRUE(has(why, "(e_machine " + std::to_string(other) + "), but this rgraph runs on ")) << why;
  EXPECT_TRUE(has(why, "(e_machine " + std::to_string(host) + ")")) << why;
}

TEST(PluginFileCheck, OtherClassByteOrderTypeAndVersion) {
  auto with = [](size_t off, unsigned char v) {
    Bytes b = bloom();
    b[off] = v;
    return check(b);
  };
  const bool host64 = sizeof(void*) == 8;
  EXPECT_EQ(with(EI_CLASS, host64 ? ELFCLASS32 : ELFCLASS64), std::string("a ") + (host64 ? "32-bit" : "64-bit") +
                                                                  " ELF file, but this rgraph is " +
                                                                  (host64 ? "64-bit" : "32-bit"));
  EXPECT_TRUE(has(with(EI_CLASS, 7), "unknown ELF class 7"));
  const bool little = ehdr(bloom()).e_ident[EI_DATA] == ELFDATA2LSB;
  EXPECT_EQ(with(EI_DATA, little ? ELFDATA2MSB : ELFDATA2LSB),
            little ? "a big-endian ELF file, but this machine is little-endian"
                   : "a little-endian ELF file, but this machine is big-endian");
  EXPECT_TRUE(has(with(EI_VERSION, 2), "unknown ELF version 2"));

  Bytes b = bloom();
  put<uint16_t>(b, offsetof(ElfW(Ehdr), e_type), ET_EXEC);
  EXPECT_TRUE(has(check(b), "an executable (ET_EXEC), not a shared library")) << check(b);
  put<uint16_t>(b, offsetof(ElfW(Ehdr), e_type), ET_REL);
  EXPECT_TRUE(has(check(b), "an object file (ET_REL, a .o)")) << check(b);
}

TEST(PluginFileCheck, ProgramHeaderTablePastTheEndOrOverflowing) {
  Bytes b = bloom();
  put<ElfW(Off)>(b, offsetof(ElfW(Ehdr), e_phoff), ElfW(Off)(b.size() - 10));
  EXPECT_TRUE(has(check(b), "the program header table (")) << check(b);
  EXPECT_TRUE(has(check(b), "(truncated?)")) << check(b);
  put<ElfW(Off)>(b, offsetof(ElfW(Ehdr), e_phoff), ~ElfW(Off)(0) - 8);
  EXPECT_TRUE(has(check(b), "the program header table (")) << check(b);

  b = bloom();
  put<uint16_t>(b, offsetof(ElfW(Ehdr), e_phentsize), 12);
  EXPECT_TRUE(has(check(b), "program header entries are 12 bytes")) << check(b);
  b = bloom();
  put<uint16_t>(b, offsetof(ElfW(Ehdr), e_phnum), 0);
  EXPECT_TRUE(has(check(b), "no program headers")) << check(b);
}

TEST(PluginFileCheck, LoadSegmentPastTheEndOrOverflowing) {
  const size_t last = findSegment(bloom(), PT_LOAD, -1), ph = phdrOffset(bloom(), last);
  const size_t filesz = ph + offsetof(ElfW(Phdr), p_filesz), offset = ph + offsetof(ElfW(Phdr), p_offset);
  const std::string name = "segment " + std::to_string(last) + " (PT_LOAD)";

  Bytes b = bloom();
  put<ElfW(Xword)>(b, filesz, ElfW(Xword)(b.size()));
  EXPECT_TRUE(has(check(b), name + " ends at byte ")) << check(b);

  b = bloom();  // offset + size wraps around: must not pass as "inside"
  put<ElfW(Off)>(b, offset, ~ElfW(Off)(0) - 15);
  put<ElfW(Xword)>(b, filesz, 32);
  EXPECT_EQ(check(b),
            name + " ends past byte 2^64 but the file has " + std::to_string(b.size()) + " bytes (truncated?)");

  b = bloom();  // address + memory size wraps around
  put<ElfW(Addr)>(b, ph + offsetof(ElfW(Phdr), p_vaddr), ~ElfW(Addr)(0) - 15);
  EXPECT_TRUE(has(check(b), name + ": address ")) << check(b);
  EXPECT_TRUE(has(check(b), "overflows")) << check(b);

  b = bloom();  // the loader maps segments relative to the first: order matters
  put<ElfW(Addr)>(b, ph + offsetof(ElfW(Phdr), p_vaddr), 0);
  EXPECT_TRUE(has(check(b), "must be in ascending order")) << check(b);

  b = bloom();
  put<ElfW(Xword)>(b, ph + offsetof(ElfW(Phdr), p_memsz), 0);
  EXPECT_TRUE(has(check(b), "is larger than its memory size 0")) << check(b);
}

TEST(PluginFileCheck, DynamicSegmentOutsideTheImage) {
  const size_t ph = phdrOffset(bloom(), findSegment(bloom(), PT_DYNAMIC));
  Bytes b = bloom();
  put<ElfW(Off)>(b, ph + offsetof(ElfW(Phdr), p_offset), ElfW(Off)(b.size() - 16));
  EXPECT_TRUE(has(check(b), "(PT_DYNAMIC) ends at byte")) << check(b);
  b = bloom();
  put<ElfW(Addr)>(b, ph + offsetof(ElfW(Phdr), p_vaddr), ElfW(Addr)(1) << 40);
  EXPECT_TRUE(has(check(b), "(PT_DYNAMIC) at address 0x10000000000")) << check(b);
  b = bloom();
  put<uint32_t>(b, ph + offsetof(ElfW(Phdr), p_type), PT_NULL);
  EXPECT_EQ(check(b), "no PT_DYNAMIC segment: not a shared library");
}

TEST(PluginFileCheck, DynamicSectionPointingOutside) {
  // No DT_NULL: the loader would read on past the section.
  Bytes b = bloom();
  const auto dyn = get<ElfW(Phdr)>(b, phdrOffset(b, findSegment(b, PT_DYNAMIC)));
  for (size_t off = dyn.p_offset; off + sizeof(ElfW(Dyn)) <= dyn.p_offset + dyn.p_filesz; off += sizeof(ElfW(Dyn)))
    put<ElfW(Sxword)>(b, off, DT_DEBUG);
  EXPECT_TRUE(has(check(b), "has no DT_NULL terminator")) << check(b);

  auto withDynamic = [](int64_t tag, uint64_t value) {
    Bytes c = bloom();
    const size_t off = findDynamic(c, tag);
    EXPECT_NE(off, 0u) << "tag " << tag;
    put<ElfW(Xword)>(c, off + offsetof(ElfW(Dyn), d_un), ElfW(Xword)(value));
    return check(c);
  };
  EXPECT_TRUE(has(withDynamic(DT_STRTAB, uint64_t(1) << 40), "the string table (DT_STRTAB) at address"))
      << withDynamic(DT_STRTAB, 1ull << 40);
  EXPECT_TRUE(has(withDynamic(DT_STRSZ, uint64_t(1) << 40), "the string table (DT_STRTAB)"));
  EXPECT_TRUE(has(withDynamic(DT_NEEDED, uint64_t(1) << 30), "DT_NEEDED names string 1073741824"));
  EXPECT_TRUE(has(withDynamic(DT_RELA, uint64_t(1) << 40), "the relocations (DT_RELA)"));
  EXPECT_TRUE(has(withDynamic(DT_RELAENT, 16), "DT_RELAENT is 16, expected 24"));
  EXPECT_TRUE(has(withDynamic(DT_INIT_ARRAYSZ, uint64_t(1) << 40), "DT_INIT_ARRAY at address"));
  EXPECT_TRUE(has(withDynamic(DT_PLTREL, 3), "DT_PLTREL is 3"));
}

TEST(PluginFileCheck, HashTablesTheLoaderWouldDivideByOrAssertOn) {
  Bytes b = bloom();
  const size_t off = fileOffsetOf(b, get<ElfW(Dyn)>(b, findDynamic(b, DT_GNU_HASH)).d_un.d_ptr);
  Bytes c = b;
  put<uint32_t>(c, off, 0);  // nbuckets: the loader takes hash % nbuckets
  EXPECT_EQ(check(c), "the GNU hash table (DT_GNU_HASH) has no buckets");
  c = b;
  put<uint32_t>(c, off + 8, 3);  // bloom words: the loader asserts a power of two
  EXPECT_EQ(check(c), "the GNU hash table (DT_GNU_HASH): its bloom filter size 3 is not a power of two");
  c = b;
  put<uint32_t>(c, off + 4, 1u << 30);  // first hashed symbol beyond the symbol table
  EXPECT_TRUE(has(check(c), "starts at symbol 1073741824")) << check(c);
}

TEST(PluginFileCheck, RelocationWritingOutsideTheImage) {
  Bytes b = bloom();
  const auto rela = get<ElfW(Dyn)>(b, findDynamic(b, DT_RELA)).d_un.d_ptr;
  const size_t off = fileOffsetOf(b, rela);
  put<ElfW(Addr)>(b, off + offsetof(ElfW(Rela), r_offset), ElfW(Addr)(1) << 40);
  EXPECT_EQ(check(b), "relocation 0 of DT_RELA writes to 0x10000000000, outside every loaded segment");
  // Into the read-only first segment (the ELF header).
  put<ElfW(Addr)>(b, off + offsetof(ElfW(Rela), r_offset), 0);
  EXPECT_TRUE(has(check(b), "relocation 0 of DT_RELA writes to 0x0, inside read-only segment 0 (PT_LOAD)")) << check(b);
}

TEST(PluginFileCheck, CheckPluginFileReportsUnreadableFiles) {
  EXPECT_TRUE(has(checkPluginFile("/no/such/dir/librgraph_x.so"), "cannot open the file: No such file or directory"));
  EXPECT_TRUE(has(checkPluginFile("/"), "cannot read the file: Is a directory")) << checkPluginFile("/");
  EXPECT_EQ(checkPluginFile(std::string("/tmp/a\0b", 8)), "the path contains a NUL byte");
}
