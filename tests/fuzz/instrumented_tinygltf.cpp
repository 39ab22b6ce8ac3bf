// fuzz_gltf only: tinygltf and stb_image's decoders compiled from the same
// Debian headers that libtinygltf.so and libstb.so were built from, but here
// with the fuzzer's coverage instrumentation and ASan. The definitions in the
// executable take precedence over the shared libraries', so the JSON parse,
// the GLB container and the image decoders are guided and checked too, not
// only rgraph's own loader code. (stb_image_write still comes from libstb.)
// (tiny_gltf.h includes stb_image.h itself: the decoders come with it.)
#define STB_IMAGE_IMPLEMENTATION
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
