#include "ui/platform/studio_font.h"

// The TTF is placed in read-only data by the assembler (.incbin), avoiding a 760 KB generated
// C array; RECON_STUDIO_FONT is its absolute path, set by CMake.
asm(".section .rodata\n"
    ".balign 16\n"
    ".globl recon_studio_font_begin\n"
    ".hidden recon_studio_font_begin\n"
    ".globl recon_studio_font_end\n"
    ".hidden recon_studio_font_end\n"
    "recon_studio_font_begin:\n"
    ".incbin \"" RECON_STUDIO_FONT
    "\"\n"
    "recon_studio_font_end:\n"
    ".previous\n");

extern "C" const unsigned char recon_studio_font_begin[];
extern "C" const unsigned char recon_studio_font_end[];

namespace recon::ui {

StudioFontData StudioFont() {
  return {recon_studio_font_begin,
          static_cast<size_t>(recon_studio_font_end - recon_studio_font_begin)};
}

}  // namespace recon::ui
