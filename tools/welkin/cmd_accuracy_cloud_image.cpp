// welkin accuracy clouds --image SCENE [--size WxH] [--paths-per-pixel N] [--qualities ...] [--out DIR]
// The scene's view under the probe's light (the sun alone: no sky, no air, no ground), marched at each
// quality three ways: as shipped (the preset's march resolution and temporal upscaling), at the
// preset's march resolution without the upscaling, and at every pixel (the preset's steps and light,
// resolution 1). Beside the path tracer's image of the same rays through the same field; with
// --paths-per-pixel 0 the shipped frame beside the march at every pixel, without path tracing.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "cloud_image.h"
#include "cloud_light_fit.h"
#include "comparison_panels.h"
#include "session.h"
#include "validation/cloud_probe.h"
#include "validation/isolated_pixels.h"
#include "welkin/core/disk_cache.h"
#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/gfx/gl_context.h"

namespace welkin::cli {

namespace {

namespace fs = std::filesystem;
using clouds::Quality;

// Quality custom with the preset's march and light, at `resolution_scale` of the frame's pixels and
// without the temporal upscaling.
void march_without_upscaling(clouds::VolumetricClouds& c, float resolution_scale) {
  const clouds::ResolvedQuality q = clouds::resolve_quality(c);
  c.quality = Quality::custom;
  c.max_steps = q.max_steps, c.min_step_m = q.min_step_m, c.max_step_m = q.max_step_m;
  c.light_steps = q.light_steps, c.light_step_m = q.light_step_m, c.shape_detail = q.shape_detail;
  c.step_growth = q.step_growth, c.turbulence = q.turbulence;
  c.resolution_scale = resolution_scale, c.temporal_upscaling = false;
}

// One quality's view three ways (the file's head comment).
struct QualityImages {
  std::vector<double> shipped, preset_resolution, every_pixel;
  float resolution_scale = 1.0f;
};

QualityImages march_three_ways(clouds::CloudProbe& probe, const Camera& camera, bool temporal_upscaling,
                               int width, int height) {
  QualityImages m;
  // As the scene ships it: the probe turns the upscaling off for its rays, the scene may have it on.
  const clouds::VolumetricClouds preset = probe.clouds();
  probe.clouds().temporal_upscaling = temporal_upscaling;
  m.shipped = probe.gpu_image(camera, width, height);
  probe.clouds() = preset;
  m.resolution_scale = clouds::resolve_quality(preset).resolution_scale;
  march_without_upscaling(probe.clouds(), m.resolution_scale);
  m.preset_resolution = probe.gpu_image(camera, width, height);
  probe.clouds() = preset;
  // The same march at every pixel: the light's and the shape's error without the upscaler's, which
  // at small sizes marches a few dozen pixels across.
  march_without_upscaling(probe.clouds(), 1.0f);
  m.every_pixel = probe.gpu_image(camera, width, height);
  probe.clouds() = preset;
  return m;
}

double mean_of(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / double(v.size());
}

// An image's error against a reference image (the path tracer's, or the march at every pixel), over
// the pixels and over 4 x 4 blocks of both (the reference's noise a quarter there).
struct ImageError {
  double rmse = 0.0, noise = 0.0, mean_ratio = 0.0, block_rmse = 0.0, block_noise = 0.0;
  double gpu_mean = 0.0, reference_mean = 0.0;  // over the cloud pixels (cd/m2)
  int pixels = 0;
};

ImageError compare(const std::vector<double>& gpu, const std::vector<double>& ref,
                   const std::vector<double>& ref_sigma, const std::vector<double>& ref_transmittance,
                   int width, int height) {
  ImageError e;
  double sum = 0.0, mean = 0.0, noise = 0.0, gpu_mean = 0.0;
  for (size_t i = 0; i < gpu.size(); ++i) {
    if (ref_transmittance[i] > 0.999 && gpu[i] <= 0.0) continue;  // no cloud on this pixel
    sum += (gpu[i] - ref[i]) * (gpu[i] - ref[i]), mean += ref[i], gpu_mean += gpu[i], ++e.pixels;
    noise += ref_sigma[i] * ref_sigma[i];
  }
  mean = std::max(mean / std::max(e.pixels, 1), 1e-30);
  e.rmse = std::sqrt(sum / std::max(e.pixels, 1)) / mean;
  e.noise = std::sqrt(noise / std::max(e.pixels, 1)) / mean;
  e.mean_ratio = gpu_mean / std::max(e.pixels, 1) / mean;
  e.gpu_mean = gpu_mean / std::max(e.pixels, 1), e.reference_mean = mean;
  double block_sum = 0.0, block_mean = 0.0, block_noise = 0.0;
  int blocks = 0;
  for (int by = 0; by + 4 <= height; by += 4)
    for (int bx = 0; bx + 4 <= width; bx += 4) {
      double g = 0.0, r = 0.0, v = 0.0;
      for (int y = by; y < by + 4; ++y)
        for (int x = bx; x < bx + 4; ++x) {
          const size_t i = size_t(y) * width + x;
          g += gpu[i] / 16.0, r += ref[i] / 16.0, v += std::pow(ref_sigma[i] / 16.0, 2.0);
        }
      if (g <= 0.0 && r <= 0.0) continue;
      block_sum += (g - r) * (g - r), block_mean += r, block_noise += v, ++blocks;
    }
  block_mean = std::max(block_mean / std::max(blocks, 1), 1e-30);
  e.block_rmse = std::sqrt(block_sum / std::max(blocks, 1)) / block_mean;
  e.block_noise = std::sqrt(block_noise / std::max(blocks, 1)) / block_mean;
  return e;
}

// Isolated pixels are counted where the neighbours (or the pixel, for a firefly) are above 2% of the
// march's mean: the black between clouds is no hole.
constexpr double kIsolatedFloor = 0.02;

void write_panels(const std::string& png, const std::vector<double>& gpu, const std::vector<double>& ref,
                  int width, int height) {
  ComparisonPanels panels{.width = width, .height = height};
  const double mean = std::max(mean_of(ref), 1e-30);
  for (size_t i = 0; i < gpu.size(); ++i) {
    panels.approximation.push_back(glm::dvec3(gpu[i])), panels.reference.push_back(glm::dvec3(ref[i]));
    panels.relative.push_back((gpu[i] - ref[i]) / mean);
  }
  write_comparison_panels(png, panels, std::max(1, 384 / width), 0.25);
}

// Every march's values beside each other (and the path tracer's), pixel by pixel (rows from the top):
// single pixels that stand out (a hole, a firefly) found by their numbers.
void write_pixels_csv(const std::string& path, const QualityImages& m,
                      const std::vector<clouds::reference::CloudRadianceEstimate>& reference, int width,
                      int height) {
  std::ostringstream csv;
  csv << "x,y,shipped,preset_resolution,every_pixel,reference,reference_ci95,reference_transmittance\n";
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const size_t i = size_t(y) * width + x;
      csv << x << "," << y << "," << m.shipped[i] << "," << m.preset_resolution[i] << "," << m.every_pixel[i];
      if (reference.empty())
        csv << ",,,\n";
      else
        csv << "," << reference[i].radiance() << "," << reference[i].scattered.ci95 << ","
            << reference[i].transmittance.mean << "\n";
    }
  write_file_atomically(path, csv.str());
}

}  // namespace

int write_cloud_images(const CloudAccuracyOptions& o, const std::map<std::string, Quality>& names, int width,
                       int height) {
  if (int64_t(width) * height > 640 * 360)
    throw Error(
        ErrorInfo{.path = "--size", .expected = "at most 640x360 pixels for --image", .found = o.size});
  const MeasuredCase measured = case_from_scene(o.image);
  fs::create_directories(o.out);
  std::unique_ptr<GlContext> gl = create_headless_context();
  clouds::CloudProbe probe(measured.clouds, measured.sun_azimuth_deg, measured.sun_elevation_deg);
  probe.set_reference_cache(o.cache.empty() ? DiskCache::from_environment() : DiskCache(o.cache));
  std::vector<clouds::reference::CloudRadianceEstimate> reference;
  std::vector<double> ref, ref_sigma, ref_transmittance;
  if (o.paths_per_pixel > 0) {
    clouds::reference::PathTraceSettings settings;
    settings.samples = uint64_t(o.paths_per_pixel);
    std::fprintf(stderr, "path tracing %dx%d pixels, %d paths each\n", width, height, o.paths_per_pixel);
    reference = probe.reference_image(measured.camera, width, height, settings);
    for (const auto& r : reference)
      ref.push_back(r.radiance()), ref_sigma.push_back(r.scattered.ci95 / 1.96),
          ref_transmittance.push_back(r.transmittance.mean);
  }
  const std::string stem = fs::path(o.image).stem().string();
  for (const std::string& q : o.qualities) {
    probe.clouds().quality = names.at(q);
    const QualityImages m =
        march_three_ways(probe, measured.camera, measured.clouds.temporal_upscaling, width, height);
    const std::string base = (fs::path(o.out) / ("clouds-image-" + stem + "-" + q)).string();
    write_pixels_csv(base + "-marches.csv", m, reference, width, height);
    const double least = kIsolatedFloor * mean_of(m.every_pixel);
    std::printf(
        "%s at %s, %dx%d: mean of the shipped frame %.1f%% of the march at every pixel's (at the preset's "
        "march "
        "resolution %.2f without the temporal upscaling %.1f%%)\n",
        stem.c_str(), q.c_str(), width, height,
        100 * mean_of(m.shipped) / std::max(mean_of(m.every_pixel), 1e-30), m.resolution_scale,
        100 * mean_of(m.preset_resolution) / std::max(mean_of(m.every_pixel), 1e-30));
    for (const auto& [label, image] :
         {std::pair{"shipped", &m.shipped}, std::pair{"preset's resolution", &m.preset_resolution},
          std::pair{"every pixel", &m.every_pixel}}) {
      const clouds::IsolatedPixels n = clouds::count_isolated_pixels(*image, width, height, least);
      std::printf(
          "  %-19s of %d pixels: %d off their 8 neighbours' median by a factor %.0f; %d holes and %d "
          "fireflies "
          "(a factor %.0f outside all 8); %d not finite\n",
          label, (width - 2) * (height - 2), n.off_median, clouds::kMedianFactor, n.holes, n.fireflies,
          clouds::kOutsideFactor, n.not_finite);
    }
    if (reference.empty()) {
      write_panels(base + "-against-every-pixel.png", m.shipped, m.every_pixel, width, height);
      std::printf("  wrote %s-against-every-pixel.png (shipped above, every pixel in the middle)\n",
                  base.c_str());
      continue;
    }
    for (const auto& [label, image] :
         {std::pair{q, &m.shipped}, std::pair{q + " marched at every pixel", &m.every_pixel}}) {
      const ImageError e = compare(*image, ref, ref_sigma, ref_transmittance, width, height);
      // The squared difference's expectation is the squared bias plus the reference's variance: what is
      // left after the variance is the real-time frame's own error, less noisy than the RMSE itself.
      const double bias = std::sqrt(std::max(e.rmse * e.rmse - e.noise * e.noise, 0.0));
      const std::string png = base + (image == &m.shipped ? "" : "-every-pixel") + ".png";
      write_panels(png, *image, ref, width, height);
      // The panels' radiances, pixel by pixel (rows from the top), for analysis beyond the picture.
      std::ostringstream pixels;
      pixels << "x,y,march,reference,reference_ci95,reference_transmittance\n";
      for (size_t i = 0; i < image->size(); ++i)
        pixels << i % size_t(width) << "," << i / size_t(width) << "," << (*image)[i] << "," << ref[i] << ","
               << reference[i].scattered.ci95 << "," << ref_transmittance[i] << "\n";
      write_file_atomically(png.substr(0, png.size() - 4) + ".csv", pixels.str());
      std::printf(
          "%s at %s, %dx%d: real time above, path tracer (%d paths a pixel) in the middle, difference below "
          "(full red or blue at 25%% of the mean): relative RMSE %.1f%% over %d cloud pixels (the "
          "reference's own "
          "noise %.1f%%; net of it %.1f%%), mean %.1f%% of the reference's (%.1f against %.1f cd/m2); over "
          "4x4 "
          "blocks %.1f%% (noise %.1f%%); wrote %s\n",
          stem.c_str(), label.c_str(), width, height, o.paths_per_pixel, 100 * e.rmse, e.pixels,
          100 * e.noise, 100 * bias, 100 * e.mean_ratio, e.gpu_mean, e.reference_mean, 100 * e.block_rmse,
          100 * e.block_noise, png.c_str());
    }
  }
  return kOk;
}

}  // namespace welkin::cli
