#include "devices/camera/opencv_io.h"

#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <mutex>

#include "engine/core/error.h"

#ifndef RECON_OPENCV_IO_MODULE_PATH
#error "RECON_OPENCV_IO_MODULE_PATH must name the built module (devices/camera/CMakeLists.txt)"
#endif

namespace recon::camera {

namespace {

using ModuleEntry = const OpenCvIo* (*)();

std::mutex load_mutex;
std::atomic<const OpenCvIo*> loaded{nullptr};

const OpenCvIo* Load() {
  const char* override_path = std::getenv("RECON_OPENCV_IO_MODULE");
  const std::string path = override_path != nullptr && override_path[0] != '\0'
                               ? override_path
                               : RECON_OPENCV_IO_MODULE_PATH;
  const std::string why = "cameras and image files need it; ./scripts/build builds it";
  // Never closed: OpenCV's backends keep static state for the life of the process.
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* error = dlerror();
    throw UserError("cannot load the OpenCV I/O module " + path + " (" +
                    (error != nullptr ? error : "unknown error") + "): " + why);
  }
  const auto entry = reinterpret_cast<ModuleEntry>(dlsym(handle, kOpenCvIoEntry));
  const OpenCvIo* module = entry != nullptr ? entry() : nullptr;
  if (module == nullptr || module->interface_version != kOpenCvIoInterface) {
    throw UserError("the OpenCV I/O module " + path +
                    " was built for another version of recon: " + why);
  }
  return module;
}

}  // namespace

const OpenCvIo& LoadOpenCvIo() {
  if (const OpenCvIo* module = loaded.load(std::memory_order_acquire)) return *module;
  const std::lock_guard<std::mutex> lock(load_mutex);
  if (loaded.load() == nullptr) loaded.store(Load(), std::memory_order_release);
  return *loaded.load();
}

}  // namespace recon::camera
