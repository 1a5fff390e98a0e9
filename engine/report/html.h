#pragma once

#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "engine/report/chart.h"

namespace recon::report {

// Building blocks for HTML reports: escaping, embedded images, tables and the number formats
// their cells use.

/// `text` made safe to place in HTML element content or a quoted attribute value: the five
/// characters with a meaning in markup (& < > " ') become character references.
std::string EscapeHtml(std::string_view text);

/// Standard base64 (RFC 4648, with padding) of `bytes`, for data: URIs.
std::string Base64(std::string_view bytes);

/// A data: URI that embeds PNG bytes, so the page needs no file next to it.
std::string PngDataUri(std::string_view png_bytes);

/// A table with escaped `headers`; `rows` hold HTML (escape text before passing it). Columns
/// listed in `numeric` are right-aligned with tabular digits (class "num").
std::string HtmlTable(const std::vector<std::string>& headers,
                      const std::vector<std::vector<std::string>>& rows,
                      const std::set<size_t>& numeric = {});

/// `value` with `decimals` digits after the point; "n/a" for NaN and infinities.
std::string FormatFixed(double value, int decimals);

/// About three significant digits and no exponent in the usual range (1e-4 and up), so columns
/// of losses and metrics read alike; whole numbers without decimals; "n/a" for NaN and
/// infinities.
std::string FormatNumber(double value);

/// "#rrggbb" for CSS.
std::string CssColor(const Color& color);

}  // namespace recon::report
