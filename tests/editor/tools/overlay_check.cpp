// rgraph_overlay_check FRAME.png RGRAPH.png FRAME_HIDDEN.png RGRAPH_HIDDEN.png
// Whether the editor's overlay is depth-tested against rgraph's depth, from
// two runs of the editor: one with an object (FRAME: the window with the
// overlay, RGRAPH: rgraph's frame under it) and one with that object hidden.
//   overlay  pixels FRAME and RGRAPH differ at (the overlay is drawn there)
//   lines    pixels FRAME_HIDDEN and RGRAPH_HIDDEN differ at (the overlay where
//            nothing of the object can cover it)
//   object   pixels RGRAPH and RGRAPH_HIDDEN differ at (the object)
// Prints how many lines-and-object pixels show the object (the overlay behind
// it: hidden) and how many show the overlay (in front of it), and how many
// lines pixels away from the object lost the overlay. Exit 0 when both of the
// first are above zero and the last is zero; 2 otherwise; 1 for unusable files.
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace {

struct Image {
  int w = 0, h = 0;
  std::vector<unsigned char> rgba;
};

bool load(const char* path, Image& image) {
  int n = 0;
  unsigned char* px = stbi_load(path, &image.w, &image.h, &n, 4);
  if (!px) {
    std::fprintf(stderr, "error: cannot read %s: %s\n", path, stbi_failure_reason());
    return false;
  }
  image.rgba.assign(px, px + size_t(image.w) * image.h * 4);
  stbi_image_free(px);
  return true;
}

bool differ(const Image& a, const Image& b, size_t pixel) { return std::memcmp(&a.rgba[pixel * 4], &b.rgba[pixel * 4], 3) != 0; }

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s FRAME.png RGRAPH.png FRAME_HIDDEN.png RGRAPH_HIDDEN.png\n", argv[0]);
    return 1;
  }
  Image frame, plain, frameHidden, plainHidden;
  if (!load(argv[1], frame) || !load(argv[2], plain) || !load(argv[3], frameHidden) || !load(argv[4], plainHidden))
    return 1;
  for (const Image* i : {&plain, &frameHidden, &plainHidden})
    if (i->w != frame.w || i->h != frame.h) {
      std::fprintf(stderr, "error: the four images differ in size\n");
      return 1;
    }
  size_t behind = 0, inFront = 0, lost = 0, lines = 0, object = 0;
  for (size_t p = 0; p < size_t(frame.w) * frame.h; ++p) {
    const bool drawn = differ(frame, plain, p), line = differ(frameHidden, plainHidden, p),
               covered = differ(plain, plainHidden, p);
    lines += line;
    object += covered;
    if (line && covered) (drawn ? inFront : behind) += 1;
    if (line && !covered && !drawn) ++lost;
  }
  std::printf("overlay lines %zu px, object %zu px; over the object: %zu px hidden (behind it), %zu px drawn (in front); "
              "lines away from the object not drawn: %zu px\n",
              lines, object, behind, inFront, lost);
  return behind > 0 && inFront > 0 && lost == 0 ? 0 : 2;
}
