// Checkpoints: one PyTorch archive (zip) per file holding the weights and Adam moments as
// tensors, and the configurations, data shape and trainer state as JSON strings. The archive
// itself is read and written by the Torch module (torch_module.h), loaded here on first use.

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>
#include <vector>

#include "engine/core/digest.h"
#include "engine/core/error.h"
#include "engine/core/files.h"
#include "engine/learn/config_json.h"
#include "engine/learn/learner.h"
#include "engine/learn/policy_impl.h"
#include "engine/learn/torch_module.h"
#include "engine/learn/trainer_impl.h"

namespace recon::learn {

namespace {

using nlohmann::json;

constexpr char kFormat[] = "recon-checkpoint/1";

struct CheckpointContents {
  NetworkConfig network;
  TrainConfig train;
  DataSpec spec;
  uint64_t fingerprint = 0;
  TrainerState state;
  std::vector<float> scaling;  ///< TargetScaling::Flatten()
};

json RngToJson(const Rng::State& s) {
  return {{"s", {s.s[0], s.s[1], s.s[2], s.s[3]}},
          {"has_spare_normal", s.has_spare_normal},
          {"spare_normal_bits", std::bit_cast<uint64_t>(s.spare_normal)}};
}

Rng::State RngFromJson(const json& j) {
  Rng::State s{};
  const json& words = j.at("s");
  if (!words.is_array() || words.size() != 4) throw UserError("generator state is invalid");
  for (int i = 0; i < 4; ++i) s.s[i] = words.at(i).get<uint64_t>();
  s.has_spare_normal = j.at("has_spare_normal").get<bool>();
  s.spare_normal = std::bit_cast<double>(j.at("spare_normal_bits").get<uint64_t>());
  return s;
}

std::string StateToJson(const TrainerState& s, uint64_t fingerprint) {
  json j;
  j["attempt"] = s.attempt;
  j["step"] = s.step;
  j["finished"] = s.finished;
  j["adam_step"] = s.adam_step;
  j["batch_rng"] = RngToJson(s.batch_rng);
  j["noise_rng"] = RngToJson(s.noise_rng);
  j["augment_rng"] = RngToJson(s.augment_rng);
  j["last"] = {{"attempt", s.last.attempt},         {"step", s.last.step},
               {"action_loss", s.last.action_loss}, {"beacon_loss", s.last.beacon_loss},
               {"play_loss", s.last.play_loss},     {"total_loss", s.last.total_loss},
               {"gate_mean", s.last.gate_mean},     {"consistency_loss", s.last.consistency_loss}};
  j["dataset_fingerprint"] = fingerprint;
  return j.dump();
}

void StateFromJson(const std::string& text, TrainerState& s, uint64_t& fingerprint) {
  try {
    const json j = json::parse(text);
    s.attempt = j.at("attempt").get<int>();
    s.step = j.at("step").get<int>();
    s.finished = j.at("finished").get<bool>();
    s.adam_step = j.at("adam_step").get<int64_t>();
    s.batch_rng = RngFromJson(j.at("batch_rng"));
    s.noise_rng = RngFromJson(j.at("noise_rng"));
    // Checkpoints from before augmentation: it was off, so the stream was never drawn from.
    if (j.contains("augment_rng")) s.augment_rng = RngFromJson(j.at("augment_rng"));
    const json& last = j.at("last");
    s.last.attempt = last.at("attempt").get<int>();
    s.last.step = last.at("step").get<int>();
    s.last.action_loss = last.at("action_loss").get<float>();
    s.last.beacon_loss = last.at("beacon_loss").get<float>();
    s.last.play_loss = last.at("play_loss").get<float>();
    s.last.total_loss = last.at("total_loss").get<float>();
    // States from before the feature gate: no gate, open.
    if (last.contains("gate_mean")) s.last.gate_mean = last.at("gate_mean").get<float>();
    // ... and before play consistency: no such term.
    if (last.contains("consistency_loss")) {
      s.last.consistency_loss = last.at("consistency_loss").get<float>();
    }
    fingerprint = j.at("dataset_fingerprint").get<uint64_t>();
  } catch (const json::exception& e) {
    throw UserError(std::string("trainer state is missing or invalid (") + e.what() + ")");
  }
}

// A model that diverged, or a file altered on disk, must not be rolled out as if it were fine.
std::vector<float> CheckedFinite(std::vector<float> values, const std::string& name) {
  for (size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw UserError("tensor '" + name + "' value " + std::to_string(i) + " of " +
                      std::to_string(values.size()) + " is " +
                      (std::isnan(values[i]) ? "NaN" : "infinite") +
                      ": the model diverged or the file was altered; train it again");
    }
  }
  return values;
}

std::string ReadString(ArchiveReader& archive, const char* key) {
  std::string text;
  if (!archive.TryReadString(key, text))
    throw UserError(std::string("entry '") + key + "' is missing");
  return text;
}

std::string FirstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

// FNV-1a (64 bits) of a byte range, as 16 hex digits: a digest of each entry, so that a flipped
// bit that leaves a weight finite (or a configuration parseable) is still found on reading.
std::string Digest(const void* bytes, size_t size) { return DigestHex(Fnv1a(bytes, size)); }
std::string Digest(const std::vector<float>& values) {
  return Digest(values.data(), values.size() * sizeof(float));
}
std::string Digest(const std::string& text) { return Digest(text.data(), text.size()); }

// The digests a checkpoint stores ("digests", a JSON object by entry name); checkpoints written
// before them have none, and read as before.
class Digests {
 public:
  explicit Digests(ArchiveReader& archive) {
    std::string text;
    if (archive.TryReadString("digests", text)) {
      try {
        stored_ = json::parse(text);
      } catch (const json::exception&) {
        throw UserError("entry 'digests' is damaged");
      }
    }
  }
  /// UserError when `contents` of `entry` do not match the digest stored for it.
  template <typename T>
  void Check(const char* entry, const T& contents) const {
    if (stored_.is_object() && stored_.contains(entry) &&
        stored_[entry] != json(Digest(contents))) {
      throw UserError(std::string("entry '") + entry +
                      "' is damaged (its contents do not match the digest written with them): "
                      "train it again");
    }
  }
  /// ReadString(archive, entry), checked.
  std::string CheckedString(ArchiveReader& archive, const char* entry) const {
    std::string text = ReadString(archive, entry);
    Check(entry, text);
    return text;
  }
  /// The 1-D float tensor `entry`, checked (FromTensor's checks first).
  std::vector<float> CheckedTensor(ArchiveReader& archive, const char* entry) const {
    std::vector<float> values = CheckedFinite(archive.ReadFloatTensor(entry), entry);
    Check(entry, values);
    return values;
  }

 private:
  json stored_;
};

// Reads and checks everything; `with_optimizer` = false drops the Adam moments (LoadPolicy).
CheckpointContents ReadCheckpoint(const std::string& path, bool with_optimizer) {
  RefuseNonRegularFile(path);
  if (!std::filesystem::is_regular_file(path)) {
    throw UserError("checkpoint '" + path + "' does not exist");
  }
  const TorchModule& torch = Torch();
  CheckpointContents c;
  try {
    const std::unique_ptr<ArchiveReader> reader = torch.open_archive(path);
    ArchiveReader& archive = *reader;
    if (ReadString(archive, "format") != kFormat) {
      throw UserError("not a RECON checkpoint (format is not " + std::string(kFormat) + ")");
    }
    const Digests digests(archive);
    c.network = NetworkConfigFromJson(digests.CheckedString(archive, "network"));
    c.train = TrainConfigFromJson(digests.CheckedString(archive, "train"));
    c.spec = DataSpecFromJson(digests.CheckedString(archive, "spec"));
    StateFromJson(digests.CheckedString(archive, "state"), c.state, c.fingerprint);
    c.state.params = digests.CheckedTensor(archive, "params");
    c.scaling = digests.CheckedTensor(archive, "target_scaling");
    // The moments are checked even for a policy that does not use them: a checkpoint with a
    // damaged entry is refused wherever it is read, not only once training resumes from it.
    std::vector<float> exp_avg = digests.CheckedTensor(archive, "exp_avg");
    std::vector<float> exp_avg_sq = digests.CheckedTensor(archive, "exp_avg_sq");
    if (with_optimizer) {
      c.state.exp_avg = std::move(exp_avg);
      c.state.exp_avg_sq = std::move(exp_avg_sq);
    }
  } catch (const UserError& e) {
    throw UserError("checkpoint '" + path + "': " + e.what());
  } catch (const std::exception& e) {
    throw UserError("checkpoint '" + path + "' is corrupt or not a RECON checkpoint (" +
                    FirstLine(e.what()) + ")");
  }
  return c;
}

}  // namespace

void Trainer::SaveCheckpoint(const std::string& path) const {
  const TrainerState s = impl_->State();
  // The archive is built in memory and written by WriteFileAtomically (temporary, fsync,
  // rename): Torch's own file writer aborts the process when the disk fills (its destructor
  // throws while an exception is in flight), and a crash must leave the old checkpoint or the
  // new one, never a half-written file or a temporary.
  const TorchModule& torch = Torch();
  std::string bytes;
  try {
    const std::unique_ptr<ArchiveWriter> archive = torch.new_archive();
    json digests;
    auto write_string = [&](const char* entry, const std::string& text) {
      archive->WriteString(entry, text);
      digests[entry] = Digest(text);
    };
    auto write_tensor = [&](const char* entry, const std::vector<float>& values) {
      archive->WriteFloatTensor(entry, values);
      digests[entry] = Digest(values);
    };
    archive->WriteString("format", kFormat);
    write_string("network", ToJson(impl_->network()));
    write_string("train", ToJson(impl_->train()));
    write_string("spec", ToJson(impl_->arch().spec));
    write_string("state", StateToJson(s, impl_->fingerprint()));
    write_tensor("params", s.params);
    write_tensor("target_scaling", impl_->scaling().Flatten());
    write_tensor("exp_avg", s.exp_avg);
    write_tensor("exp_avg_sq", s.exp_avg_sq);
    archive->WriteString("digests", digests.dump());
    bytes = archive->Bytes();
  } catch (const std::exception& e) {
    throw UserError("cannot write checkpoint '" + path + "': " + FirstLine(e.what()));
  }
  try {
    WriteFileAtomically(path, bytes);
  } catch (const UserError& e) {
    // "cannot write <path>: <reason>" becomes "cannot write checkpoint '<path>': <reason>".
    const std::string plain = "cannot write " + path + ": ", what = e.what();
    const std::string reason = what.rfind(plain, 0) == 0 ? what.substr(plain.size()) : what;
    throw UserError("cannot write checkpoint '" + path + "': " + reason);
  }
}

std::unique_ptr<Trainer> Trainer::Resume(const std::string& path, const Dataset& data,
                                         std::optional<Backend> backend) {
  CheckpointContents c = ReadCheckpoint(path, /*with_optimizer=*/true);
  // Both backends continue the same state, so switching is only a setting.
  if (backend.has_value()) c.train.backend = *backend;
  if (!(c.spec == data.spec)) {
    throw UserError("checkpoint '" + path + "' was trained on data shaped (" + c.spec.ToString() +
                    ") but this data is (" + data.spec.ToString() + ")");
  }
  std::unique_ptr<Trainer> trainer(new Trainer());
  trainer->impl_ = std::make_unique<TrainerImpl>(data, c.network, c.train);
  if (trainer->impl_->fingerprint() != c.fingerprint) {
    std::ostringstream msg;
    msg << "checkpoint '" << path << "' was trained on different data (dataset fingerprint "
        << std::hex << c.fingerprint << ", this data " << trainer->impl_->fingerprint()
        << "): resume with the dataset it was trained on";
    throw UserError(msg.str());
  }
  try {
    trainer->impl_->SetState(c.state);
  } catch (const UserError& e) {
    throw UserError("checkpoint '" + path + "': " + e.what());
  }
  return trainer;
}

Policy LoadPolicy(const std::string& checkpoint_path) {
  CheckpointContents c = ReadCheckpoint(checkpoint_path, /*with_optimizer=*/false);
  Architecture arch;
  TargetScaling scaling;
  try {
    arch = BuildArchitecture(c.spec, c.network, c.train.method);
    scaling = TargetScaling::Unflatten(c.spec, c.scaling);
  } catch (const UserError& e) {
    throw UserError("checkpoint '" + checkpoint_path + "': " + e.what());
  }
  if (static_cast<int64_t>(c.state.params.size()) != arch.num_params) {
    throw UserError("checkpoint '" + checkpoint_path + "' holds " +
                    std::to_string(c.state.params.size()) +
                    " parameters but its configuration describes " +
                    std::to_string(arch.num_params) + ": the architecture differs");
  }
  return Policy(std::make_shared<PolicyImpl>(std::move(arch), c.state.params, std::move(scaling)));
}

}  // namespace recon::learn
