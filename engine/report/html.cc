#include "engine/report/html.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>

namespace recon::report {

std::string EscapeHtml(std::string_view text) {
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string Base64(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  auto byte = [&](size_t i) { return static_cast<uint32_t>(static_cast<unsigned char>(bytes[i])); };
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const uint32_t n = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    for (const int shift : {18, 12, 6, 0}) out += kAlphabet[(n >> shift) & 63];
  }
  const size_t rest = bytes.size() - i;
  if (rest > 0) {
    const uint32_t n = byte(i) << 16 | (rest == 2 ? byte(i + 1) << 8 : 0);
    out += kAlphabet[(n >> 18) & 63];
    out += kAlphabet[(n >> 12) & 63];
    out += rest == 2 ? kAlphabet[(n >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string PngDataUri(std::string_view png_bytes) {
  return "data:image/png;base64," + Base64(png_bytes);
}

std::string HtmlTable(const std::vector<std::string>& headers,
                      const std::vector<std::vector<std::string>>& rows,
                      const std::set<size_t>& numeric) {
  auto open = [&](const char* tag, size_t column) {
    return std::string("<") + tag + (numeric.count(column) ? " class=\"num\">" : ">");
  };
  std::string out = "<table>\n<thead><tr>";
  for (size_t c = 0; c < headers.size(); ++c)
    out += open("th", c) + EscapeHtml(headers[c]) + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (size_t c = 0; c < row.size(); ++c) out += open("td", c) + row[c] + "</td>";
    out += "</tr>\n";
  }
  return out + "</tbody>\n</table>\n";
}

std::string FormatFixed(double value, int decimals) {
  if (!std::isfinite(value)) return "n/a";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

std::string FormatNumber(double value) {
  if (!std::isfinite(value)) return "n/a";
  const double magnitude = std::abs(value);
  // Counts (collisions, steps) read better without decimals that are always zero.
  if (value == std::round(value) && magnitude < 1e15) return FormatFixed(value, 0);
  if (magnitude < 1e-4) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.2e", value);
    return buffer;
  }
  const int exponent = static_cast<int>(std::floor(std::log10(magnitude)));
  return FormatFixed(value, std::clamp(2 - exponent, 0, 6));
}

std::string CssColor(const Color& color) {
  auto channel = [](double c) {
    return static_cast<int>(std::lround(std::clamp(c, 0.0, 1.0) * 255));
  };
  char css[16];
  std::snprintf(css, sizeof css, "#%02x%02x%02x", channel(color.r), channel(color.g),
                channel(color.b));
  return css;
}

}  // namespace recon::report
