#include "app/studio/device_scanner.h"

#include <exception>
#include <utility>

namespace recon::studio {

DeviceScanner::DeviceScanner(discovery::DiscoveryOptions options, std::chrono::milliseconds period)
    : options_([&] {
        options.probe = false;  // opening a port the studio is streaming from would steal it
        return std::move(options);
      }()),
      period_(period),
      thread_([this] { Run(); }) {}

DeviceScanner::~DeviceScanner() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void DeviceScanner::RescanNow() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    rescan_ = true;
  }
  wake_.notify_all();
}

std::vector<ui::ConnectedDeviceView> DeviceScanner::Latest(uint64_t* scans) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (scans != nullptr) *scans = scans_;
  return latest_;
}

std::string DeviceScanner::Where() const {
  std::string where = options_.dev_dir;
  for (const std::string& host : options_.robot_hosts) where += ", " + host;
  return where;
}

void DeviceScanner::Run() {
  while (true) {
    std::vector<ui::ConnectedDeviceView> found;
    try {
      for (const discovery::FoundDevice& d : discovery::DiscoverDevices(options_)) {
        found.push_back(
            {discovery::DeviceKindName(d.kind), d.path, d.identity, d.usable, d.detail});
      }
    } catch (const std::exception& e) {
      // The folder itself is unreadable: say so in the list rather than end the thread.
      found = {{"", options_.dev_dir, "", false, e.what()}};
    }
    std::unique_lock<std::mutex> lock(mutex_);
    latest_ = std::move(found);
    ++scans_;
    wake_.wait_for(lock, period_, [this] { return stop_ || rescan_; });
    if (stop_) return;
    rescan_ = false;
  }
}

}  // namespace recon::studio
