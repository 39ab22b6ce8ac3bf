// Plugin files checked before the dynamic loader sees them (GL-free).
//
// dlopen maps a shared library's PT_LOAD segments straight from the file and
// then reads its dynamic section, relocations and hash tables through those
// mappings. A file cut short inside a segment (an interrupted copy) makes
// those reads touch pages past the end of the file, and the process dies
// with SIGBUS inside dlopen, before any error can be reported. PluginLoader
// therefore checks the bytes first and refuses a damaged file with a message.
//
// What is checked, in order (the first problem found is reported):
//   - ELF magic, class (32/64-bit) and data encoding (byte order) of the host,
//     e_type ET_DYN, e_machine of the host (from the compiler's target);
//   - the program header table: entry size, count, inside the file;
//   - every PT_LOAD segment: its file range inside the file, file size <=
//     memory size, no address overflow, ascending addresses (the loader maps
//     them relative to the first one);
//   - PT_DYNAMIC inside the file and inside a loaded segment, with a DT_NULL
//     terminator; PT_TLS, PT_NOTE, PT_GNU_PROPERTY, PT_GNU_EH_FRAME and
//     PT_GNU_RELRO inside loaded segments;
//   - what the dynamic section points at: string, symbol and relocation
//     tables, hash tables, init/fini arrays and version tables inside loaded
//     segments, with their sizes; DT_NEEDED/SONAME/RPATH strings inside the
//     string table; every relocation's target inside a segment and its symbol
//     inside the symbol table; the version need/definition chains;
//   - the section header table inside the file (the linker writes it last,
//     so a cut anywhere in the file shows there even where no segment is hit).
//
// This catches damage (truncation, a text file, another architecture, a
// corrupted header), not malice: a plugin runs its own code when it loads.
#pragma once

#include <cstddef>
#include <string>

namespace rgraph {

// Empty string: the bytes look like a loadable shared object for this host.
// Otherwise: what is wrong, in words, e.g. "segment 2 (PT_LOAD) ends at byte
// 71234 but the file has 32768 bytes (truncated?)".
std::string checkPluginImage(const unsigned char* data, std::size_t size);

// Reads the file (no mmap, so a file that shrinks while read cannot fault)
// and checks it; the message names the problem (the caller names the file).
std::string checkPluginFile(const std::string& path);

}  // namespace rgraph
