// Inside the Torch module: PyTorch archives (torch::serialize), as checkpoints store them.

#include "engine/learn/torch/archive.h"

#include <torch/serialize/input-archive.h>
#include <torch/serialize/output-archive.h>

#include <ATen/ATen.h>

#include <sstream>

#include "engine/core/error.h"

namespace recon::learn {

namespace {

class TorchArchiveReader final : public ArchiveReader {
 public:
  explicit TorchArchiveReader(const std::string& path) { archive_.load_from(path); }

  bool TryReadString(const std::string& key, std::string& text) override {
    c10::IValue value;
    if (!archive_.try_read(key, value) || !value.isString()) return false;
    text = value.toStringRef();
    return true;
  }

  std::vector<float> ReadFloatTensor(const std::string& key) override {
    at::Tensor tensor;
    archive_.read(key, tensor);
    if (tensor.scalar_type() != at::kFloat || tensor.dim() != 1) {
      throw UserError("tensor '" + key + "' is not a 1-D float tensor");
    }
    const at::Tensor t = tensor.contiguous();
    const float* data = t.data_ptr<float>();
    return std::vector<float>(data, data + t.numel());
  }

 private:
  torch::serialize::InputArchive archive_;
};

class TorchArchiveWriter final : public ArchiveWriter {
 public:
  void WriteString(const std::string& key, const std::string& text) override {
    archive_.write(key, c10::IValue(text));
  }

  void WriteFloatTensor(const std::string& key, const std::vector<float>& values) override {
    archive_.write(key, at::from_blob(const_cast<float*>(values.data()),
                                      {static_cast<int64_t>(values.size())}, at::kFloat)
                            .clone());
  }

  std::string Bytes() override {
    std::ostringstream bytes;
    archive_.save_to(bytes);
    return bytes.str();
  }

 private:
  torch::serialize::OutputArchive archive_;
};

}  // namespace

std::unique_ptr<ArchiveReader> OpenTorchArchive(const std::string& path) {
  return std::make_unique<TorchArchiveReader>(path);
}

std::unique_ptr<ArchiveWriter> NewTorchArchive() { return std::make_unique<TorchArchiveWriter>(); }

}  // namespace recon::learn
