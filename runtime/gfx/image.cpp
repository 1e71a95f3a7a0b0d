#include "welkin/gfx/image.h"

#include <ImfArray.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb_image.h>

#include "welkin/core/error.h"
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
  for (int y = 0; y < d.height; ++y) std::copy_n(&raw[size_t(d.height - 1 - y) * row], row, &img.rgba[size_t(y) * row]);
  return img;
}

namespace {
std::string temp_name(const std::string& path) {
  // Keep the extension: some writers pick the format from it.
  auto dot = path.find_last_of('.');
  std::string ext = dot == std::string::npos ? "" : path.substr(dot);
  return path + ".tmp-" + std::to_string(::getpid()) + ext;
}
void commit(const std::string& tmp, const std::string& path) {
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Error(ErrorInfo{.file = path, .message = "cannot replace the file"});
  }
}
}  // namespace

void write_png(const std::string& path, const ImageU8& img) {
  std::string tmp = temp_name(path);
  if (!stbi_write_png(tmp.c_str(), img.width, img.height, 4, img.rgba.data(), img.width * 4)) {
    std::remove(tmp.c_str());
    throw Error(ErrorInfo{.file = path, .message = "cannot write PNG (does the folder exist?)"});
  }
  commit(tmp, path);
}

void write_exr(const std::string& path, const ImageF& img, ExrPrecision precision) {
  std::string tmp = temp_name(path);
  try {
    Imf::Header header(img.width, img.height);
    Imf::PixelType type = precision == ExrPrecision::half ? Imf::HALF : Imf::FLOAT;
    const char* names[] = {"R", "G", "B", "A"};
    for (const char* n : names) header.channels().insert(n, Imf::Channel(type));
    Imf::OutputFile file(tmp.c_str(), header);
    Imf::FrameBuffer fb;
    std::vector<half> halves;
    if (type == Imf::HALF) {
      halves.resize(img.rgba.size());
      for (size_t i = 0; i < halves.size(); ++i) halves[i] = half(img.rgba[i]);
      for (int c = 0; c < 4; ++c)
        fb.insert(names[c], Imf::Slice(Imf::HALF, reinterpret_cast<char*>(halves.data() + c), sizeof(half) * 4,
                                       sizeof(half) * 4 * img.width));
    } else {
      for (int c = 0; c < 4; ++c)
        fb.insert(names[c], Imf::Slice(Imf::FLOAT, (char*)(img.rgba.data() + c), sizeof(float) * 4,
                                       sizeof(float) * 4 * img.width));
    }
    file.setFrameBuffer(fb);
    file.writePixels(img.height);
  } catch (const std::exception& e) {
    std::remove(tmp.c_str());
    throw Error(ErrorInfo{.file = path, .message = std::string("cannot write EXR: ") + e.what()});
  }
  commit(tmp, path);
}

ImageF read_exr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    Imath::Box2i dw = file.header().dataWindow();
    ImageF img{dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1, {}};
    img.rgba.assign(size_t(img.width) * img.height * 4, 1.0f);
    Imf::FrameBuffer fb;
    const char* names[] = {"R", "G", "B", "A"};
    char* base = (char*)(img.rgba.data()) - (dw.min.x + size_t(dw.min.y) * img.width) * sizeof(float) * 4;
    for (int c = 0; c < 4; ++c)
      fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), sizeof(float) * 4,
                                     sizeof(float) * 4 * img.width, 1, 1, c == 3 ? 1.0 : 0.0));
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    return img;
  } catch (const std::exception& e) {
    throw Error(ErrorInfo{.file = path, .message = std::string("cannot read EXR: ") + e.what()});
  }
}

ImageU8 read_png(const std::string& path) {
  int w = 0, h = 0, n = 0;
  stbi_uc* data = stbi_load(path.c_str(), &w, &h, &n, 4);
  if (!data) throw Error(ErrorInfo{.file = path, .message = std::string("cannot read PNG: ") + stbi_failure_reason()});
  ImageU8 img{w, h, std::vector<uint8_t>(data, data + size_t(w) * h * 4)};
  stbi_image_free(data);
  return img;
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
