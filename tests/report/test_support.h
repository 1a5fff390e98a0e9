#pragma once

#include <cairo.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>

#include "engine/report/chart.h"

namespace recon::report::testing {

/// A decoded PNG, read back through cairo as a reader would.
class PngImage {
 public:
  explicit PngImage(const std::string& path)
      : surface_(cairo_image_surface_create_from_png(path.c_str())) {
    if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS) {
      const std::string reason = cairo_status_to_string(cairo_surface_status(surface_));
      cairo_surface_destroy(surface_);
      throw std::runtime_error("cannot decode " + path + ": " + reason);
    }
  }
  ~PngImage() { cairo_surface_destroy(surface_); }
  PngImage(const PngImage&) = delete;
  PngImage& operator=(const PngImage&) = delete;

  int width() const { return cairo_image_surface_get_width(surface_); }
  int height() const { return cairo_image_surface_get_height(surface_); }

  /// 0xRRGGBB of the pixel at (x, y); charts are opaque, so premultiplication does not matter.
  uint32_t Rgb(double x, double y) const {
    const int col = static_cast<int>(std::floor(x));
    const int row = static_cast<int>(std::floor(y));
    const unsigned char* data = cairo_image_surface_get_data(surface_);
    const int stride = cairo_image_surface_get_stride(surface_);
    return *reinterpret_cast<const uint32_t*>(data + row * stride + col * 4) & 0xFFFFFF;
  }

  size_t DistinctColors() const {
    std::set<uint32_t> colors;
    for (int y = 0; y < height(); ++y) {
      for (int x = 0; x < width(); ++x) colors.insert(Rgb(x, y));
    }
    return colors.size();
  }

  /// Pixels within `tolerance` (0-255 per channel) of `color`.
  size_t CountNear(const Color& color, int tolerance) const {
    size_t count = 0;
    for (int y = 0; y < height(); ++y) {
      for (int x = 0; x < width(); ++x) count += Near(Rgb(x, y), color, tolerance);
    }
    return count;
  }

  /// Pixels that look like `color` drawn over white with coverage >= `min_alpha`: how thin
  /// anti-aliased lines show up.
  size_t CountTinted(const Color& color, double min_alpha) const {
    size_t count = 0;
    for (int y = 0; y < height(); ++y) {
      for (int x = 0; x < width(); ++x) count += Tinted(Rgb(x, y), color, min_alpha);
    }
    return count;
  }

  static bool Tinted(uint32_t rgb, const Color& color, double min_alpha) {
    const double pixel[3] = {((rgb >> 16) & 0xFF) / 255.0, ((rgb >> 8) & 0xFF) / 255.0,
                             (rgb & 0xFF) / 255.0};
    const double target[3] = {color.r, color.g, color.b};
    // pixel = 1 - alpha * (1 - target); solve alpha on the channel with the most contrast and
    // require the other channels to agree with it.
    int best = 0;
    for (int c = 1; c < 3; ++c) best = target[c] < target[best] ? c : best;
    const double alpha = (1 - pixel[best]) / (1 - target[best]);
    if (alpha < min_alpha || alpha > 1.05) return false;
    for (int c = 0; c < 3; ++c) {
      if (std::abs(1 - alpha * (1 - target[c]) - pixel[c]) > 0.04) return false;
    }
    return true;
  }

  static bool Near(uint32_t rgb, const Color& color, int tolerance) {
    const int r = (rgb >> 16) & 0xFF, g = (rgb >> 8) & 0xFF, b = rgb & 0xFF;
    return std::abs(r - std::lround(color.r * 255)) <= tolerance &&
           std::abs(g - std::lround(color.g * 255)) <= tolerance &&
           std::abs(b - std::lround(color.b * 255)) <= tolerance;
  }

 private:
  cairo_surface_t* surface_;
};

/// A fresh directory under the system temp folder, removed with everything in it at the end.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("recon_report_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  std::string File(const std::string& name) const { return (path_ / name).string(); }
  /// Names of the entries in the directory, to check nothing was left behind.
  std::set<std::string> Entries() const {
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(path_)) {
      names.insert(entry.path().filename().string());
    }
    return names;
  }

 private:
  std::filesystem::path path_;
};

inline std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

/// Ten bars like the paper's Dynamic 2D figure: values 13-17, SEM about 0.3, two references.
inline BarChart PaperBarChart() {
  BarChart chart;
  chart.title = "Dynamic 2D: episode return";
  chart.subtitle = "15 runs per bar, seeds 1-15; whiskers show the standard error";
  chart.y_label = "return";
  chart.labels = {"RECON",           "RECON no beacons", "Baseline",           "Baseline + beacons",
                  "RECON 25% demos", "RECON 50% demos",  "Baseline 25% demos", "Baseline 50% demos",
                  "RECON play only", "Behaviour cloning"};
  chart.values = {16.82, 16.41, 14.07, 15.36, 15.12, 16.05, 13.02, 13.74, 14.58, 13.31};
  chart.errors = {0.28, 0.31, 0.35, 0.27, 0.33, 0.29, 0.38, 0.32, 0.30, 0.36};
  chart.references = {{17.79, "expert 17.79"}, {10.0, "standing still 10.0"}};
  return chart;
}

}  // namespace recon::report::testing
