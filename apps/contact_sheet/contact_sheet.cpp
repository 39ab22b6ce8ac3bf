// rgraph_contact_sheet: lays images out in rows of labelled cells, for
// docs/images/gltf_contact_sheet.png (scripts/gltf-samples.sh --sheet): each
// row a label and its images side by side, each scaled to fit its cell with
// its aspect kept. Reads PNG, JPEG and GIF (stb_image), draws and writes with cairo.
//
//   rgraph_contact_sheet OUT.png --cell W H --columns "rgraph deferred-pbr" "screenshot" \
//       --row LABEL IMAGE IMAGE [--row LABEL IMAGE IMAGE ...]
//
// An image that is missing or unreadable leaves its cell grey with a note; the
// sheet is still written (a sample without a screenshot is not an error). Bad
// arguments: a message and exit 1.
#include <cairo.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_GIF  // some samples' screenshots are animations: their first frame
#include <stb_image.h>

namespace {

struct Row {
  std::string label;
  std::vector<std::string> images;
};

struct Sheet {
  std::string out;
  int cellW = 320, cellH = 180;
  std::vector<std::string> columns;
  std::vector<Row> rows;
};

constexpr int kLabelW = 220, kHeaderH = 28, kPad = 6;

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr,
               "rgraph_contact_sheet: %s\nusage: rgraph_contact_sheet OUT.png [--cell W H] [--columns NAME...] "
               "--row LABEL IMAGE... [--row ...]\n",
               why.c_str());
  std::exit(1);
}

int positive(const char* text, const char* what) {
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  if (!end || *end || v < 16 || v > 4096) usage(std::string(what) + " must be a whole number in 16..4096, got '" + text + "'");
  return static_cast<int>(v);
}

Sheet parse(int argc, char** argv) {
  if (argc < 2) usage("no output file");
  Sheet s;
  s.out = argv[1];
  std::vector<std::string>* list = nullptr;  // where bare words go
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--cell") {
      if (i + 2 >= argc) usage("--cell needs W and H");
      s.cellW = positive(argv[++i], "cell width");
      s.cellH = positive(argv[++i], "cell height");
      list = nullptr;
    } else if (a == "--columns") {
      list = &s.columns;
    } else if (a == "--row") {
      if (i + 1 >= argc) usage("--row needs a label");
      s.rows.push_back({argv[++i], {}});
      list = &s.rows.back().images;
    } else if (list) {
      list->push_back(a);
    } else {
      usage("unexpected argument '" + a + "'");
    }
  }
  if (s.rows.empty()) usage("no --row given");
  return s;
}

// cairo wants premultiplied BGRA in native-endian 32-bit words.
cairo_surface_t* loadImage(const std::string& path) {
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load(path.c_str(), &w, &h, &n, 4);
  if (!px) return nullptr;
  cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
  cairo_surface_flush(img);
  unsigned char* dst = cairo_image_surface_get_data(img);
  const int stride = cairo_image_surface_get_stride(img);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const unsigned char* p = px + (static_cast<size_t>(y) * w + x) * 4;
      const unsigned a = p[3];
      const uint32_t word = (a << 24) | ((p[0] * a / 255) << 16) | ((p[1] * a / 255) << 8) | (p[2] * a / 255);
      *reinterpret_cast<uint32_t*>(dst + static_cast<size_t>(y) * stride + x * 4) = word;
    }
  cairo_surface_mark_dirty(img);
  stbi_image_free(px);
  return img;
}

void text(cairo_t* cr, double x, double y, const std::string& s, double size) {
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
}

void drawCell(cairo_t* cr, const std::string& path, double x, double y, int w, int h) {
  cairo_set_source_rgb(cr, 0.55, 0.55, 0.55);
  cairo_rectangle(cr, x, y, w, h);
  cairo_fill(cr);
  cairo_surface_t* img = loadImage(path);
  if (!img) {
    text(cr, x + 8, y + h / 2.0, "missing: " + path.substr(path.find_last_of('/') + 1), 11);
    return;
  }
  const double iw = cairo_image_surface_get_width(img), ih = cairo_image_surface_get_height(img);
  const double scale = std::min(w / iw, h / ih);
  cairo_save(cr);
  cairo_translate(cr, x + (w - iw * scale) / 2.0, y + (h - ih * scale) / 2.0);
  cairo_scale(cr, scale, scale);
  cairo_set_source_surface(cr, img, 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_GOOD);
  cairo_paint(cr);
  cairo_restore(cr);
  cairo_surface_destroy(img);
}

}  // namespace

int main(int argc, char** argv) {
  const Sheet s = parse(argc, argv);
  size_t columns = s.columns.size();
  for (const Row& r : s.rows) columns = std::max(columns, r.images.size());
  const int width = kLabelW + static_cast<int>(columns) * (s.cellW + kPad) + kPad;
  const int height = kHeaderH + static_cast<int>(s.rows.size()) * (s.cellH + kPad) + kPad;
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  for (size_t c = 0; c < s.columns.size(); ++c)
    text(cr, kLabelW + c * (s.cellW + kPad) + kPad, kHeaderH - 9, s.columns[c], 15);
  for (size_t r = 0; r < s.rows.size(); ++r) {
    const double y = kHeaderH + r * (s.cellH + kPad);
    text(cr, kPad, y + s.cellH / 2.0, s.rows[r].label, 13);
    for (size_t c = 0; c < s.rows[r].images.size(); ++c)
      drawCell(cr, s.rows[r].images[c], kLabelW + c * (s.cellW + kPad) + kPad, y, s.cellW, s.cellH);
  }
  cairo_destroy(cr);
  const cairo_status_t status = cairo_surface_write_to_png(surface, s.out.c_str());
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS) {
    std::fprintf(stderr, "rgraph_contact_sheet: cannot write '%s': %s\n", s.out.c_str(), cairo_status_to_string(status));
    return 1;
  }
  return 0;
}
