// What this test program's GL calls could wait for the GPU with: the GL
// entry points that block the CPU until earlier GPU work is done (glFinish,
// read-backs into client memory (not into a pixel pack buffer), buffer maps, fence waits) counted, and every
// timer query result read checked against what GL_QUERY_RESULT_AVAILABLE said
// about that query before. gl_wait_log.cpp defines those entry points in the
// program itself, exported (ENABLE_EXPORTS), so that librgraph's calls bind to
// them too; each records, then calls libOpenGL's own (dlsym RTLD_NEXT), the
// way bench/gl_call_counter.h counts calls. Only in this program.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace rgraph::stalltest {

struct GlWaits {
  // Blocking calls made, per entry point (those made at least once).
  std::map<std::string, uint64_t> blocking;
  // One line per query result read (GL_QUERY_RESULT) of a query whose
  // GL_QUERY_RESULT_AVAILABLE was not seen true since it was last begun.
  std::vector<std::string> unavailableReads;
  uint64_t availabilityChecks = 0;  // GL_QUERY_RESULT_AVAILABLE asked
  uint64_t resultReads = 0;         // GL_QUERY_RESULT read (any of the four getters)
  uint64_t queriesBegun = 0;        // glBeginQuery(GL_TIME_ELAPSED, ...)
  // Read-backs (glReadPixels, glGetTextureSubImage, ...) into a bound pixel
  // pack buffer: copies the GPU makes later, not waits (not in `blocking`).
  uint64_t packBufferReads = 0;
};

// Starts recording afresh (what was recorded is forgotten; which queries were
// seen available is kept, so that a read after reset() is judged rightly).
void resetWaits();
GlWaits waits();

}  // namespace rgraph::stalltest
