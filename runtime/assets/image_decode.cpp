// PNG and JPEG decoding for glTF images. A private, static copy of stb_image: the runtime's copy is
// built PNG-only (STBI_ONLY_PNG) and glTF images are often JPEG; STB_IMAGE_STATIC keeps these
// symbols local so they never clash with the runtime's exported ones.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_MAX_DIMENSIONS 16384
#if defined(__GNUC__)  // GCC and clang: the static copy has functions this file does not call
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <climits>
#include <cstring>

#include "internal.h"

namespace welkin::assets::detail {

Image decode_image(std::span<const uint8_t> encoded, const Source& src, const std::string& path,
                   uint64_t& total_bytes) {
  const auto& lim = src.options.limits;
  if (encoded.empty() || encoded.size() > uint64_t(INT_MAX))
    fail(src, path, "1 to " + std::to_string(INT_MAX) + " bytes of PNG or JPEG",
         std::to_string(encoded.size()) + " bytes");
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(encoded.data(), int(encoded.size()), &w, &h, &comp))
    fail(src, path, "a PNG or JPEG image", std::string("undecodable data (") + stbi_failure_reason() + ")");
  if (w < 1 || h < 1 || w > lim.max_image_side || h > lim.max_image_side ||
      uint64_t(w) * h > lim.max_image_pixels)
    fail(src, path,
         "an image of at most " + std::to_string(lim.max_image_side) + " pixels a side and " +
             std::to_string(lim.max_image_pixels) + " pixels",
         std::to_string(w) + " x " + std::to_string(h));
  const uint64_t bytes = uint64_t(w) * h * 4;
  if (total_bytes + bytes > lim.max_total_image_bytes)
    fail(src, path,
         "decoded images of at most " + std::to_string(lim.max_total_image_bytes) + " bytes in all",
         std::to_string(total_bytes + bytes) + " bytes");
  int dw = 0, dh = 0;
  stbi_uc* pixels = stbi_load_from_memory(encoded.data(), int(encoded.size()), &dw, &dh, &comp, 4);
  if (!pixels)
    fail(src, path, "a decodable PNG or JPEG image",
         std::string("a decoding error (") + stbi_failure_reason() + ")");
  Image img;
  if (dw != w || dh != h) {
    stbi_image_free(pixels);
    fail(src, path, "the size its header states", std::to_string(dw) + " x " + std::to_string(dh));
  }
  img.width = w;
  img.height = h;
  img.rgba.assign(pixels, pixels + bytes);
  stbi_image_free(pixels);
  total_bytes += bytes;
  return img;
}

}  // namespace welkin::assets::detail
