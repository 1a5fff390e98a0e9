#pragma once

// The physically possible values of recorded data: a joint angle of 1e6 rad or a beacon 5 km
// from the arm is finite, but no robot recorded it. A world states its bounds (PhysicalBounds in
// engine/worlds); the store checks every sample it writes or reads against them, so a damaged
// or hand-edited file is refused naming the sample, the field and the dimension, instead of
// being trained on.

#include <string>
#include <vector>

namespace recon {

/// What one dimension of a field may hold, inclusive, and what it is (for messages).
struct ValueRange {
  double lo = 0;
  double hi = 0;
  std::string what;  ///< "joint 2 angle (rad)"
};

/// Per field, one range per dimension; an empty field is not checked (beyond being finite).
struct ValueBounds {
  std::vector<ValueRange> x, y, b, u;
  bool empty() const { return x.empty() && y.empty() && b.empty() && u.empty(); }
};

/// "" when every value lies in its range (or `ranges` is empty), else what is wrong:
/// "field 'x' dimension 2 (joint 2 angle (rad)) is 1000000, outside the physical range
/// -6.2832 to 6.2832". `values` must have one entry per range when `ranges` is not empty.
std::string OutOfBounds(const std::vector<ValueRange>& ranges, const std::vector<float>& values,
                        const char* field);

}  // namespace recon
