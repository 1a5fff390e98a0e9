#pragma once

#include <cstddef>

namespace recon::ui {

/// The studio's font (DejaVu Sans, assets/fonts/DejaVuSans.ttf, licence beside it), compiled
/// into the program so that text looks the same on every machine and in every golden image.
struct StudioFontData {
  const unsigned char* data;
  size_t size;
};
StudioFontData StudioFont();

}  // namespace recon::ui
