#pragma once
// CPU images, GPU readback and files: PNG (8-bit, sRGB-encoded) and OpenEXR (linear HDR, half or
// float). Rows are stored top to bottom, as in files; readback flips GL's bottom-up rows.
#include <cstdint>
#include <string>
#include <vector>

namespace welkin {

class Texture;

struct ImageU8 {
  int width = 0, height = 0;
  std::vector<uint8_t> rgba;  // 4 bytes per pixel
  const uint8_t* pixel(int x, int y) const { return &rgba[(size_t(y) * width + x) * 4]; }
};

struct ImageF {
  int width = 0, height = 0;
  std::vector<float> rgba;  // 4 floats per pixel
  const float* pixel(int x, int y) const { return &rgba[(size_t(y) * width + x) * 4]; }
  float* pixel(int x, int y) { return &rgba[(size_t(y) * width + x) * 4]; }
};

enum class ExrPrecision { half, full };

// Bounds for images read from files (checked from the header, before pixels are decoded) and for
// images the tools are asked to make (sequence frames, contact sheets).
inline constexpr int kMaxImageSide = 16384;
inline constexpr uint64_t kMaxImagePixels = 1ull << 26;  // 256 MiB as RGBA8, 1 GiB as RGBA float
inline constexpr uint64_t kMaxImageFileBytes = 512ull << 20;

ImageU8 read_texture_rgba8(const Texture& texture);
// Layer `layer` of a 3D texture, or the 2D texture itself.
ImageF read_texture_float(const Texture& texture, int layer = 0);

// Files are written with write_file_atomically (welkin/core/files.h) and read with the bounded
// regular-file reader; images over the bounds above are refused. Throw Error on failure.
void write_png(const std::string& path, const ImageU8& image);
// The PNG file's bytes, in memory (what write_png writes).
std::vector<uint8_t> encode_png(const ImageU8& image);
void write_exr(const std::string& path, const ImageF& image, ExrPrecision precision = ExrPrecision::half);
// max_side: the largest width and height the caller takes, checked from the header before decoding.
ImageU8 read_png(const std::string& path, int max_side = kMaxImageSide);
ImageF read_exr(const std::string& path);

// How far two 8-bit images of one size are apart over their colour channels (alpha aside): the
// peak signal-to-noise ratio in dB (infinite when equal), the mean and the largest difference in steps.
struct ImageDifference {
  double psnr_db = 0.0, mean = 0.0;
  int max = 0;
};
// Throws Error when the sizes differ.
ImageDifference image_difference(const ImageU8& a, const ImageU8& b);

// Linear [0,1] to sRGB-encoded 8-bit, with the exact sRGB transfer function.
uint8_t linear_to_srgb8(float linear);
float srgb8_to_linear(uint8_t encoded);

}  // namespace welkin
