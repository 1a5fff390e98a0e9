#include "engine/learn/beacon_filter.h"

#include <algorithm>

namespace recon::learn {

void SmoothBeaconRows(std::vector<float>& b, int dim, const std::vector<int32_t>& group,
                      int half_window) {
  if (half_window <= 0 || dim <= 0) return;
  const int64_t rows = static_cast<int64_t>(group.size());
  // Prefix sums over all rows, in double, taken before any row is rewritten: a window (clipped
  // to its group below) then costs one subtraction per value however long it is.
  std::vector<double> prefix(static_cast<size_t>((rows + 1) * dim), 0.0);
  for (int64_t r = 0; r < rows; ++r) {
    for (int k = 0; k < dim; ++k) prefix[(r + 1) * dim + k] = prefix[r * dim + k] + b[r * dim + k];
  }
  int64_t begin = 0;
  while (begin < rows) {
    int64_t end = begin + 1;
    while (end < rows && group[end] == group[begin]) ++end;
    for (int64_t r = begin; r < end; ++r) {
      const int64_t lo = std::max(begin, r - half_window);
      const int64_t hi = std::min(end, r + half_window + 1);
      for (int k = 0; k < dim; ++k) {
        const double sum = prefix[hi * dim + k] - prefix[lo * dim + k];
        b[r * dim + k] = static_cast<float>(sum / static_cast<double>(hi - lo));
      }
    }
    begin = end;
  }
}

std::vector<int32_t> GroupsOfChunks(int64_t rows, const std::vector<int>& chunk_sizes) {
  std::vector<int32_t> group(static_cast<size_t>(rows));
  if (chunk_sizes.empty()) {
    for (int64_t r = 0; r < rows; ++r) group[r] = static_cast<int32_t>(r);
    return group;
  }
  int64_t row = 0;
  int32_t id = 0;
  for (int size : chunk_sizes) {
    for (int i = 0; i < size && row < rows; ++i) group[row++] = id;
    ++id;
  }
  // Rows past the chunks (a caller's mistake, refused by ValidateDataset) stand alone.
  while (row < rows) group[row++] = id++;
  return group;
}

}  // namespace recon::learn
