#include "engine/probe/linear_readout.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <utility>

#include "engine/core/error.h"

namespace recon::probe {

namespace {

using Rows = std::vector<std::vector<float>>;
using Targets = std::vector<std::vector<double>>;

/// The frames' sizes, checked: (features per frame, target values per frame).
std::pair<size_t, size_t> CheckFrames(const Rows& features, const Targets& targets,
                                      const std::vector<int>& groups) {
  if (features.size() != targets.size()) {
    throw UserError("a read-out needs one target per frame: " + std::to_string(features.size()) +
                    " frames, " + std::to_string(targets.size()) + " targets");
  }
  const size_t n = features.size();
  if (!groups.empty() && groups.size() != n) {
    throw UserError("a read-out needs one group per frame: " + std::to_string(n) + " frames, " +
                    std::to_string(groups.size()) + " groups");
  }
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
  return {k, d};
}

Eigen::MatrixXd RowsOf(const Rows& features, const std::vector<size_t>& index) {
  Eigen::MatrixXd x(static_cast<Eigen::Index>(index.size()),
                    static_cast<Eigen::Index>(features[0].size()));
  for (size_t r = 0; r < index.size(); ++r) {
    for (size_t c = 0; c < features[0].size(); ++c) x(r, c) = features[index[r]][c];
  }
  return x;
}

Eigen::MatrixXd RowsOf(const Targets& targets, const std::vector<size_t>& index) {
  Eigen::MatrixXd y(static_cast<Eigen::Index>(index.size()),
                    static_cast<Eigen::Index>(targets[0].size()));
  for (size_t r = 0; r < index.size(); ++r) {
    for (size_t c = 0; c < targets[0].size(); ++c) y(r, c) = targets[index[r]][c];
  }
  return y;
}

/// The targets of frames `predict` as the ridge read-out fitted on frames `fit` predicts them.
Eigen::MatrixXd FitAndPredict(const Rows& features, const Targets& targets,
                              const std::vector<size_t>& fit, const std::vector<size_t>& predict,
                              double ridge) {
  const Eigen::MatrixXd x_fit = RowsOf(features, fit), y_fit = RowsOf(targets, fit);
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
  return (standardise(RowsOf(features, predict)) * weights).rowwise() + target_mean;
}

/// R^2 of `predicted` against `truth`, about the truth's own mean, pooled over dimensions.
void Score(const Eigen::MatrixXd& truth, const Eigen::MatrixXd& predicted, ReadoutScore& score) {
  const Eigen::RowVectorXd truth_mean = truth.colwise().mean();
  double error_sum = 0, spread_sum = 0;
  for (Eigen::Index c = 0; c < truth.cols(); ++c) {
    const double error = (truth.col(c) - predicted.col(c)).squaredNorm();
    const double variance = (truth.col(c).array() - truth_mean(c)).square().sum();
    score.r2_per_dimension.push_back(variance > 0 ? 1.0 - error / variance : 0.0);
    error_sum += error;
    spread_sum += variance;
  }
  score.r2 = spread_sum > 0 ? 1.0 - error_sum / spread_sum : 0.0;
}

/// Ridge strengths a cross-validated read-out chooses from (CrossValidatedReadout, ridge 0).
constexpr double kRidges[] = {1e-3, 1e-2, 1e-1, 1.0, 10.0, 100.0};
constexpr size_t kInnerFolds = 3;

/// The ridge of kRidges whose read-out, fitted on frames `fit` less a third of their groups and
/// tried on that third (each third in turn), misses least. The smallest when the frames have
/// too few groups to choose on.
double ChooseRidge(const Rows& features, const Targets& targets, const std::vector<size_t>& fit,
                   const std::vector<int>& groups) {
  std::map<int, size_t> dense;  // the fitted frames' groups, numbered 0, 1, ...
  for (size_t i : fit) dense.emplace(groups.empty() ? static_cast<int>(i) : groups[i], 0);
  size_t next = 0;
  for (auto& [group, number] : dense) number = next++;
  if (dense.size() < kInnerFolds) return kRidges[0];
  double best_ridge = kRidges[0], best_error = std::numeric_limits<double>::infinity();
  for (double ridge : kRidges) {
    double error = 0;
    for (size_t k = 0; k < kInnerFolds; ++k) {
      std::vector<size_t> inner_fit, inner_held;
      for (size_t i : fit) {
        const size_t number = dense.at(groups.empty() ? static_cast<int>(i) : groups[i]);
        (number % kInnerFolds == k ? inner_held : inner_fit).push_back(i);
      }
      error += (RowsOf(targets, inner_held) -
                FitAndPredict(features, targets, inner_fit, inner_held, ridge))
                   .squaredNorm();
    }
    if (error < best_error) {
      best_error = error;
      best_ridge = ridge;
    }
  }
  return best_ridge;
}

}  // namespace

ReadoutScore FitLinearReadout(const Rows& features, const Targets& targets, int fold, double ridge,
                              const std::vector<int>& groups) {
  if (fold < 2) throw UserError("a read-out holds out one frame in at least 2");
  CheckFrames(features, targets, groups);
  const size_t n = features.size();
  std::vector<size_t> fit, held;
  for (size_t i = 0; i < n; ++i) {
    const size_t key = groups.empty() ? i : static_cast<size_t>(groups[i]);
    (key % static_cast<size_t>(fold) == 0 ? held : fit).push_back(i);
  }
  if (held.size() < 2 || fit.size() < 2) {
    throw UserError("a read-out needs at least 2 fitted and 2 held-out frames, got " +
                    std::to_string(n) + " frames");
  }
  ReadoutScore score;
  score.fitted = static_cast<int>(fit.size());
  score.held_out = static_cast<int>(held.size());
  Score(RowsOf(targets, held), FitAndPredict(features, targets, fit, held, ridge), score);
  return score;
}

ReadoutScore CrossValidatedReadout(const Rows& features, const Targets& targets,
                                   const std::vector<int>& groups, int folds, double ridge) {
  if (folds < 2) throw UserError("a cross-validated read-out needs at least 2 folds");
  CheckFrames(features, targets, groups);
  const size_t n = features.size();
  Eigen::MatrixXd predicted(static_cast<Eigen::Index>(n),
                            static_cast<Eigen::Index>(targets[0].size()));
  std::vector<size_t> all(n);
  for (size_t i = 0; i < n; ++i) all[i] = i;
  ReadoutScore score;
  for (int k = 0; k < folds; ++k) {
    std::vector<size_t> fit, held;
    for (size_t i = 0; i < n; ++i) {
      const size_t key = groups.empty() ? i : static_cast<size_t>(groups[i]);
      (key % static_cast<size_t>(folds) == static_cast<size_t>(k) ? held : fit).push_back(i);
    }
    if (held.empty()) continue;
    if (fit.size() < 2) {
      throw UserError("a cross-validated read-out needs at least 2 fitted frames per fold, got " +
                      std::to_string(fit.size()));
    }
    const double fold_ridge = ridge > 0 ? ridge : ChooseRidge(features, targets, fit, groups);
    const Eigen::MatrixXd fold_predicted = FitAndPredict(features, targets, fit, held, fold_ridge);
    for (size_t r = 0; r < held.size(); ++r) {
      predicted.row(static_cast<Eigen::Index>(held[r])) =
          fold_predicted.row(static_cast<Eigen::Index>(r));
    }
    score.fitted += static_cast<int>(fit.size());
  }
  score.fitted /= folds;  // per fold, on average
  score.held_out = static_cast<int>(n);
  Score(RowsOf(targets, all), predicted, score);
  return score;
}

}  // namespace recon::probe
