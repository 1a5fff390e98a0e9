#include "engine/probe/linear_readout.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <string>

#include "engine/core/error.h"

namespace recon::probe {

ReadoutScore FitLinearReadout(const std::vector<std::vector<float>>& features,
                              const std::vector<std::vector<double>>& targets, int fold,
                              double ridge) {
  if (features.size() != targets.size()) {
    throw UserError("a read-out needs one target per frame: " + std::to_string(features.size()) +
                    " frames, " + std::to_string(targets.size()) + " targets");
  }
  if (fold < 2) throw UserError("a read-out holds out one frame in at least 2");
  const size_t n = features.size();
  const size_t k = n == 0 ? 0 : features[0].size(), d = n == 0 ? 0 : targets[0].size();
  if (k == 0 || d == 0) throw UserError("a read-out needs features and a target");
  for (size_t i = 0; i < n; ++i) {
    if (features[i].size() != k || targets[i].size() != d) {
      throw UserError("read-out frame " + std::to_string(i) + " has " +
                      std::to_string(features[i].size()) + " features and " +
                      std::to_string(targets[i].size()) + " target values, not " +
                      std::to_string(k) + " and " + std::to_string(d));
    }
  }
  std::vector<size_t> fit, held;
  for (size_t i = 0; i < n; ++i) (i % static_cast<size_t>(fold) == 0 ? held : fit).push_back(i);
  if (held.size() < 2 || fit.size() < 2) {
    throw UserError("a read-out needs at least 2 fitted and 2 held-out frames, got " +
                    std::to_string(n) + " frames");
  }
  const auto rows = [&](const std::vector<size_t>& index, Eigen::MatrixXd& x, Eigen::MatrixXd& y) {
    x.resize(static_cast<Eigen::Index>(index.size()), static_cast<Eigen::Index>(k));
    y.resize(static_cast<Eigen::Index>(index.size()), static_cast<Eigen::Index>(d));
    for (size_t r = 0; r < index.size(); ++r) {
      for (size_t c = 0; c < k; ++c) x(r, c) = features[index[r]][c];
      for (size_t c = 0; c < d; ++c) y(r, c) = targets[index[r]][c];
    }
  };
  Eigen::MatrixXd x_fit, y_fit, x_held, y_held;
  rows(fit, x_fit, y_fit);
  rows(held, x_held, y_held);
  // Standardised features (a constant one reads as 0), so the ridge penalty is unit-free.
  const Eigen::RowVectorXd mean = x_fit.colwise().mean();
  Eigen::RowVectorXd spread =
      ((x_fit.rowwise() - mean).array().square().colwise().mean()).sqrt().matrix();
  for (Eigen::Index c = 0; c < spread.size(); ++c) {
    if (!(spread(c) > 1e-12)) spread(c) = std::numeric_limits<double>::infinity();
  }
  const auto standardise = [&](const Eigen::MatrixXd& x) -> Eigen::MatrixXd {
    return ((x.rowwise() - mean).array().rowwise() / spread.array()).matrix();
  };
  const Eigen::MatrixXd a = standardise(x_fit);
  const Eigen::RowVectorXd target_mean = y_fit.colwise().mean();
  const Eigen::MatrixXd b = y_fit.rowwise() - target_mean;
  Eigen::MatrixXd normal = a.transpose() * a;
  normal.diagonal().array() += ridge * static_cast<double>(fit.size());
  const Eigen::MatrixXd weights = normal.ldlt().solve(a.transpose() * b);
  const Eigen::MatrixXd predicted = (standardise(x_held) * weights).rowwise() + target_mean;

  ReadoutScore score;
  score.fitted = static_cast<int>(fit.size());
  score.held_out = static_cast<int>(held.size());
  const Eigen::RowVectorXd held_mean = y_held.colwise().mean();
  double error_sum = 0, spread_sum = 0;
  for (Eigen::Index c = 0; c < static_cast<Eigen::Index>(d); ++c) {
    const double error = (y_held.col(c) - predicted.col(c)).squaredNorm();
    const double variance = (y_held.col(c).array() - held_mean(c)).square().sum();
    score.r2_per_dimension.push_back(variance > 0 ? 1.0 - error / variance : 0.0);
    error_sum += error;
    spread_sum += variance;
  }
  score.r2 = spread_sum > 0 ? 1.0 - error_sum / spread_sum : 0.0;
  return score;
}

}  // namespace recon::probe
