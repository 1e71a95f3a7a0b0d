#include "welkin/gfx/image.h"

#include <ImfArray.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb_image.h>

#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/gfx/gl_objects.h"

namespace welkin {

ImageU8 read_texture_rgba8(const Texture& t) {
  ImageU8 img{t.desc().width, t.desc().height, {}};
  std::vector<uint8_t> raw(size_t(img.width) * img.height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(t.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(raw.size()), raw.data());
  check_gl("texture readback");
  img.rgba.resize(raw.size());
  size_t row = size_t(img.width) * 4;
  for (int y = 0; y < img.height; ++y)
    std::copy_n(&raw[size_t(img.height - 1 - y) * row], row, &img.rgba[size_t(y) * row]);
  return img;
}

ImageF read_texture_float(const Texture& t, int layer) {
  const auto& d = t.desc();
  ImageF img{d.width, d.height, {}};
  size_t row = size_t(d.width) * 4;
  std::vector<float> raw(row * d.height);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (t.is_3d())
    glGetTextureSubImage(t.id(), 0, 0, 0, layer, d.width, d.height, 1, GL_RGBA, GL_FLOAT,
                         GLsizei(raw.size() * sizeof(float)), raw.data());
  else
    glGetTextureImage(t.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(raw.size() * sizeof(float)), raw.data());
  check_gl("texture readback");
  img.rgba.resize(raw.size());
  for (int y = 0; y < d.height; ++y)
    std::copy_n(&raw[size_t(d.height - 1 - y) * row], row, &img.rgba[size_t(y) * row]);
  return img;
}

// Encoders write into memory; the one atomic writer puts the bytes on disk (so a full disk never
// replaces a good image with a truncated one), and readers go through the bounded regular-file reader.

std::vector<uint8_t> encode_png(const ImageU8& img) {
  std::vector<uint8_t> bytes;
  auto append = [](void* ctx, void* data, int size) {
    auto* out = static_cast<std::vector<uint8_t>*>(ctx);
    out->insert(out->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
  };
  if (!stbi_write_png_to_func(append, &bytes, img.width, img.height, 4, img.rgba.data(), img.width * 4))
    throw Error(ErrorInfo{.message = "cannot encode PNG"});
  return bytes;
}

void write_png(const std::string& path, const ImageU8& img) {
  std::vector<uint8_t> bytes;
  try {
    bytes = encode_png(img);
  } catch (const Error&) {
    throw Error(ErrorInfo{.file = path, .message = "cannot encode PNG"});
  }
  write_file_atomically(path, bytes);
}

void write_exr(const std::string& path, const ImageF& img, ExrPrecision precision) {
  Imf::StdOSStream out;
  try {
    Imf::Header header(img.width, img.height);
    Imf::PixelType type = precision == ExrPrecision::half ? Imf::HALF : Imf::FLOAT;
    const char* names[] = {"R", "G", "B", "A"};
    for (const char* n : names) header.channels().insert(n, Imf::Channel(type));
    Imf::OutputFile file(out, header);  // finishes writing (the offset table) when destroyed
    Imf::FrameBuffer fb;
    std::vector<half> halves;
    if (type == Imf::HALF) {
      halves.resize(img.rgba.size());
      for (size_t i = 0; i < halves.size(); ++i) halves[i] = half(img.rgba[i]);
      for (int c = 0; c < 4; ++c)
        fb.insert(names[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.data() + c),
                                       sizeof(half) * 4, sizeof(half) * 4 * img.width));
    } else {
      for (int c = 0; c < 4; ++c)
        fb.insert(names[c], Imf::Slice(Imf::FLOAT, (char*)(img.rgba.data() + c), sizeof(float) * 4,
                                       sizeof(float) * 4 * img.width));
    }
    file.setFrameBuffer(fb);
    file.writePixels(img.height);
  } catch (const std::exception& e) {
    throw Error(ErrorInfo{.file = path, .message = std::string("cannot encode EXR: ") + e.what()});
  }
  write_file_atomically(path, out.str());
}

namespace {
void check_image_size(const std::string& path, int64_t width, int64_t height, int max_side = kMaxImageSide) {
  if (width <= 0 || height <= 0 || width > max_side || height > max_side ||
      width * height > int64_t(kMaxImagePixels))
    throw Error(ErrorInfo{.file = path,
                          .expected = "an image of 1 to " + std::to_string(max_side) +
                                      " pixels a side and at most " + std::to_string(kMaxImagePixels) +
                                      " pixels",
                          .found = std::to_string(width) + "x" + std::to_string(height)});
}
}  // namespace

ImageF read_exr(const std::string& path) {
  Imf::StdISStream in;
  in.str(read_file_text(path, kMaxImageFileBytes));
  try {
    // OpenEXR sizes its tables from the header while opening: its own checks bound them first.
    Imf::Header::setMaxImageSize(kMaxImageSide, kMaxImageSide);
    Imf::Header::setMaxTileSize(kMaxImageSide, kMaxImageSide);
    Imf::InputFile file(in);
    Imath::Box2i dw = file.header().dataWindow();
    check_image_size(path, int64_t(dw.max.x) - dw.min.x + 1, int64_t(dw.max.y) - dw.min.y + 1);
    ImageF img{dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1, {}};
    img.rgba.assign(size_t(img.width) * img.height * 4, 1.0f);
    Imf::FrameBuffer fb;
    const char* names[] = {"R", "G", "B", "A"};
    // The slice base is the address of pixel (0, 0), which lies outside the buffer for a data window
    // not at the origin; compute it in integers so no out-of-range pointer arithmetic happens.
    const intptr_t origin =
        intptr_t(img.rgba.data()) -
        (intptr_t(dw.min.x) + intptr_t(dw.min.y) * img.width) * intptr_t(sizeof(float) * 4);
    for (int c = 0; c < 4; ++c)
      fb.insert(names[c],
                Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(origin + c * intptr_t(sizeof(float))),
                           sizeof(float) * 4, sizeof(float) * 4 * img.width, 1, 1, c == 3 ? 1.0 : 0.0));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return img;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(ErrorInfo{.file = path, .message = std::string("cannot read EXR: ") + e.what()});
  }
}

ImageU8 read_png(const std::string& path, int max_side) {
  const std::vector<uint8_t> bytes = read_file_bytes(path, kMaxImageFileBytes);
  if (bytes.size() > size_t(INT_MAX)) throw Error(ErrorInfo{.file = path, .message = "PNG file too large"});
  int w = 0, h = 0, n = 0;
  // The header first: the pixel count is checked before anything is decoded.
  if (!stbi_info_from_memory(bytes.data(), int(bytes.size()), &w, &h, &n))
    throw Error(ErrorInfo{.file = path, .message = std::string("cannot read PNG: ") + stbi_failure_reason()});
  check_image_size(path, w, h, std::min(max_side, kMaxImageSide));
  stbi_uc* data = stbi_load_from_memory(bytes.data(), int(bytes.size()), &w, &h, &n, 4);
  if (!data)
    throw Error(ErrorInfo{.file = path, .message = std::string("cannot read PNG: ") + stbi_failure_reason()});
  ImageU8 img{w, h, std::vector<uint8_t>(data, data + size_t(w) * h * 4)};
  stbi_image_free(data);
  return img;
}

ImageDifference image_difference(const ImageU8& a, const ImageU8& b) {
  if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
    throw Error(ErrorInfo{.expected = "two images of one size",
                          .found = std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                                   std::to_string(b.width) + "x" + std::to_string(b.height)});
  ImageDifference d;
  double squares = 0.0, sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < a.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const int e = std::abs(int(a.rgba[i]) - int(b.rgba[i]));
    squares += double(e) * e, sum += e, d.max = std::max(d.max, e), ++n;
  }
  d.mean = n ? sum / double(n) : 0.0;
  d.psnr_db = squares == 0.0 ? INFINITY : 10.0 * std::log10(255.0 * 255.0 / (squares / double(n)));
  return d;
}

uint8_t linear_to_srgb8(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  float s = v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
  return uint8_t(std::lround(s * 255.0f));
}

float srgb8_to_linear(uint8_t e) {
  float s = e / 255.0f;
  return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f);
}

}  // namespace welkin
