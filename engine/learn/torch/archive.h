#pragma once

// Inside the Torch module: reading and writing PyTorch archives (archive.cc).

#include <memory>
#include <string>

#include "engine/learn/torch_module.h"

namespace recon::learn {

std::unique_ptr<ArchiveReader> OpenTorchArchive(const std::string& path);
std::unique_ptr<ArchiveWriter> NewTorchArchive();

}  // namespace recon::learn
