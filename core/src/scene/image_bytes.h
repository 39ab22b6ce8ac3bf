// What an image's bytes are, checked before a decoder sees them.
//
// Images reach stb_image from glTF files (PNG or JPEG, the formats the glTF
// specification allows) and from environment files (Radiance .hdr, or a PNG
// or JPEG). stb_image recognises more formats than those (GIF, PSD, TGA, PIC,
// PNM), each more attack surface for no use here, so anything else is refused
// by its signature first. And the stb_image Debian ships (2022-09-08) writes
// past a Huffman table's arrays when a JPEG's DHT segment declares more than
// 256 codes (fuzz_gltf found it): such a JPEG is refused here, unread.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace rgraph::image_bytes {

enum class Format { png, jpeg, hdr };

// The format the bytes' signature names, or nullopt.
std::optional<Format> sniff(const unsigned char* bytes, size_t size);

// Why these bytes must not reach the decoder ("not a PNG or JPEG image",
// "corrupt JPEG: ..."), or nullopt when they may. `allowHdr`: whether a
// Radiance .hdr is acceptable too.
std::optional<std::string> problem(const unsigned char* bytes, size_t size, bool allowHdr);

}  // namespace rgraph::image_bytes
