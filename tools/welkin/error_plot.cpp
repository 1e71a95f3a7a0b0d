// A log-log plot of error against GPU time, drawn by hand (no plotting library in Debian's C++ set).
#include "error_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "welkin/gfx/image.h"

// Debian's stb: a tiny vector font, enough for axis labels (static functions, one translation unit).
#include <stb/stb_easy_font.h>

namespace welkin::cli {

namespace {

struct Canvas {
  ImageU8 image;
  Canvas(int w, int h) : image{w, h, std::vector<uint8_t>(size_t(w) * h * 4, 255)} {}
  void pixel(int x, int y, glm::u8vec3 c) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    uint8_t* p = &image.rgba[(size_t(y) * image.width + x) * 4];
    p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = 255;
  }
  void rect(int x0, int y0, int x1, int y1, glm::u8vec3 c) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) pixel(x, y, c);
  }
  void line(double x0, double y0, double x1, double y1, glm::u8vec3 c, int width = 1) {
    const int n = int(std::max(std::abs(x1 - x0), std::abs(y1 - y0))) + 1;
    for (int i = 0; i <= n; ++i) {
      const double t = double(i) / n;
      const int x = int(std::lround(x0 + (x1 - x0) * t)), y = int(std::lround(y0 + (y1 - y0) * t));
      rect(x - width / 2, y - width / 2, x - width / 2 + width, y - width / 2 + width, c);
    }
  }
  void disc(double cx, double cy, double r, glm::u8vec3 c) {
    for (int y = int(cy - r); y <= int(cy + r) + 1; ++y)
      for (int x = int(cx - r); x <= int(cx + r) + 1; ++x)
        if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r) pixel(x, y, c);
  }
  void square(double cx, double cy, double r, glm::u8vec3 c) {
    line(cx - r, cy - r, cx + r, cy - r, c, 2);
    line(cx + r, cy - r, cx + r, cy + r, c, 2);
    line(cx + r, cy + r, cx - r, cy + r, c, 2);
    line(cx - r, cy + r, cx - r, cy - r, c, 2);
  }
  // stb_easy_font emits quads (4 vertices of x, y, z, colour); each is an axis-aligned rectangle.
  void text(double x, double y, const std::string& s, glm::u8vec3 c, int scale = 1) {
    static char buffer[60000];
    std::string copy = s;
    unsigned char colour[4] = {c.r, c.g, c.b, 255};
    const int quads = stb_easy_font_print(0, 0, copy.data(), colour, buffer, sizeof buffer);
    const float* v = reinterpret_cast<const float*>(buffer);
    for (int q = 0; q < quads; ++q, v += 16) {
      const int x0 = int(x + v[0] * scale), y0 = int(y + v[1] * scale);
      const int x1 = int(x + v[8] * scale), y1 = int(y + v[9] * scale);
      rect(std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1), c);
    }
  }
  static int text_width(const std::string& s, int scale = 1) {
    std::string copy = s;
    return stb_easy_font_width(copy.data()) * scale;
  }
};

double floor_decade(double v) {
  return std::pow(10.0, std::floor(std::log10(v)));
}
double ceil_decade(double v) {
  return std::pow(10.0, std::ceil(std::log10(v)));
}

std::string tick_label(double v, bool percent) {
  char buf[32];
  std::snprintf(buf, sizeof buf, percent ? "%g%%" : "%g", percent ? v * 100.0 : v);
  return buf;
}

}  // namespace

void write_error_plot(const std::string& path, const std::string& title, const std::string& subtitle,
                      const std::string& x_label, const std::vector<PlotSeries>& series) {
  const int W = 760, H = 520, left = 70, right = 180, top = 70, bottom = 60;
  Canvas c(W, H);
  double x_lo = 1e30, x_hi = 0, y_lo = 1e30, y_hi = 0;
  for (const PlotSeries& s : series)
    for (const PlotPoint& p : s.points) {
      x_lo = std::min(x_lo, p.ms), x_hi = std::max(x_hi, p.ms);
      y_lo = std::min(y_lo, std::max(p.rmse, 1e-4));
      y_hi = std::max(y_hi, std::max(p.max, 1e-4));
    }
  x_lo = floor_decade(x_lo), x_hi = ceil_decade(x_hi * 1.0001), y_lo = floor_decade(y_lo),
  y_hi = ceil_decade(y_hi * 1.0001);
  auto px = [&](double x) {
    return left + (std::log10(x) - std::log10(x_lo)) / std::log10(x_hi / x_lo) * (W - left - right);
  };
  auto py = [&](double y) {
    return H - bottom - (std::log10(y) - std::log10(y_lo)) / std::log10(y_hi / y_lo) * (H - top - bottom);
  };
  const glm::u8vec3 grid(225, 225, 225), axis(60, 60, 60), ink(20, 20, 20);
  for (double d = x_lo; d <= x_hi * 1.0001; d *= 10)
    for (int k = 1; k < 10 && d * k <= x_hi * 1.0001; ++k) {
      c.line(px(d * k), top, px(d * k), H - bottom, k == 1 ? glm::u8vec3(190, 190, 190) : grid);
      if (k == 1 || (k == 2 || k == 5)) {
        const std::string l = tick_label(d * k, false);
        c.text(px(d * k) - Canvas::text_width(l) / 2.0, H - bottom + 6, l, ink);
      }
    }
  for (double d = y_lo; d <= y_hi * 1.0001; d *= 10)
    for (int k = 1; k < 10 && d * k <= y_hi * 1.0001; ++k) {
      c.line(left, py(d * k), W - right, py(d * k), k == 1 ? glm::u8vec3(190, 190, 190) : grid);
      if (k == 1 || k == 2 || k == 5) {
        const std::string l = tick_label(d * k, true);
        c.text(left - 6 - Canvas::text_width(l), py(d * k) - 3, l, ink);
      }
    }
  c.line(left, H - bottom, W - right, H - bottom, axis, 2);
  c.line(left, top, left, H - bottom, axis, 2);
  c.text(left, 10, title, ink, 2);
  c.text(left, 32, subtitle, axis);
  c.text(left + (W - left - right - Canvas::text_width(x_label)) / 2.0, H - 24, x_label, ink);
  c.text(6, top - 14, "relative error (log)", ink);

  for (const PlotSeries& s : series) {
    for (size_t i = 1; i < s.points.size(); ++i)
      c.line(px(s.points[i - 1].ms), py(std::max(s.points[i - 1].rmse, y_lo)), px(s.points[i].ms),
             py(std::max(s.points[i].rmse, y_lo)), s.colour);
    int k = 0;
    for (const PlotPoint& p : s.points) {
      const double x = px(p.ms), y = py(std::max(p.rmse, y_lo)), ym = py(std::max(p.max, y_lo));
      c.disc(x, y, 4.5, s.colour);
      c.square(x, ym, 4, s.colour);
      // Neighbouring points alternate above and below, so close ones stay legible.
      c.text(x + 6, (k++ % 2 == 0) ? y - 14 : y + 6, p.label, s.colour);
    }
  }
  // Legend.
  double ly = top + 10;
  const double lx = W - right + 16;
  for (const PlotSeries& s : series) {
    c.disc(lx + 5, ly + 3, 4.5, s.colour);
    c.text(lx + 16, ly, s.name + ": relative RMSE", ink);
    ly += 16;
    c.square(lx + 5, ly + 3, 4, s.colour);
    c.text(lx + 16, ly, s.name + ": max error", ink);
    ly += 22;
  }
  c.text(lx, ly, "labels: quality preset", axis);
  write_png(path, c.image);
}


}  // namespace welkin::cli
