#pragma once

#include <cairo.h>

#include <string>

#include "engine/report/chart.h"

namespace recon::report {

enum class ImageFormat { kPng, kSvg };

/// A font request for Canvas text; sizes are in device pixels.
struct Font {
  double size = 12;
  bool bold = false;
  bool italic = false;
};

enum class HAlign { kLeft, kCenter, kRight };
enum class VAlign { kBaseline, kTop, kMiddle, kBottom };

/// One cairo surface and context, plus the few text helpers charts need. Rendering goes to memory
/// and Encode() returns the file bytes, so a failed render never touches the output path.
class Canvas {
 public:
  Canvas(ImageFormat format, int width, int height);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  cairo_t* cr() { return cr_; }

  void SetColor(const Color& color, double alpha = 1.0);
  double TextWidth(const std::string& text, const Font& font);
  /// Height of one line of `font` (ascent + descent), used for stacking lines.
  double LineHeight(const Font& font);
  /// Draws `text` anchored at (x, y); with `angle_rad` the anchor box turns around (x, y).
  /// `halo` strokes a white outline first so the text stays legible over lines.
  void Text(const std::string& text, double x, double y, const Font& font, const Color& color,
            HAlign h_align, VAlign v_align, double angle_rad = 0, bool halo = false);

  /// Finishes drawing and returns the encoded PNG or SVG. Throws std::runtime_error on a cairo
  /// failure (out of memory), which is not the user's fault.
  std::string Encode();

 private:
  void SelectFont(const Font& font);

  ImageFormat format_;
  std::string svg_bytes_;  // filled by the SVG surface's stream callback
  cairo_surface_t* surface_ = nullptr;
  cairo_t* cr_ = nullptr;
};

/// Rounds a coordinate so that a line of `width_px` lands on whole pixels (crisp, not blurred).
double Crisp(double coordinate, double width_px);

}  // namespace recon::report
