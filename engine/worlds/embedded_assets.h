#pragma once

#include <string>
#include <vector>

namespace recon::worlds {

/// One file of assets/ compiled into the program (see cmake/EmbedAssets.cmake).
struct EmbeddedAsset {
  const char* path;      ///< relative to assets/, e.g. "mjcf/tabletop.xml"
  const char* contents;  ///< the file's text
};

/// Every embedded asset, in the order CMake listed them.
const std::vector<EmbeddedAsset>& EmbeddedAssets();

}  // namespace recon::worlds
