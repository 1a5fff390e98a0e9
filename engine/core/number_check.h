#pragma once

// One check for every number a person types: a command-line option (app/cli/option_checks) or
// a line of a studio script (ui/testing/ui_script). The whole text must be a finite number in
// range, whole where asked; NaN, infinity, "3x", "" and overflow are refused, and the range is
// said in plain numbers.

#include <string>

namespace recon {

/// "" if `text` is a number from `min` to `max` (above `min` when `min_exclusive`; an integer
/// when `whole`), else what is wrong: "must be a whole number from 0 to 100000 (got '-5')".
/// `max` may be infinity ("must be a number >= 0").
std::string CheckNumber(const std::string& text, double min, double max, bool whole,
                        bool min_exclusive);

}  // namespace recon
