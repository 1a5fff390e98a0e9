#pragma once

// A part of the program kept in a shared module that is loaded (dlopen) the first time it is
// needed, because linking it would cost every process its start-up: LibTorch
// (engine/learn/torch_module.h) and OpenCV's video and image-file libraries
// (devices/camera/opencv_io.h). A module exports one extern "C" function returning a table of
// what it offers, whose first member is the table's interface version.

#include <atomic>
#include <mutex>
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

/// A module's table, loaded by `load` (which calls LoadModuleTable) on the first Get() of any
/// thread, once.
template <typename Table>
class LazyModuleTable {
 public:
  using Loader = const Table* (*)();
  explicit constexpr LazyModuleTable(Loader load) : load_(load) {}

  const Table& Get() {
    if (const Table* table = table_.load(std::memory_order_acquire)) return *table;
    const std::lock_guard<std::mutex> lock(mutex_);
    if (table_.load() == nullptr) table_.store(load_(), std::memory_order_release);
    return *table_.load();
  }

  /// Runs f(table) if the table is loaded, never during a load: a setting changed before this
  /// call is either read by a load in progress or applied here once it has finished.
  template <typename F>
  void IfLoaded(F f) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const Table* table = table_.load()) f(*table);
  }

 private:
  const Loader load_;
  std::mutex mutex_;
  std::atomic<const Table*> table_{nullptr};
};

}  // namespace recon
