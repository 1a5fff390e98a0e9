#include "tests/support/golden_image.h"

#include <cairo.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/report/image_png.h"

namespace recon::testing {
namespace {

namespace fs = std::filesystem;

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;

constexpr char kUpdateVariable[] = "RECON_UPDATE_GOLDENS";
constexpr char kFailureDirVariable[] = "RECON_GOLDEN_FAILURES";
constexpr char kUpdateFlag[] = "--update-goldens";

void CheckTolerance(int per_channel_tolerance) {
  if (per_channel_tolerance < 0 || per_channel_tolerance > 255) {
    throw std::invalid_argument("per-channel tolerance must be within 0..255, got " +
                                std::to_string(per_channel_tolerance));
  }
}

void CheckBuffer(const RgbImage& image, const char* which) {
  if (image.width < 0 || image.height < 0 ||
      image.rgb.size() != static_cast<size_t>(image.width) * image.height * 3) {
    throw std::invalid_argument(std::string("the ") + which + " image's size (" +
                                std::to_string(image.width) + "x" + std::to_string(image.height) +
                                ") and pixel buffer (" + std::to_string(image.rgb.size()) +
                                " bytes) disagree");
  }
}

int MaxChannelDifference(const uint8_t* a, const uint8_t* b) {
  int max = 0;
  for (int c = 0; c < 3; ++c) max = std::max(max, std::abs(int{a[c]} - int{b[c]}));
  return max;
}

bool UpdateRequested() {
  const char* value = std::getenv(kUpdateVariable);
  return value != nullptr && std::strcmp(value, "1") == 0;
}

std::string FailureDir(const GoldenOptions& options) {
  if (!options.failure_dir.empty()) return options.failure_dir;
  if (const char* dir = std::getenv(kFailureDirVariable); dir != nullptr && *dir != '\0') {
    return dir;
  }
#ifdef RECON_BINARY_DIR
  return std::string(RECON_BINARY_DIR) + "/golden-failures";
#else
  return (fs::temp_directory_path() / "recon-golden-failures").string();
#endif
}

std::string Fixed(double value) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(3) << value;
  return out.str();
}

std::string Percent(double fraction) { return Fixed(fraction * 100) + " %"; }

std::string Size(int width, int height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

/// Writes `<name>.actual.png` (and `<name>.diff.png` if there is a golden to diff against) and
/// returns lines naming them. A folder that cannot be written must not hide the comparison's
/// own failure, so that error is returned as a line too rather than thrown.
std::string WriteFailureImages(const RgbImage& actual, const RgbImage* golden,
                               int per_channel_tolerance, const std::string& dir,
                               const std::string& name) {
  try {
    EnsureWritableDirectory(dir);
    const std::string actual_path = (fs::path(dir) / (name + ".actual.png")).string();
    report::WritePng(actual, actual_path);
    std::string lines = "\n  actual image: " + actual_path;
    const std::string diff_path = (fs::path(dir) / (name + ".diff.png")).string();
    if (golden != nullptr) {
      report::WritePng(DiffImage(*golden, actual, per_channel_tolerance), diff_path);
      lines += "\n  diff image:   " + diff_path + " (differences in red)";
    } else {
      // A diff from an earlier run would belong to a golden that is gone.
      std::error_code ignored;
      fs::remove(diff_path, ignored);
    }
    return lines;
  } catch (const std::exception& e) {
    return std::string("\n  (could not write the failure images: ") + e.what() + ")";
  }
}

constexpr char kUpdateHint[] =
    "run the test with --update-goldens (or with RECON_UPDATE_GOLDENS=1 in the environment)";

}  // namespace

RgbImage ReadPng(const std::string& path) {
  std::error_code error;
  if (!fs::exists(path, error)) throw UserError("cannot read the image " + path + ": no such file");
  SurfacePtr loaded(cairo_image_surface_create_from_png(path.c_str()), cairo_surface_destroy);
  if (cairo_surface_status(loaded.get()) != CAIRO_STATUS_SUCCESS) {
    throw UserError("cannot read the image " + path + ": not a PNG file (" +
                    cairo_status_to_string(cairo_surface_status(loaded.get())) + ")");
  }
  const int width = cairo_image_surface_get_width(loaded.get());
  const int height = cairo_image_surface_get_height(loaded.get());
  // Cairo hands back RGB24 or ARGB32 (and float formats for 16-bit PNGs in newer releases).
  // Copying onto one ARGB32 surface with OPERATOR_SOURCE is exact for the 8-bit formats and
  // leaves a single layout to decode.
  SurfacePtr argb(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height),
                  cairo_surface_destroy);
  cairo_t* cr = cairo_create(argb.get());
  cairo_set_operator(cr, CAIRO_OPERATOR_SOURCE);
  cairo_set_source_surface(cr, loaded.get(), 0, 0);
  cairo_paint(cr);
  cairo_destroy(cr);
  cairo_surface_flush(argb.get());

  RgbImage image;
  image.width = width;
  image.height = height;
  image.rgb.resize(static_cast<size_t>(width) * height * 3);
  const unsigned char* data = cairo_image_surface_get_data(argb.get());
  const int stride = cairo_image_surface_get_stride(argb.get());
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      uint32_t pixel;  // native-endian 0xAARRGGBB, premultiplied
      std::memcpy(&pixel, data + static_cast<size_t>(r) * stride + static_cast<size_t>(c) * 4,
                  sizeof pixel);
      const uint32_t alpha = pixel >> 24;
      uint8_t* out = image.rgb.data() + (static_cast<size_t>(r) * width + c) * 3;
      for (int channel = 0; channel < 3; ++channel) {
        const uint32_t premultiplied = (pixel >> (16 - 8 * channel)) & 0xFF;
        // Un-premultiply so dropping alpha keeps the stored colour rather than darkening it.
        out[channel] = alpha == 0 ? 0
                                  : static_cast<uint8_t>(std::min<uint32_t>(
                                        255, (premultiplied * 255 + alpha / 2) / alpha));
      }
    }
  }
  return image;
}

ImageDifference CompareImages(const RgbImage& a, const RgbImage& b, int per_channel_tolerance) {
  CheckTolerance(per_channel_tolerance);
  CheckBuffer(a, "first");
  CheckBuffer(b, "second");
  ImageDifference difference;
  difference.width_a = a.width;
  difference.height_a = a.height;
  difference.width_b = b.width;
  difference.height_b = b.height;
  difference.same_size = a.width == b.width && a.height == b.height;
  if (!difference.same_size) {
    difference.pixels_over_tolerance =
        std::max(int64_t{a.width} * a.height, int64_t{b.width} * b.height);
    difference.fraction_over_tolerance = difference.pixels_over_tolerance > 0 ? 1.0 : 0.0;
    difference.max_channel_difference = 255;
    difference.mean_abs_difference = 255;
    return difference;
  }
  const int64_t pixel_count = int64_t{a.width} * a.height;
  int64_t sum = 0;
  for (int64_t i = 0; i < pixel_count; ++i) {
    const uint8_t* pa = a.rgb.data() + i * 3;
    const uint8_t* pb = b.rgb.data() + i * 3;
    for (int c = 0; c < 3; ++c) sum += std::abs(int{pa[c]} - int{pb[c]});
    const int max = MaxChannelDifference(pa, pb);
    difference.max_channel_difference = std::max(difference.max_channel_difference, max);
    if (max > per_channel_tolerance) ++difference.pixels_over_tolerance;
  }
  if (pixel_count > 0) {
    difference.fraction_over_tolerance =
        static_cast<double>(difference.pixels_over_tolerance) / static_cast<double>(pixel_count);
    difference.mean_abs_difference =
        static_cast<double>(sum) / static_cast<double>(pixel_count * 3);
  }
  return difference;
}

RgbImage DiffImage(const RgbImage& golden, const RgbImage& actual, int per_channel_tolerance) {
  CheckTolerance(per_channel_tolerance);
  CheckBuffer(golden, "golden");
  CheckBuffer(actual, "actual");
  RgbImage diff;
  diff.width = std::max(golden.width, actual.width);
  diff.height = std::max(golden.height, actual.height);
  diff.rgb.resize(static_cast<size_t>(diff.width) * diff.height * 3);
  for (int r = 0; r < diff.height; ++r) {
    for (int c = 0; c < diff.width; ++c) {
      uint8_t* out = diff.rgb.data() + (static_cast<size_t>(r) * diff.width + c) * 3;
      const bool in_golden = r < golden.height && c < golden.width;
      const bool in_actual = r < actual.height && c < actual.width;
      if (!in_golden || !in_actual) {
        out[0] = 255, out[1] = 0, out[2] = 0;
        continue;
      }
      const uint8_t* g = golden.Pixel(r, c);
      const int max = MaxChannelDifference(g, actual.Pixel(r, c));
      if (max > per_channel_tolerance) {
        // 128..255 rather than 0..255: even a difference just over tolerance must stand out.
        out[0] = static_cast<uint8_t>(128 + max * 127 / 255), out[1] = 0, out[2] = 0;
      } else {
        // Faded to 191..255 grey: enough of the golden to see where things are, light enough
        // that no part of it can be mistaken for red.
        const int luma = (299 * g[0] + 587 * g[1] + 114 * g[2]) / 1000;
        const auto grey = static_cast<uint8_t>(255 - (255 - luma) / 4);
        out[0] = grey, out[1] = grey, out[2] = grey;
      }
    }
  }
  return diff;
}

::testing::AssertionResult MatchesGolden(const RgbImage& actual, const std::string& golden_path,
                                         const GoldenOptions& options) {
  CheckTolerance(options.per_channel_tolerance);
  if (!(options.max_fraction_over_tolerance >= 0 && options.max_fraction_over_tolerance <= 1)) {
    throw std::invalid_argument("max_fraction_over_tolerance must be within 0..1");
  }
  CheckBuffer(actual, "actual");
  const fs::path golden_file(golden_path);
  const std::string name = golden_file.stem().string();
  std::error_code error;

  if (UpdateRequested()) {
    const bool existed = fs::exists(golden_file, error);
    try {
      if (golden_file.has_parent_path()) EnsureWritableDirectory(golden_file.parent_path());
      report::WritePng(actual, golden_path);
    } catch (const std::exception& e) {
      return ::testing::AssertionFailure()
             << "RECON_UPDATE_GOLDENS=1 but the golden could not be written: " << e.what();
    }
    const std::string message = std::string(existed ? "refreshed" : "created") + " golden " +
                                golden_path + " from the actual image (RECON_UPDATE_GOLDENS=1)";
    // Passing assertions print nothing, and whoever updates goldens needs to know which ones
    // to review before committing them.
    std::cerr << "[golden] " << message << "\n";
    return ::testing::AssertionSuccess() << message;
  }

  const std::string failure_dir = FailureDir(options);
  if (!fs::exists(golden_file, error)) {
    return ::testing::AssertionFailure()
           << "golden " << golden_path << " does not exist; to create it from this image, "
           << kUpdateHint << "."
           << WriteFailureImages(actual, nullptr, options.per_channel_tolerance, failure_dir, name);
  }
  RgbImage golden;
  try {
    golden = ReadPng(golden_path);
  } catch (const UserError& e) {
    return ::testing::AssertionFailure()
           << "golden " << golden_path << " is unreadable (" << e.what()
           << "); to rewrite it from this image, " << kUpdateHint << "."
           << WriteFailureImages(actual, nullptr, options.per_channel_tolerance, failure_dir, name);
  }

  const ImageDifference difference = CompareImages(golden, actual, options.per_channel_tolerance);
  if (difference.same_size &&
      difference.fraction_over_tolerance <= options.max_fraction_over_tolerance) {
    // Leftovers from an earlier failure would otherwise suggest this golden still fails.
    for (const char* suffix : {".actual.png", ".diff.png"}) {
      fs::remove(fs::path(failure_dir) / (name + suffix), error);
    }
    return ::testing::AssertionSuccess();
  }

  ::testing::AssertionResult failure = ::testing::AssertionFailure();
  if (!difference.same_size) {
    failure << "the actual image is " << Size(actual.width, actual.height) << " but golden "
            << golden_path << " is " << Size(golden.width, golden.height) << ".";
  } else {
    failure << "the actual image differs from golden " << golden_path << ": "
            << difference.pixels_over_tolerance << " of " << int64_t{golden.width} * golden.height
            << " pixels (" << Percent(difference.fraction_over_tolerance)
            << ") differ by more than " << options.per_channel_tolerance
            << " in some channel, at most " << Percent(options.max_fraction_over_tolerance)
            << " may; largest channel difference " << difference.max_channel_difference
            << ", mean absolute difference " << Fixed(difference.mean_abs_difference) << ".";
  }
  failure << WriteFailureImages(actual, &golden, options.per_channel_tolerance, failure_dir, name)
          << "\nIf the change is intended, " << kUpdateHint << ".";
  return failure;
}

void ParseGoldenFlags(int* argc, char** argv) {
  int kept = 0;
  for (int i = 0; i < *argc; ++i) {
    if (i > 0 && std::strcmp(argv[i], kUpdateFlag) == 0) {
      setenv(kUpdateVariable, "1", /*overwrite=*/1);
    } else {
      argv[kept++] = argv[i];
    }
  }
  // argv[argc] is a null pointer by the C++ standard; keep it so for whoever parses next.
  for (int i = kept; i < *argc; ++i) argv[i] = nullptr;
  *argc = kept;
}

}  // namespace recon::testing
