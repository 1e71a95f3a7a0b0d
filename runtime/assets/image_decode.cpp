// PNG and JPEG decoding for glTF images. A private, static copy of stb_image: the runtime's copy is
// built PNG-only (STBI_ONLY_PNG) and glTF images are often JPEG; STB_IMAGE_STATIC keeps these
// symbols local so they never clash with the runtime's exported ones.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_MAX_DIMENSIONS 16384
#include <stb_image.h>

#include <zlib.h>

#include <array>
#include <climits>
#include <cstring>

#include "internal.h"

namespace welkin::assets::detail {

namespace {

uint32_t read_be32(const uint8_t* p) {
  return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

// Bytes of filtered scanlines that a PNG's IHDR implies (PNG spec 7.2 and 8.2, Adam7 passes included).
uint64_t png_scanline_bytes(uint32_t w, uint32_t h, uint32_t bits_per_pixel, bool interlaced) {
  auto pass = [&](uint32_t pw, uint32_t ph) -> uint64_t {
    return pw == 0 || ph == 0 ? 0 : uint64_t(ph) * (1 + (uint64_t(pw) * bits_per_pixel + 7) / 8);
  };
  if (!interlaced) return pass(w, h);
  static constexpr uint32_t x0[7] = {0, 4, 0, 2, 0, 1, 0}, y0[7] = {0, 0, 4, 0, 2, 0, 1};
  static constexpr uint32_t dx[7] = {8, 8, 4, 4, 2, 2, 1}, dy[7] = {8, 8, 8, 4, 4, 2, 2};
  uint64_t total = 0;
  for (int i = 0; i < 7; ++i)
    total += pass(w > x0[i] ? (w - x0[i] + dx[i] - 1) / dx[i] : 0,
                  h > y0[i] ? (h - y0[i] + dy[i] - 1) / dy[i] : 0);
  return total;
}

// stb_image grows its inflate buffer for as long as the IDAT stream goes on, so a PNG of a few KiB
// with an honest small header could inflate to GiBs before stb notices the excess. The IDAT stream
// is inflated here first with zlib into a fixed 64 KiB scratch buffer (nothing kept), and refused as
// soon as its output passes the size the header implies; only then does stb decode it. Chunks that
// do not parse are left to stb, which reports them.
void check_png_inflated_size(std::span<const uint8_t> png, const Source& src, const std::string& path) {
  static constexpr uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (png.size() < 8 || std::memcmp(png.data(), kSignature, 8) != 0) return;  // JPEG
  z_stream z{};
  // Raw deflate (the 2-byte zlib header is skipped below) as stb reads it: stb checks no Adler-32.
  if (inflateInit2(&z, -15) != Z_OK) fail(src, path, "memory for inflating a PNG", "none");
  struct End {
    z_stream& z;
    ~End() { inflateEnd(&z); }
  } end{z};
  std::array<uint8_t, 64 * 1024> scratch;
  uint64_t allowed = 0, inflated = 0;
  bool have_header = false, apple_cgbi = false, stream_ended = false, idat_data_seen = false;
  size_t zlib_header_left = 2;
  std::string dims;
  for (size_t pos = 8; pos + 12 <= png.size() && !stream_ended;) {
    const uint32_t length = read_be32(&png[pos]);
    const uint8_t* type = &png[pos + 4];
    if (length > png.size() - pos - 12) return;  // cut short: stb reports it
    const uint8_t* data = &png[pos + 8];
    pos += 12 + size_t(length);
    if (std::memcmp(type, "CgBI", 4) == 0) apple_cgbi = true;  // iPhone PNG: raw deflate, no zlib header
    if (std::memcmp(type, "IHDR", 4) == 0 && length == 13 && !have_header) {
      const uint32_t w = read_be32(data), h = read_be32(data + 4), depth = data[8];
      const int channels[7] = {1, 0, 3, 1, 2, 0, 4};  // by colour type 0..6 (1 and 5 do not exist)
      if (data[9] > 6 || channels[data[9]] == 0 || depth == 0 || depth > 16) return;
      if (w > (1u << 24) || h > (1u << 24)) return;  // stb's header check refused these already
      allowed = png_scanline_bytes(w, h, uint32_t(channels[data[9]]) * depth, data[12] == 1);
      dims = std::to_string(w) + " x " + std::to_string(h);
      have_header = true;
      if (apple_cgbi) zlib_header_left = 0;
    } else if (std::memcmp(type, "IDAT", 4) == 0 && have_header) {
      // stb_image copies an empty IDAT chunk that comes before any image data through a null buffer
      // (undefined behaviour, found by the fuzzer under UBSan): such a file is refused here.
      if (length == 0 && !idat_data_seen)
        fail(src, path, "PNG image data starting in its first IDAT chunk",
             "an empty IDAT chunk before the image data");
      idat_data_seen = true;
      size_t skip = std::min<size_t>(zlib_header_left, length);
      zlib_header_left -= skip;
      z.next_in = const_cast<uint8_t*>(data + skip);
      z.avail_in = uInt(length - skip);
      // Until this chunk is used up and no output is pending (a full scratch buffer may hold more).
      do {
        z.next_out = scratch.data();
        z.avail_out = uInt(scratch.size());
        const int ret = inflate(&z, Z_NO_FLUSH);
        inflated += scratch.size() - z.avail_out;
        if (inflated > allowed)
          fail(src, path,
               "PNG image data inflating to at most " + std::to_string(allowed) + " bytes (its header's " +
                   dims + ")",
               "more (stopped after " + std::to_string(inflated) + ")");
        if (ret == Z_STREAM_END) {
          stream_ended = true;
          break;
        }
        if (ret != Z_OK && ret != Z_BUF_ERROR)
          fail(src, path, "a PNG with valid compressed image data",
               std::string("a zlib error (") + (z.msg ? z.msg : "unknown") + ")");
        if (ret == Z_BUF_ERROR) break;  // no progress: needs the next IDAT
      } while (z.avail_in > 0 || z.avail_out == 0);
    } else if (std::memcmp(type, "IEND", 4) == 0) {
      break;
    }
  }
}

}  // namespace

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
  check_png_inflated_size(encoded, src, path);  // the header is within the limits: now its data
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
