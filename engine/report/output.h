#pragma once

#include <string>

#include "engine/report/canvas.h"

namespace recon::report {

/// The image format named by the path's extension (.png or .svg, any case). Throws UserError
/// naming the path for anything else.
ImageFormat FormatFromPath(const std::string& path);

}  // namespace recon::report
