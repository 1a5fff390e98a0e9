#pragma once

#include <cstdio>
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

/// A number as a person would type it in an error message: "0.07", "1e+03", "nan".
inline std::string FormatNumber(double value) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%g", value);
  return buf;
}

}  // namespace recon
