#include "devices/camera/opencv_io.h"

#include "engine/core/loadable_module.h"

#ifndef RECON_OPENCV_IO_MODULE_PATH
#error "RECON_OPENCV_IO_MODULE_PATH must name the built module (devices/camera/CMakeLists.txt)"
#endif

namespace recon::camera {

namespace {

const OpenCvIo* Load() {
  const LoadableModule module = {ModulePath("RECON_OPENCV_IO_MODULE", RECON_OPENCV_IO_MODULE_PATH),
                                 kOpenCvIoEntry, "the OpenCV I/O module",
                                 "cameras and image files need it"};
  return static_cast<const OpenCvIo*>(LoadModuleTable(module, kOpenCvIoInterface));
}

LazyModuleTable<OpenCvIo> opencv_io(&Load);

}  // namespace

const OpenCvIo& LoadOpenCvIo() { return opencv_io.Get(); }

}  // namespace recon::camera
