#include "engine/report/output.h"

#include <algorithm>
#include <cctype>

#include "engine/core/error.h"

namespace recon::report {

ImageFormat FormatFromPath(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  std::string extension;
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) {
    extension = path.substr(dot + 1);
  }
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (extension == "png") return ImageFormat::kPng;
  if (extension == "svg") return ImageFormat::kSvg;
  throw UserError("cannot write chart '" + path + "': the extension must be .png or .svg");
}

}  // namespace recon::report
