#pragma once

// LibTorch is loaded when first needed. Every use of it (checkpoint archives, the Torch
// backend's step, Torch's thread count) lives in one shared module, librecon_torch.so
// (engine/learn/torch/), which the learner opens with dlopen the first time a checkpoint is
// read or written or a run trains on Backend::kTorch. Mapping and initialising LibTorch costs a
// process about 1.5 s, so a command that needs none of it (--help, a refused option, recording,
// the studio until it trains or loads a model) no longer pays it. Internal to the learner.
//
// The interface is C++: the module is built by the same build with the same compiler and
// standard library, and the loader refuses a module of another interface version
// (engine/core/loadable_module.h).

#include <memory>
#include <string>
#include <vector>

#include "engine/learn/torch_step.h"

namespace recon::learn {

/// A PyTorch archive being read: string entries and 1-D float tensor entries.
class ArchiveReader {
 public:
  virtual ~ArchiveReader() = default;
  /// The string entry `key`; false when it is missing or not a string.
  virtual bool TryReadString(const std::string& key, std::string& text) = 0;
  /// The tensor entry `key`'s values. UserError when it is not a 1-D float tensor; Torch's own
  /// error (a std::exception) when it is missing.
  virtual std::vector<float> ReadFloatTensor(const std::string& key) = 0;
};

/// A PyTorch archive being built in memory.
class ArchiveWriter {
 public:
  virtual ~ArchiveWriter() = default;
  virtual void WriteString(const std::string& key, const std::string& text) = 0;
  virtual void WriteFloatTensor(const std::string& key, const std::vector<float>& values) = 0;
  /// The archive's bytes (a zip file, as torch.save writes).
  virtual std::string Bytes() = 0;
};

/// What the module offers. Errors are thrown (UserError for what the user gave, Torch's own
/// std::exception for a file it cannot read).
struct TorchModule {
  int interface_version = 0;
  /// The archive at `path` (reads the whole file; Torch's error when it is not an archive).
  std::unique_ptr<ArchiveReader> (*open_archive)(const std::string& path) = nullptr;
  std::unique_ptr<ArchiveWriter> (*new_archive)() = nullptr;
  std::unique_ptr<TorchStep> (*new_step)(const TorchStepSetup& setup) = nullptr;
  void (*set_threads)(int threads) = nullptr;
};

/// The interface version this learner was built against; bumped with every change of the above.
constexpr int kTorchModuleInterface = 1;
/// The one symbol the module exports: extern "C" const TorchModule* ReconTorchModule().
constexpr char kTorchModuleEntry[] = "ReconTorchModule";

/// The module, loaded on first call (thread-safe). Its path is the one the build wrote it to,
/// or $RECON_TORCH_MODULE when set. UserError naming the path when it cannot be loaded.
const TorchModule& Torch();

}  // namespace recon::learn
