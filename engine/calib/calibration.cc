#include "engine/calib/calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::calib {

namespace {

using nlohmann::json;
constexpr int kFormatVersion = 1;

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Nearest-rank percentile (p in (0, 100]).
double Percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t rank = static_cast<size_t>(std::ceil(p / 100.0 * static_cast<double>(v.size())));
  return v[std::clamp<size_t>(rank, 1, v.size()) - 1];
}

RigidTransform FitOn(const std::vector<CalibrationPoint>& points, const std::vector<bool>& use,
                     FitDimension dimension) {
  std::vector<Eigen::Vector3d> from, to;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!use[i]) continue;
    from.push_back(points[i].uwb_m);
    to.push_back(points[i].tag_m);
  }
  return FitRigid(from, to, dimension);
}

void ComputeResiduals(CalibrationReport& r) {
  r.residual_m.clear();
  r.residual_norm_m.clear();
  for (const CalibrationPoint& p : r.points) {
    Eigen::Vector3d d = r.transform.Apply(p.uwb_m) - p.tag_m;
    if (r.options.dimension == FitDimension::k2D) d.z() = 0.0;
    r.residual_m.push_back(d);
    r.residual_norm_m.push_back(d.norm());
  }
}

json Vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

Eigen::Vector3d ReadVec(const json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 3) throw UserError(where + " must be a list of 3 numbers");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) throw UserError(where + " must be a list of 3 numbers");
    v[i] = j[i].get<double>();
  }
  return v;
}

const json& Field(const json& j, const std::string& name, const std::string& where) {
  if (!j.is_object() || !j.contains(name))
    throw UserError(where + ": missing field '" + name + "'");
  return j.at(name);
}

}  // namespace

CalibrationReport Calibrate(const std::vector<CalibrationPoint>& points,
                            const CalibrationOptions& options) {
  CalibrationReport r;
  r.options = options;
  r.points = points;
  std::vector<bool> use(points.size(), true);
  r.transform = FitOn(points, use, options.dimension);
  ComputeResiduals(r);

  // Robust outlier test on the first fit, then one refit on the inliers: a single bad point
  // (a beacon moved while the tag was read) must not drag the transform.
  const double median = Median(r.residual_norm_m);
  std::vector<double> deviations;
  for (double e : r.residual_norm_m) deviations.push_back(std::abs(e - median));
  const double robust_sigma = 1.4826 * Median(deviations);
  const double limit =
      std::max(options.pass_rmse_m, median + options.outlier_sigmas * robust_sigma);
  r.outlier.assign(points.size(), false);
  int outliers = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    if (r.residual_norm_m[i] > limit) {
      r.outlier[i] = true;
      use[i] = false;
      ++outliers;
    }
  }
  const size_t needed = options.dimension == FitDimension::k2D ? 2 : 3;
  if (outliers > 0 && points.size() - outliers >= needed) {
    r.transform = FitOn(points, use, options.dimension);
    ComputeResiduals(r);
  }

  std::vector<double> inlier_norms;
  double sum_sq = 0.0, sum = 0.0;
  r.bias_m.setZero();
  for (size_t i = 0; i < points.size(); ++i) {
    if (r.outlier[i]) continue;
    inlier_norms.push_back(r.residual_norm_m[i]);
    sum += r.residual_norm_m[i];
    sum_sq += r.residual_norm_m[i] * r.residual_norm_m[i];
    r.bias_m += r.residual_m[i];
  }
  r.num_inliers = static_cast<int>(inlier_norms.size());
  const double n = std::max(1, r.num_inliers);
  r.rmse_m = std::sqrt(sum_sq / n);
  r.mean_m = sum / n;
  r.median_m = Median(inlier_norms);
  r.p95_m = Percentile(inlier_norms, 95.0);
  r.bias_m /= n;
  const double outlier_fraction =
      static_cast<double>(outliers) / static_cast<double>(points.size());
  r.passed = r.rmse_m <= options.pass_rmse_m && outlier_fraction <= options.max_outlier_fraction;
  return r;
}

std::string CalibrationReport::Summary() const {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(4);
  s << "fit " << (options.dimension == FitDimension::k2D ? "2-D" : "3-D") << ", " << points.size()
    << " points, " << (points.size() - num_inliers) << " outliers\n";
  s << "translation " << transform.translation.x() << " " << transform.translation.y() << " "
    << transform.translation.z() << " m, yaw " << transform.YawRad() * 180.0 / M_PI << " deg\n";
  s << "RMSE " << rmse_m << " m\n";
  s << "mean " << mean_m << " m, median " << median_m << " m, 95th percentile " << p95_m << " m\n";
  s << "bias x " << bias_m.x() << " y " << bias_m.y() << " z " << bias_m.z() << " m\n";
  s << (passed ? "PASS" : "FAIL") << " (threshold " << options.pass_rmse_m << " m RMSE)\n";
  return s.str();
}

void SaveCalibration(const CalibrationReport& r, const std::string& path) {
  json points = json::array();
  for (size_t i = 0; i < r.points.size(); ++i) {
    points.push_back({{"tag_m", Vec(r.points[i].tag_m)},
                      {"uwb_m", Vec(r.points[i].uwb_m)},
                      {"residual_m", Vec(r.residual_m[i])},
                      {"outlier", static_cast<bool>(r.outlier[i])}});
  }
  json rotation = json::array();
  for (int i = 0; i < 3; ++i) rotation.push_back(Vec(r.transform.rotation.row(i).transpose()));
  const json j = {
      {"version", kFormatVersion},
      {"dimension", r.options.dimension == FitDimension::k2D ? "2d" : "3d"},
      {"transform", {{"rotation", rotation}, {"translation_m", Vec(r.transform.translation)}}},
      {"options",
       {{"pass_rmse_m", r.options.pass_rmse_m},
        {"outlier_sigmas", r.options.outlier_sigmas},
        {"max_outlier_fraction", r.options.max_outlier_fraction}}},
      {"statistics",
       {{"rmse_m", r.rmse_m},
        {"mean_m", r.mean_m},
        {"median_m", r.median_m},
        {"p95_m", r.p95_m},
        {"bias_m", Vec(r.bias_m)},
        {"inliers", r.num_inliers},
        {"passed", r.passed}}},
      {"points", points}};
  WriteFileAtomically(path, j.dump(2) + "\n");
}

CalibrationReport LoadCalibration(const std::string& path) {
  const std::optional<std::string> text = ReadWholeFile(path);
  if (!text) throw UserError("cannot read calibration " + path);
  json j;
  try {
    j = json::parse(*text);
  } catch (const json::exception& e) {
    throw UserError("calibration " + path + " is not valid JSON: " + e.what());
  }
  const std::string where = "calibration " + path;
  try {
    const json& version = Field(j, "version", where);
    if (!version.is_number_integer()) throw UserError(where + ": 'version' must be an integer");
    if (version.get<int>() > kFormatVersion) {
      throw UserError(where + " has version " + std::to_string(version.get<int>()) +
                      ", newer than this program understands (" + std::to_string(kFormatVersion) +
                      ")");
    }
    const std::string dimension = Field(j, "dimension", where).get<std::string>();
    if (dimension != "2d" && dimension != "3d") {
      throw UserError(where + ": 'dimension' must be \"2d\" or \"3d\"");
    }
    CalibrationOptions options;
    options.dimension = dimension == "2d" ? FitDimension::k2D : FitDimension::k3D;
    const json& o = Field(j, "options", where);
    options.pass_rmse_m = Field(o, "pass_rmse_m", where + ": options").get<double>();
    options.outlier_sigmas = Field(o, "outlier_sigmas", where + ": options").get<double>();
    options.max_outlier_fraction =
        Field(o, "max_outlier_fraction", where + ": options").get<double>();
    std::vector<CalibrationPoint> points;
    const json& list = Field(j, "points", where);
    if (!list.is_array()) throw UserError(where + ": 'points' must be a list");
    for (size_t i = 0; i < list.size(); ++i) {
      const std::string at = where + ": points[" + std::to_string(i) + "]";
      points.push_back({ReadVec(Field(list[i], "tag_m", at), at + ".tag_m"),
                        ReadVec(Field(list[i], "uwb_m", at), at + ".uwb_m")});
    }
    // Refit from the stored points: the file cannot hold a transform that disagrees with them.
    CalibrationReport r = Calibrate(points, options);
    const json& t = Field(j, "transform", where);
    const Eigen::Vector3d stored = ReadVec(Field(t, "translation_m", where + ": transform"),
                                           where + ": transform.translation_m");
    if ((stored - r.transform.translation).norm() > 1e-6) {
      throw UserError(where + ": 'transform' does not match its points (edited by hand?)");
    }
    return r;
  } catch (const json::exception& e) {
    throw UserError(where + ": a field has the wrong type (" + e.what() + ")");
  }
}

}  // namespace recon::calib
