// rgraph_png_probe FILE [X Y]...: prints "WIDTH HEIGHT", then "R G B A" for
// each point (x from the left, y from the top). Exit 1 when the file cannot
// be read or a point lies outside.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  if (argc < 2 || argc % 2 != 0) {
    std::fprintf(stderr, "usage: %s FILE [X Y]...\n", argv[0]);
    return 1;
  }
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load(argv[1], &w, &h, &n, 4);
  if (!px) {
    std::fprintf(stderr, "error: cannot read %s: %s\n", argv[1], stbi_failure_reason());
    return 1;
  }
  std::printf("%d %d\n", w, h);
  int rc = 0;
  for (int i = 2; i + 1 < argc; i += 2) {
    int x = std::atoi(argv[i]), y = std::atoi(argv[i + 1]);
    if (x < 0 || y < 0 || x >= w || y >= h) {
      std::fprintf(stderr, "error: point %d,%d outside %dx%d\n", x, y, w, h);
      rc = 1;
      continue;
    }
    const unsigned char* p = px + 4 * (static_cast<size_t>(y) * w + x);
    std::printf("%d %d %d %d\n", p[0], p[1], p[2], p[3]);
  }
  stbi_image_free(px);
  return rc;
}
