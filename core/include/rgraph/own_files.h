// Where rgraph's own files are: its built-in shaders, its shipped pipelines and
// its plugin folder. Found at run time from the file the running rgraph code
// was loaded from (librgraph.so, found with dladdr; the program itself where
// rgraph is linked statically), never from a path baked in at build time, so
// that an installed rgraph works wherever its prefix is copied or moved and
// never reads the build or source tree it was built from.
//
// Two layouts, told apart by a marker file beside that code file:
//   - an install (no marker): <libdir>/librgraph.so with
//       <prefix>/share/rgraph/shaders, <prefix>/share/rgraph/pipelines
//     (the path from <libdir> to <prefix>/share/rgraph is fixed when rgraph is
//     configured: "../share/rgraph" for lib/, "../../share/rgraph" for a
//     multiarch lib/<triplet>/) and <libdir>/rgraph/plugins;
//   - a build tree: CMake writes rgraph-build-tree.txt into <build>/lib and
//     <build>/bin (never installed); it names the source tree's shaders/ and
//     pipelines/, so a build tree runs its sources' shaders as they are edited.
//     Plugins are <build>/lib/rgraph/plugins, the install's layout.
#pragma once

#include <string>

namespace rgraph {

struct OwnFiles {
  std::string shaders;    // the built-in shaders' folder
  std::string pipelines;  // the shipped pipelines' folder (default.json, ...)
  std::string plugins;    // rgraph's own plugin folder
  std::string codeFile;   // the file they were found from (librgraph.so, or the program)
  bool buildTree = false; // found through the build tree's marker file
};

// The folders for this process, found on the first call (thread-safe) and
// logged once at debug level; a folder may not exist (an install without its
// pipelines). Empty strings when the code's file cannot be found.
const OwnFiles& ownFiles();

// The rule itself, for code loaded from `file` (an absolute path): what
// ownFiles() gives when the running code is there. Reads the marker if any.
OwnFiles ownFilesBeside(const std::string& file);

// The marker's file name (rgraph-build-tree.txt): lines "shaders=DIR" and
// "pipelines=DIR"; '#' starts a comment line.
extern const char* const kBuildTreeMarker;

}  // namespace rgraph
