// Image files (no GL). Pixels are RGBA8, rows top-down.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace rgraph {

// Writes a PNG. Throws rgraph::RuntimeError naming the path when the size of
// `rgba` is not w*h*4 or the file cannot be written.
void writePng(const std::string& path, uint32_t w, uint32_t h, const std::vector<uint8_t>& rgba);

}  // namespace rgraph
