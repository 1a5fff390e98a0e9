#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "devices/discovery/device_discovery.h"
#include "ui/studio/studio_snapshot.h"

namespace recon::studio {

/// What is plugged in, for the Cell screen: `recon devices list` without opening anything
/// (DiscoverDevices with probe off), repeated every `period` on a thread of its own so that a slow
/// device folder or an unplug never stalls the cell thread. A device opened by the studio is not
/// disturbed: nothing is opened here.
class DeviceScanner {
 public:
  DeviceScanner(discovery::DiscoveryOptions options, std::chrono::milliseconds period);
  ~DeviceScanner();
  DeviceScanner(const DeviceScanner&) = delete;
  DeviceScanner& operator=(const DeviceScanner&) = delete;

  /// Scans now rather than at the end of the current period.
  void RescanNow();
  /// The latest list (empty before the first scan ends) and how many scans have ended.
  std::vector<ui::ConnectedDeviceView> Latest(uint64_t* scans = nullptr) const;
  /// Where it looks, for the screen: the device folder and the robot hosts.
  std::string Where() const;

 private:
  void Run();

  const discovery::DiscoveryOptions options_;
  const std::chrono::milliseconds period_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  bool rescan_ = false;
  uint64_t scans_ = 0;
  std::vector<ui::ConnectedDeviceView> latest_;
  std::thread thread_;  // last: starts after everything it reads is made
};

}  // namespace recon::studio
