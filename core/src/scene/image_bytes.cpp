// Image signatures and the JPEG Huffman-table check (see image_bytes.h).
#include "image_bytes.h"

#include <cstring>

namespace rgraph::image_bytes {

namespace {

bool startsWith(const unsigned char* bytes, size_t size, const char* sig, size_t n) {
  return size >= n && std::memcmp(bytes, sig, n) == 0;
}

// Walks a JPEG's marker segments, entropy-coded data included (a progressive
// JPEG defines Huffman tables between its scans), and checks each DHT table:
// at most 256 codes, all inside the segment. Anything else is left to the
// decoder, which checks it itself.
std::optional<std::string> jpegProblem(const unsigned char* b, size_t size) {
  size_t i = 2;  // after SOI
  while (i < size) {
    if (b[i] != 0xFF) {  // entropy-coded data, or padding the decoder skips too
      ++i;
      continue;
    }
    while (i < size && b[i] == 0xFF) ++i;  // fill bytes
    if (i >= size) break;
    const unsigned char m = b[i++];
    if (m == 0x00 || (m >= 0xD0 && m <= 0xD7) || m == 0x01) continue;  // stuffed byte, restart, TEM
    if (m == 0xD9) break;                                                // EOI
    if (i + 2 > size) break;
    const size_t length = (size_t(b[i]) << 8) | b[i + 1];
    if (m == 0xC4) {
      // The decoder reads every table whole, even past a segment's or the
      // file's end, so a table must fit inside both.
      const size_t end = i + length;
      if (length < 2 || end > size) return std::string("corrupt JPEG: Huffman table segment cut short");
      for (size_t p = i + 2; p < end;) {
        if (p + 17 > end) return std::string("corrupt JPEG: Huffman table header cut short");
        size_t codes = 0;
        for (size_t k = 1; k <= 16; ++k) codes += b[p + k];
        if (codes > 256)
          return "corrupt JPEG: a Huffman table declares " + std::to_string(codes) + " codes (at most 256)";
        p += 17 + codes;
        if (p > end) return std::string("corrupt JPEG: Huffman table longer than its segment");
      }
    }
    if (length < 2) break;  // the decoder refuses it
    i += length;
  }
  return std::nullopt;
}

}  // namespace

std::optional<Format> sniff(const unsigned char* bytes, size_t size) {
  if (startsWith(bytes, size, "\x89PNG\r\n\x1a\n", 8)) return Format::png;
  if (size >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return Format::jpeg;
  if (startsWith(bytes, size, "#?RADIANCE\n", 11) || startsWith(bytes, size, "#?RGBE\n", 7)) return Format::hdr;
  return std::nullopt;
}

std::optional<std::string> problem(const unsigned char* bytes, size_t size, bool allowHdr) {
  const std::optional<Format> f = sniff(bytes, size);
  if (!f || (*f == Format::hdr && !allowHdr))
    return allowHdr ? "not a Radiance .hdr, PNG or JPEG image" : "not a PNG or JPEG image";
  if (*f == Format::jpeg) return jpegProblem(bytes, size);
  return std::nullopt;
}

}  // namespace rgraph::image_bytes
