#include "engine/core/digest.h"

#include <cstdio>

namespace recon {

std::string DigestHex(uint64_t hash) {
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

}  // namespace recon
