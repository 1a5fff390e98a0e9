#include "devices/uwb/simulated_dwm1001.h"

#include <algorithm>
#include <stdexcept>

#include "devices/uwb/lec_format.h"
#include "devices/uwb/uwb_reading.h"

namespace recon::uwb {

SimulatedDwm1001::SimulatedDwm1001(SimulatedDwm1001Options options)
    : options_(std::move(options)), rng_(options_.seed) {
  if (options_.anchors_m.size() != options_.anchor_ids.size()) {
    throw std::invalid_argument("SimulatedDwm1001: one id per anchor");
  }
}

UwbReading SimulatedDwm1001::NextReading(const Eigen::Vector3d& table_position_m) {
  const Eigen::Vector3d true_uwb = options_.table_to_uwb.Apply(table_position_m);
  const double sigma = options_.position_noise_m;
  const Eigen::Vector3d estimate =
      true_uwb +
      Eigen::Vector3d(sigma * rng_.Normal(), sigma * rng_.Normal(), sigma * rng_.Normal());
  UwbReading reading;
  for (size_t a = 0; a < options_.anchors_m.size(); ++a) {
    const Eigen::Vector3d& anchor = options_.anchors_m[a];
    const double range = (anchor - true_uwb).norm() + options_.range_noise_m * rng_.Normal();
    reading.anchors.push_back({options_.anchor_ids[a], anchor.x(), anchor.y(), anchor.z(),
                               std::max(0.0, range)});  // the firmware reports unsigned ranges
  }
  reading.has_position = true;
  reading.x_m = estimate.x();
  reading.y_m = estimate.y();
  reading.z_m = estimate.z();
  reading.quality = 50 + static_cast<int>(rng_.UniformInt(51));
  return reading;
}

std::string SimulatedDwm1001::NextUpdate(const Eigen::Vector3d& table_position_m) {
  // Draw every random number of the update first, so the stream does not depend on which
  // failure happens (a dropped line costs the same draws as a good one).
  const UwbReading reading = NextReading(table_position_m);
  const double fate = rng_.Uniform();
  const uint64_t cut = rng_.Next();

  if (fate < options_.drop_probability) {
    ++dropped_;
    return "";
  }
  std::string line = FormatLecLine(reading);
  if (fate < options_.drop_probability + options_.garble_probability) {
    ++garbled_;
    // Half the time an echo fragment is glued in front (the parser resynchronises on it), half
    // the time the line is cut short (the parser must drop it).
    if (cut % 2 == 0) return "le" + line;
    return line.substr(0, 1 + (cut >> 1) % (line.size() - 3)) + "\r\n";
  }
  return line;
}

}  // namespace recon::uwb
