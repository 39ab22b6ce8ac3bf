#include "gl_call_counter.h"

#if defined(__x86_64__) && defined(__ELF__) && defined(RGRAPH_GL_ENTRY_POINTS)
#define RGRAPH_GL_COUNTING 1
#endif

#ifdef RGRAPH_GL_COUNTING
#include <EGL/egl.h>
#include <dlfcn.h>

#include <cstdio>

// Per entry point: its counter, the function it forwards to, and the
// trampoline under the entry point's own name (arguments stay in their
// registers and on the stack: a jump, not a call). The trampoline goes into
// .text and the assembler is put back in the section it was in: the
// compiler does not know the asm switched, and would otherwise place the
// variables after it in .text (read-only: a crash at the first write, seen
// in the sanitizer build).
#define RGRAPH_GL_ENTRY(name)                                                                                      \
  extern "C" {                                                                                                     \
  __attribute__((used, visibility("hidden"))) uint64_t rgraph_count_##name = 0;                                     \
  __attribute__((used, visibility("hidden"))) void* rgraph_real_##name = nullptr;                                   \
  }                                                                                                                \
  asm(".pushsection .text\n.p2align 4\n.globl " #name "\n.type " #name ", @function\n" #name                       \
      ":\n  endbr64\n  addq $1, rgraph_count_" #name "(%rip)\n  jmp *rgraph_real_" #name "(%rip)\n.size " #name \
      ", . - " #name "\n.popsection\n");
#include "gl_entry_points.inc"
#undef RGRAPH_GL_ENTRY

namespace {
struct Entry {
  const char* name;
  void** real;
  const uint64_t* count;
};
const Entry kEntries[] = {
#define RGRAPH_GL_ENTRY(name) {#name, &rgraph_real_##name, &rgraph_count_##name},
#include "gl_entry_points.inc"
#undef RGRAPH_GL_ENTRY
};

// Before main(), so before any GL call.
__attribute__((constructor)) void resolveEntryPoints() {
  for (const Entry& e : kEntries) {
    *e.real = dlsym(RTLD_NEXT, e.name);
    if (!*e.real) *e.real = reinterpret_cast<void*>(eglGetProcAddress(e.name));
    if (!*e.real) std::fprintf(stderr, "gl_call_counter: %s not found; calling it will crash\n", e.name);
  }
}
}  // namespace
#endif

namespace rgraph::bench {

#ifdef RGRAPH_GL_COUNTING
bool GlCallCounter::available() { return true; }
uint64_t GlCallCounter::total() {
  uint64_t n = 0;
  for (const Entry& e : kEntries) n += *e.count;
  return n;
}
std::vector<std::pair<std::string, uint64_t>> GlCallCounter::perFunction() {
  std::vector<std::pair<std::string, uint64_t>> out;
  for (const Entry& e : kEntries)
    if (*e.count) out.emplace_back(e.name, *e.count);
  return out;
}
#else
bool GlCallCounter::available() { return false; }
uint64_t GlCallCounter::total() { return 0; }
std::vector<std::pair<std::string, uint64_t>> GlCallCounter::perFunction() { return {}; }
#endif

}  // namespace rgraph::bench
