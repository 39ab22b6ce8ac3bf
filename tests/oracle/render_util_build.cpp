// The image tests' helpers (tests/render/render_util.cpp: pipeline loading,
// rendering with an inspect hook, rays through pixel centres), built into this
// program too: one source, compiled here because suites are globbed per folder.
#include "render/render_util.cpp"  // NOLINT(bugprone-suspicious-include)
