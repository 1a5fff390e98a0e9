// Inside the Torch module: PyTorch archives (torch::serialize), as checkpoints store them.

#include "engine/learn/torch/archive.h"

#include <torch/serialize/input-archive.h>
#include <torch/serialize/output-archive.h>

#include <ATen/ATen.h>

#include <memory>
#include <mutex>
#include <sstream>

#include "engine/core/error.h"

namespace recon::learn {

namespace {

// TorchScript's archives (torch::serialize wraps torch::jit::load and save) share process-wide
// state that is not safe to use from two threads at once: TSan saw two methods' checkpoints,
// read at once by the parallel evaluation of a session's methods, race inside LibTorch, and
// concurrent torch.jit.load calls are known to corrupt its registry. So every use of an
// archive, its construction and destruction included, holds this one lock; a checkpoint is
// read or written in milliseconds, next to minutes of training.
std::mutex& ArchiveMutex() {
  static std::mutex mutex;
  return mutex;
}

class TorchArchiveReader final : public ArchiveReader {
 public:
  explicit TorchArchiveReader(const std::string& path) {
    const std::lock_guard<std::mutex> lock(ArchiveMutex());
    archive_ = std::make_unique<torch::serialize::InputArchive>();
    archive_->load_from(path);
  }
  ~TorchArchiveReader() override {
    const std::lock_guard<std::mutex> lock(ArchiveMutex());
    archive_.reset();
  }

  bool TryReadString(const std::string& key, std::string& text) override {
    const std::lock_guard<std::mutex> lock(ArchiveMutex());
    c10::IValue value;
    if (!archive_->try_read(key, value) || !value.isString()) return false;
    text = value.toStringRef();
    return true;
  }

  std::vector<float> ReadFloatTensor(const std::string& key) override {
    const std::lock_guard<std::mutex> lock(ArchiveMutex());
    at::Tensor tensor;
    archive_->read(key, tensor);
    if (tensor.scalar_type() != at::kFloat || tensor.dim() != 1) {
      throw UserError("tensor '" + key + "' is not a 1-D float tensor");
    }
    const at::Tensor t = tensor.contiguous();
    const float* data = t.data_ptr<float>();
    return std::vector<float>(data, data + t.numel());
  }

 private:
  std::unique_ptr<torch::serialize::InputArchive> archive_;
};

class TorchArchiveWriter final : public ArchiveWriter {
 public:
  TorchArchiveWriter() {
    const std::lock_guard<std::mutex> lock(ArchiveMutex());
    archive_ = std::make_unique<torch::serialize::OutputArchive>();
  }
  ~TorchArchiveWriter() override {
    const std::lock_guard<std::mutex> lock(ArchiveMutex());
    archive_.reset();
  }

  void WriteString(const std::string& key, const std::string& text) override {
    const std::lock_guard<std::mutex> lock(ArchiveMutex());
    archive_->write(key, c10::IValue(text));
  }

  void WriteFloatTensor(const std::string& key, const std::vector<float>& values) override {
    const std::lock_guard<std::mutex> lock(ArchiveMutex());
    archive_->write(key, at::from_blob(const_cast<float*>(values.data()),
                                       {static_cast<int64_t>(values.size())}, at::kFloat)
                             .clone());
  }

  std::string Bytes() override {
    const std::lock_guard<std::mutex> lock(ArchiveMutex());
    std::ostringstream bytes;
    archive_->save_to(bytes);
    return bytes.str();
  }

 private:
  std::unique_ptr<torch::serialize::OutputArchive> archive_;
};

}  // namespace

std::unique_ptr<ArchiveReader> OpenTorchArchive(const std::string& path) {
  return std::make_unique<TorchArchiveReader>(path);
}

std::unique_ptr<ArchiveWriter> NewTorchArchive() { return std::make_unique<TorchArchiveWriter>(); }

}  // namespace recon::learn
