// Shared by the GL test programs (gl, render, stability): one headless
// context per program and pipeline loading that fails loudly.
#pragma once

#include <functional>
#include <string>

#include "rgraph/config.h"
#include "rgraph/gl/context.h"

namespace rgraph::testsupport {

// The program's headless context: created on first use (~70 ms), destroyed
// by a GoogleTest environment after the last test, before static destructors
// run (EGL may already be gone by then).
GlContext& sharedGlContext();
bool hasSharedGlContext();
// Runs `fn` at teardown before the context goes (for GL objects kept across tests).
void destroyBeforeContext(std::function<void()> fn);

// A pipeline file or JSON text checked against the built-in pass types;
// throws RuntimeError listing every diagnostic (and `context`, if given).
PipelineConfig loadPipelineOrThrow(const std::string& path);
PipelineConfig buildPipelineOrThrow(const std::string& text, const std::string& name, const std::string& context = {});

// The message of the RuntimeError `fn` throws; "(no error)" when it throws none.
std::string errorOf(const std::function<void()>& fn);

}  // namespace rgraph::testsupport
