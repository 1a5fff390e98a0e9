#pragma once

// A part of the program kept in a shared module that is loaded (dlopen) the first time it is
// needed, because linking it would cost every process its start-up: LibTorch
// (engine/learn/torch_module.h) and OpenCV's video and image-file libraries
// (devices/camera/opencv_io.h). A module exports one extern "C" function returning a table of
// what it offers, whose first member is the table's interface version.

#include <string>

namespace recon {

/// Where a module is and how to name it in errors.
struct LoadableModule {
  std::string path;         ///< what dlopen opens
  std::string entry;        ///< the exported function returning the table
  std::string description;  ///< e.g. "the Torch module"
  std::string needed_by;    ///< e.g. "checkpoints and the Torch backend need it"
};

/// $`environment_variable` when it is set and not empty, else `built_path`.
std::string ModulePath(const char* environment_variable, const char* built_path);

/// Opens `module` (never closed: what it registers must outlive the process's last use of it)
/// and returns its entry function's table. UserError naming the path when the file cannot be
/// loaded, has no entry, or its table's version is not `interface_version`.
const void* LoadModuleTable(const LoadableModule& module, int interface_version);

}  // namespace recon
