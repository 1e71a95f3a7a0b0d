// Mip levels with stb_image_resize (a private, static copy, as image_decode.cpp does with stb_image).
#include "welkin/assets/mip_levels.h"

#include <vector>

#define STB_IMAGE_RESIZE_STATIC
#define STB_IMAGE_RESIZE_IMPLEMENTATION
#include <stb_image_resize.h>

#include "welkin/core/error.h"

namespace welkin::assets {

namespace {

stbir_edge stb_edge(MipEdge e) {
  return e == MipEdge::wrap ? STBIR_EDGE_WRAP : e == MipEdge::mirror ? STBIR_EDGE_REFLECT : STBIR_EDGE_CLAMP;
}

}  // namespace

MipEdge mip_edge_of_gl_wrap(int gl_wrap) {
  switch (gl_wrap) {
    case 33071: return MipEdge::clamp;
    case 33648: return MipEdge::mirror;
    default: return MipEdge::wrap;
  }
}

void for_each_mip_level(const Image& image, bool srgb, MipEdge edge_s, MipEdge edge_t,
                        const std::function<void(int, int, int, const uint8_t*)>& level) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != size_t(image.width) * size_t(image.height) * 4)
    throw Error(
        ErrorInfo{.file = image.name, .expected = "decoded pixels", .found = "an image without them"});
  std::vector<uint8_t> current, next;
  const uint8_t* pixels = image.rgba.data();
  int w = image.width, h = image.height;
  level(0, w, h, pixels);
  for (int l = 1; l < mip_level_count(image.width, image.height); ++l) {
    const int nw = std::max(1, w / 2), nh = std::max(1, h / 2);
    next.resize(size_t(nw) * size_t(nh) * 4);
    // STBIR_FLAG_ALPHA_PREMULTIPLIED: the colours are filtered as they are, not weighted by alpha.
    stbir_resize(pixels, w, h, 0, next.data(), nw, nh, 0, STBIR_TYPE_UINT8, 4, 3,
                 STBIR_FLAG_ALPHA_PREMULTIPLIED, stb_edge(edge_s), stb_edge(edge_t), STBIR_FILTER_BOX,
                 STBIR_FILTER_BOX, srgb ? STBIR_COLORSPACE_SRGB : STBIR_COLORSPACE_LINEAR, nullptr);
    current.swap(next);
    pixels = current.data();
    w = nw, h = nh;
    level(l, w, h, pixels);
  }
}

}  // namespace welkin::assets
