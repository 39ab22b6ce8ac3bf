#include "rgraph/image.h"

#include <climits>

#include "rgraph/error.h"

// Private copy of the writer: static functions, so no clash with another stb user.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace rgraph {

void writePng(const std::string& path, uint32_t w, uint32_t h, const std::vector<uint8_t>& rgba) {
  if (w == 0 || h == 0 || w > INT_MAX / 4 || h > INT_MAX)
    throw RuntimeError("cannot write " + path + ": invalid image size " + std::to_string(w) + "x" + std::to_string(h));
  if (rgba.size() != static_cast<size_t>(w) * h * 4)
    throw RuntimeError("cannot write " + path + ": expected " + std::to_string(static_cast<size_t>(w) * h * 4) +
                       " bytes of RGBA8 pixels, got " + std::to_string(rgba.size()));
  if (!stbi_write_png(path.c_str(), static_cast<int>(w), static_cast<int>(h), 4, rgba.data(), static_cast<int>(w * 4)))
    throw RuntimeError("cannot write PNG file " + path);
}

}  // namespace rgraph
