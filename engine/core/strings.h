#pragma once

#include <string>
#include <vector>

namespace recon {

/// "a, b, c": the list of valid names in error messages and help texts.
inline std::string JoinNames(const std::vector<std::string>& names,
                             const std::string& separator = ", ") {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : separator) + name;
  return out;
}

}  // namespace recon
