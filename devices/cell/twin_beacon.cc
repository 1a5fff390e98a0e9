#include "devices/cell/twin_beacon.h"

#include <utility>

#include "devices/uwb/fake_dwm1001.h"

namespace recon::cell {

TwinBeacon::TwinBeacon(const Eigen::Vector3d& table_m, TwinBeaconOptions options)
    : options_(std::move(options)), table_m_(table_m), noise_(options_.seed) {
  uwb::FakeDwm1001::Options fake;
  fake.period_ms = options_.period_ms;
  fake.node_id = options_.node_id;
  fake.next_reading = [this] {
    std::lock_guard lock(mutex_);
    const Eigen::Vector3d p = options_.table_to_uwb.Apply(table_m_);
    uwb::UwbReading r;
    r.has_position = !silent_;
    r.x_m = p.x() + noise_.Uniform(-options_.noise_m, options_.noise_m);
    r.y_m = p.y() + noise_.Uniform(-options_.noise_m, options_.noise_m);
    r.z_m = p.z();
    r.quality = 90;
    return r;
  };
  fake_ = std::make_unique<uwb::FakeDwm1001>(fake);
}

TwinBeacon::~TwinBeacon() { fake_.reset(); }

void TwinBeacon::MoveTo(const Eigen::Vector3d& table_m) {
  std::lock_guard lock(mutex_);
  table_m_ = table_m;
}

void TwinBeacon::Silence(bool silent) {
  std::lock_guard lock(mutex_);
  silent_ = silent;
}

const std::string& TwinBeacon::port() const { return fake_->port(); }

}  // namespace recon::cell
