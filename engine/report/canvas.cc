#include "engine/report/canvas.h"

#include <cairo-svg.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace recon::report {
namespace {

constexpr const char* kFontFamily = "DejaVu Sans";

cairo_status_t AppendBytes(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

void CheckStatus(cairo_status_t status, const char* what) {
  if (status != CAIRO_STATUS_SUCCESS) {
    throw std::runtime_error(std::string("cairo failed to ") + what + ": " +
                             cairo_status_to_string(status));
  }
}

}  // namespace

Canvas::Canvas(ImageFormat format, int width, int height) : format_(format) {
  if (format == ImageFormat::kPng) {
    surface_ = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
  } else {
    surface_ = cairo_svg_surface_create_for_stream(&AppendBytes, &svg_bytes_, width, height);
  }
  cr_ = cairo_create(surface_);
  CheckStatus(cairo_status(cr_), "create a drawing surface");
  // Unhinted metrics make text widths identical on PNG and SVG surfaces, so one layout serves
  // both; anti-aliasing is on for shapes and text.
  cairo_font_options_t* options = cairo_font_options_create();
  cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
  cairo_font_options_set_antialias(options, CAIRO_ANTIALIAS_GRAY);
  cairo_set_font_options(cr_, options);
  cairo_font_options_destroy(options);
  cairo_set_antialias(cr_, CAIRO_ANTIALIAS_DEFAULT);
  cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
}

Canvas::~Canvas() {
  if (cr_ != nullptr) cairo_destroy(cr_);
  if (surface_ != nullptr) cairo_surface_destroy(surface_);
}

void Canvas::SetColor(const Color& color, double alpha) {
  cairo_set_source_rgba(cr_, color.r, color.g, color.b, alpha);
}

void Canvas::SelectFont(const Font& font) {
  cairo_select_font_face(cr_, kFontFamily,
                         font.italic ? CAIRO_FONT_SLANT_ITALIC : CAIRO_FONT_SLANT_NORMAL,
                         font.bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr_, font.size);
}

double Canvas::TextWidth(const std::string& text, const Font& font) {
  SelectFont(font);
  cairo_text_extents_t extents;
  cairo_text_extents(cr_, text.c_str(), &extents);
  return extents.x_advance;
}

double Canvas::LineHeight(const Font& font) {
  SelectFont(font);
  cairo_font_extents_t extents;
  cairo_font_extents(cr_, &extents);
  return extents.ascent + extents.descent;
}

void Canvas::Text(const std::string& text, double x, double y, const Font& font, const Color& color,
                  HAlign h_align, VAlign v_align, double angle_rad, bool halo) {
  if (text.empty()) return;
  SelectFont(font);
  cairo_font_extents_t font_extents;
  cairo_font_extents(cr_, &font_extents);
  cairo_text_extents_t extents;
  cairo_text_extents(cr_, text.c_str(), &extents);
  double dx = 0;
  if (h_align == HAlign::kCenter) dx = -extents.x_advance / 2;
  if (h_align == HAlign::kRight) dx = -extents.x_advance;
  // Vertical anchors use the font's ascent/descent, not the string's ink, so labels in a row
  // share one baseline whatever their letters.
  double dy = 0;
  if (v_align == VAlign::kTop) dy = font_extents.ascent;
  if (v_align == VAlign::kMiddle) dy = (font_extents.ascent - font_extents.descent) / 2;
  if (v_align == VAlign::kBottom) dy = -font_extents.descent;

  cairo_save(cr_);
  cairo_translate(cr_, x, y);
  cairo_rotate(cr_, angle_rad);
  cairo_move_to(cr_, dx, dy);
  if (halo) {
    cairo_text_path(cr_, text.c_str());
    cairo_set_source_rgb(cr_, 1, 1, 1);
    cairo_set_line_width(cr_, std::max(2.0, font.size / 4));
    cairo_stroke(cr_);
    cairo_move_to(cr_, dx, dy);
  }
  SetColor(color);
  cairo_show_text(cr_, text.c_str());
  cairo_restore(cr_);
}

std::string Canvas::Encode() {
  CheckStatus(cairo_status(cr_), "draw the chart");
  if (format_ == ImageFormat::kPng) {
    cairo_surface_flush(surface_);
    std::string png;
    CheckStatus(cairo_surface_write_to_png_stream(surface_, &AppendBytes, &png), "encode PNG");
    return png;
  }
  cairo_surface_finish(surface_);
  CheckStatus(cairo_surface_status(surface_), "encode SVG");
  return svg_bytes_;
}

double Crisp(double coordinate, double width_px) {
  const bool odd = static_cast<long>(std::lround(width_px)) % 2 == 1;
  return odd ? std::floor(coordinate) + 0.5 : std::round(coordinate);
}

}  // namespace recon::report
