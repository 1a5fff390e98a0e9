#include "engine/calib/rigid_fit.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/error.h"

namespace recon::calib {

namespace {

// Points closer together than this (metres) carry no orientation: UWB noise alone is ~0.1 m.
constexpr double kMinSpreadM = 1e-3;

void CheckFinite(const std::vector<Eigen::Vector3d>& points, const char* which) {
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw UserError(std::string("calibration point ") + std::to_string(i) + ": the " + which +
                      " position is not finite");
    }
  }
}

template <int D>
Eigen::Matrix<double, D, Eigen::Dynamic> Columns(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Matrix<double, D, Eigen::Dynamic> m(D, static_cast<Eigen::Index>(points.size()));
  for (size_t i = 0; i < points.size(); ++i)
    m.col(static_cast<Eigen::Index>(i)) = points[i].head<D>();
  return m;
}

template <int D>
void CheckSpread(const Eigen::Matrix<double, D, Eigen::Dynamic>& m, FitDimension dimension) {
  const Eigen::Matrix<double, D, Eigen::Dynamic> centred = m.colwise() - m.rowwise().mean();
  // The centred points' singular values, largest first, as the square roots of the eigenvalues
  // of their D x D scatter matrix: the same numbers as a JacobiSVD of the D x n matrix, whose
  // instantiation alone took this file 60 s to compile.
  const Eigen::Matrix<double, D, D> scatter = centred * centred.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>> eigen(scatter,
                                                                         Eigen::EigenvaluesOnly);
  Eigen::Matrix<double, D, 1> s;
  for (int i = 0; i < D; ++i) s(i) = std::sqrt(std::max(0.0, eigen.eigenvalues()(D - 1 - i)));
  const double scale = std::sqrt(static_cast<double>(m.cols()));
  if (s(0) / scale < kMinSpreadM) {
    throw UserError("calibration points all lie in one place: move the beacon between points");
  }
  if (dimension == FitDimension::k3D && s(1) / scale < kMinSpreadM) {
    throw UserError("calibration points lie on one line: a 3-D fit needs points off that line");
  }
}

}  // namespace

double RigidTransform::YawRad() const { return std::atan2(rotation(1, 0), rotation(0, 0)); }

RigidTransform FitRigid(const std::vector<Eigen::Vector3d>& from,
                        const std::vector<Eigen::Vector3d>& to, FitDimension dimension) {
  if (from.size() != to.size()) {
    throw UserError("calibration: " + std::to_string(from.size()) + " UWB points but " +
                    std::to_string(to.size()) + " tag points");
  }
  const size_t needed = dimension == FitDimension::k2D ? 2 : 3;
  if (from.size() < needed) {
    throw UserError("calibration needs at least " + std::to_string(needed) + " points for a " +
                    (dimension == FitDimension::k2D ? "2-D" : "3-D") + " fit, got " +
                    std::to_string(from.size()));
  }
  CheckFinite(from, "UWB");
  CheckFinite(to, "tag");

  RigidTransform t;
  if (dimension == FitDimension::k2D) {
    const Eigen::Matrix2Xd src = Columns<2>(from), dst = Columns<2>(to);
    CheckSpread<2>(src, dimension);
    // The planar least-squares rotation has a closed form: the angle that best aligns the
    // centred point pairs, atan2(sum of cross products, sum of dot products). It is always a
    // proper rotation, so no reflection case arises.
    const Eigen::Vector2d src_mean = src.rowwise().mean(), dst_mean = dst.rowwise().mean();
    double cross = 0.0, dot = 0.0;
    for (Eigen::Index i = 0; i < src.cols(); ++i) {
      const Eigen::Vector2d a = src.col(i) - src_mean, b = dst.col(i) - dst_mean;
      cross += a.x() * b.y() - a.y() * b.x();
      dot += a.dot(b);
    }
    const double yaw = std::atan2(cross, dot);
    t.rotation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    t.translation.head<2>() = dst_mean - t.rotation.topLeftCorner<2, 2>() * src_mean;
    double dz = 0.0;
    for (size_t i = 0; i < from.size(); ++i) dz += to[i].z() - from[i].z();
    t.translation.z() = dz / static_cast<double>(from.size());
  } else {
    const Eigen::Matrix3Xd src = Columns<3>(from), dst = Columns<3>(to);
    CheckSpread<3>(src, dimension);
    const Eigen::Matrix4d h = Eigen::umeyama(src, dst, /*with_scaling=*/false);
    t.rotation = h.topLeftCorner<3, 3>();
    t.translation = h.topRightCorner<3, 1>();
  }
  return t;
}

}  // namespace recon::calib
