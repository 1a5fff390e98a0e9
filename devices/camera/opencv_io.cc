#include "devices/camera/opencv_io.h"

#include <atomic>
#include <mutex>

#include "engine/core/loadable_module.h"

#ifndef RECON_OPENCV_IO_MODULE_PATH
#error "RECON_OPENCV_IO_MODULE_PATH must name the built module (devices/camera/CMakeLists.txt)"
#endif

namespace recon::camera {

namespace {

std::mutex load_mutex;
std::atomic<const OpenCvIo*> loaded{nullptr};

const OpenCvIo* Load() {
  const LoadableModule module = {ModulePath("RECON_OPENCV_IO_MODULE", RECON_OPENCV_IO_MODULE_PATH),
                                 kOpenCvIoEntry, "the OpenCV I/O module",
                                 "cameras and image files need it"};
  return static_cast<const OpenCvIo*>(LoadModuleTable(module, kOpenCvIoInterface));
}

}  // namespace

const OpenCvIo& LoadOpenCvIo() {
  if (const OpenCvIo* module = loaded.load(std::memory_order_acquire)) return *module;
  const std::lock_guard<std::mutex> lock(load_mutex);
  if (loaded.load() == nullptr) loaded.store(Load(), std::memory_order_release);
  return *loaded.load();
}

}  // namespace recon::camera
