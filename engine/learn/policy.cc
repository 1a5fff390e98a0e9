#include "engine/learn/policy.h"

#include <algorithm>

#include "engine/core/error.h"
#include "engine/learn/policy_impl.h"

namespace recon::learn {

namespace {

constexpr int kMaxChunk = 256;  // bounds the activation buffers of a large ActBatch

void CheckSize(const std::vector<float>& v, int64_t expected, const char* name, size_t row) {
  if (static_cast<int64_t>(v.size()) != expected) {
    throw UserError(std::string("policy input ") + name + " (row " + std::to_string(row) +
                    ") has " + std::to_string(v.size()) + " values, expected " +
                    std::to_string(expected));
  }
}

}  // namespace

PolicyImpl::PolicyImpl(Architecture arch, const std::vector<float>& params, TargetScaling scaling)
    : arch_(std::move(arch)), params_(params.begin(), params.end()), scaling_(std::move(scaling)) {}

std::vector<std::vector<float>> PolicyImpl::Run(Output output,
                                                const std::vector<std::vector<float>>& xs,
                                                const std::vector<std::vector<float>>& ys,
                                                std::vector<float>* gates) {
  if (xs.size() != ys.size()) {
    throw UserError("policy input: " + std::to_string(xs.size()) + " x rows but " +
                    std::to_string(ys.size()) + " y rows");
  }
  for (size_t i = 0; i < xs.size(); ++i) {
    CheckSize(xs[i], arch_.spec.x_dim, "x", i);
    CheckSize(ys[i], arch_.spec.YSize(), "y", i);
  }
  std::vector<std::vector<float>> result(xs.size());
  if (gates != nullptr) gates->assign(xs.size(), 1.0f);
  if (output == Output::kBeacon && !arch_.has_beacon_net()) return result;
  std::lock_guard<std::mutex> lock(mutex_);
  for (size_t begin = 0; begin < xs.size(); begin += kMaxChunk) {
    const int count = static_cast<int>(std::min<size_t>(kMaxChunk, xs.size() - begin));
    RunChunk(output, xs, ys, begin, count, result, gates);
  }
  return result;
}

void PolicyImpl::RunChunk(Output output, const std::vector<std::vector<float>>& xs,
                          const std::vector<std::vector<float>>& ys, size_t begin, int count,
                          std::vector<std::vector<float>>& result, std::vector<float>* gates) {
  if (buffers_.batch != count) buffers_.Resize(arch_, count);
  const int x_dim = arch_.spec.x_dim;
  const int64_t y_size = arch_.spec.YSize();
  const float scale = arch_.image() ? arch_.network.image_scale : 1.0f;
  images_.resize(static_cast<size_t>(count) * y_size);
  for (int b = 0; b < count; ++b) {
    std::copy_n(xs[begin + b].data(), x_dim, buffers_.x.data() + static_cast<size_t>(b) * x_dim);
    float* y = images_.data() + static_cast<size_t>(b) * y_size;
    const std::vector<float>& source = ys[begin + b];
    for (int64_t i = 0; i < y_size; ++i) y[i] = source[i] * scale;
    if (scaling_.ScalesInputs()) {
      scaling_.ApplyToInputs(buffers_.x.data() + static_cast<size_t>(b) * x_dim, y);
    }
    buffers_.y[b] = y;
  }
  // Inference-only use of the training passes: no gradients are computed.
  ForwardFeatures(arch_, params_.data(), buffers_);
  const float* rows = buffers_.phi();
  int stride = arch_.feature_dim(), width = arch_.feature_dim();
  if (output == Output::kAction || output == Output::kActionChunk) {
    ForwardPolicy(arch_, params_.data(), buffers_);
    // The head holds the means of the whole chunk, then their log-variances.
    stride = 2 * arch_.action_width();
    width = output == Output::kActionChunk ? arch_.action_width() : arch_.spec.u_dim;
    scaling_.RestoreActions(buffers_.mutable_policy_head(), count, stride, width);
    rows = buffers_.policy_head();
    if (gates != nullptr && arch_.has_gate()) {
      std::copy_n(buffers_.gate_value.data(), count, gates->data() + begin);
    }
  } else if (output == Output::kGate) {
    if (!arch_.has_gate()) {
      for (int b = 0; b < count; ++b) result[begin + b] = {1.0f};
      return;
    }
    ForwardPolicy(arch_, params_.data(), buffers_);
    rows = buffers_.gate_value.data();
    width = stride = 1;
  } else if (output == Output::kBeacon) {
    ForwardBeacon(arch_, params_.data(), buffers_);
    width = arch_.spec.b_dim;
    stride = 2 * width;
    scaling_.RestoreBeacons(buffers_.beacon.out.back().data(), count, stride);
    rows = buffers_.beacon_head();
  }
  for (int b = 0; b < count; ++b) {
    const float* row = rows + static_cast<size_t>(b) * stride;
    result[begin + b].assign(row, row + width);
  }
}

std::vector<std::vector<float>> PolicyImpl::ActionImageJacobian(const std::vector<float>& x,
                                                                const std::vector<float>& y) {
  if (!arch_.image()) throw UserError("the policy reads no camera image: it has no saliency");
  CheckSize(x, arch_.spec.x_dim, "x", 0);
  CheckSize(y, arch_.spec.YSize(), "y", 0);
  std::lock_guard<std::mutex> lock(mutex_);
  // One row per action component, the same observation in each: one backward pass gives every
  // component's gradient at once.
  const int u_dim = arch_.spec.u_dim, x_dim = arch_.spec.x_dim;
  const int64_t y_size = arch_.spec.YSize();
  const float image_scale = arch_.network.image_scale;
  if (buffers_.batch != u_dim) buffers_.Resize(arch_, u_dim);
  images_.resize(static_cast<size_t>(u_dim) * y_size);
  for (int b = 0; b < u_dim; ++b) {
    float* row_x = buffers_.x.data() + static_cast<size_t>(b) * x_dim;
    std::copy_n(x.data(), x_dim, row_x);
    float* row_y = images_.data() + static_cast<size_t>(b) * y_size;
    for (int64_t i = 0; i < y_size; ++i) row_y[i] = y[i] * image_scale;
    if (scaling_.ScalesInputs()) scaling_.ApplyToInputs(row_x, row_y);
    buffers_.y[b] = row_y;
  }
  ForwardFeatures(arch_, params_.data(), buffers_);
  ForwardPolicy(arch_, params_.data(), buffers_);
  // Row b asks for component b of the first action's mean, in the user's units (the head's
  // mean times its scale). With a feature gate the acting head is g * seeing + (1 - g) * blind;
  // only the seeing branch reads the image, and g reads x alone.
  const int head = 2 * arch_.action_width();
  std::vector<float> grad_head(static_cast<size_t>(u_dim) * head, 0.0f);
  for (int b = 0; b < u_dim; ++b) {
    const float gate = arch_.has_gate() ? buffers_.gate_value[static_cast<size_t>(b)] : 1.0f;
    grad_head[static_cast<size_t>(b) * head + b] = scaling_.u_scale[static_cast<size_t>(b)] * gate;
  }
  if (arch_.has_gate()) std::fill(buffers_.grad_gate.begin(), buffers_.grad_gate.end(), 0.0f);
  AlignedFloats grads(params_.size(), 0.0f);  // the weights' gradients, not wanted here
  AlignedFloats grad_images(static_cast<size_t>(u_dim) * y_size, 0.0f);
  Backward(arch_, params_.data(), grad_head.data(), nullptr, buffers_, grads.data(), nullptr,
           nullptr, grad_images.data());
  std::vector<std::vector<float>> jacobian(static_cast<size_t>(u_dim));
  for (int b = 0; b < u_dim; ++b) {
    const float* row = grad_images.data() + static_cast<size_t>(b) * y_size;
    jacobian[static_cast<size_t>(b)].resize(static_cast<size_t>(y_size));
    // The CNN read y * image_scale.
    for (int64_t i = 0; i < y_size; ++i) jacobian[static_cast<size_t>(b)][i] = row[i] * image_scale;
  }
  return jacobian;
}

Policy::Policy() = default;
Policy::Policy(std::shared_ptr<PolicyImpl> impl) : impl_(std::move(impl)) {}
Policy::~Policy() = default;
Policy::Policy(const Policy&) = default;
Policy& Policy::operator=(const Policy&) = default;

namespace {

PolicyImpl& Require(const std::shared_ptr<PolicyImpl>& impl) {
  if (!impl) throw UserError("the policy is empty: train a model or load a checkpoint first");
  return *impl;
}

// One kind of output of `first` and the ensemble's `others`, averaged row by row (gates too).
std::vector<std::vector<float>> RunAveraged(const std::shared_ptr<PolicyImpl>& first,
                                            const std::vector<std::shared_ptr<PolicyImpl>>& others,
                                            PolicyImpl::Output kind,
                                            const std::vector<std::vector<float>>& xs,
                                            const std::vector<std::vector<float>>& ys,
                                            std::vector<float>* gates = nullptr) {
  std::vector<std::vector<float>> sum = Require(first).Run(kind, xs, ys, gates);
  if (others.empty()) return sum;
  std::vector<float> member_gates;
  for (const std::shared_ptr<PolicyImpl>& member : others) {
    const std::vector<std::vector<float>> rows =
        member->Run(kind, xs, ys, gates != nullptr ? &member_gates : nullptr);
    for (size_t r = 0; r < sum.size(); ++r) {
      for (size_t j = 0; j < sum[r].size(); ++j) sum[r][j] += rows[r][j];
    }
    if (gates != nullptr) {
      for (size_t r = 0; r < gates->size(); ++r) (*gates)[r] += member_gates[r];
    }
  }
  const float scale = 1.0f / static_cast<float>(1 + others.size());
  for (std::vector<float>& row : sum) {
    for (float& v : row) v *= scale;
  }
  if (gates != nullptr) {
    for (float& g : *gates) g *= scale;
  }
  return sum;
}

}  // namespace

Policy Policy::Ensemble(const std::vector<Policy>& members) {
  if (members.empty()) throw UserError("a policy ensemble needs at least one member");
  Policy ensemble(members.front().impl_);  // the first member's own members are added below
  const Architecture& first = Require(ensemble.impl_).arch();
  for (size_t i = 0; i < members.size(); ++i) {
    const Policy& member = members[i];
    if (i > 0) ensemble.others_.push_back(member.impl_);
    ensemble.others_.insert(ensemble.others_.end(), member.others_.begin(), member.others_.end());
    const Architecture& a = Require(member.impl_).arch();
    if (!(a.spec == first.spec) || a.network.action_chunk != first.network.action_chunk ||
        a.network.ensembled_actions != first.network.ensembled_actions) {
      throw UserError("policy ensemble: member " + std::to_string(i) +
                      " differs from the first in its data shapes, action chunk or ensembled "
                      "actions");
    }
  }
  return ensemble;
}

int Policy::ensemble_size() const { return 1 + static_cast<int>(others_.size()); }

const DataSpec& Policy::spec() const { return Require(impl_).arch().spec; }

std::vector<float> Policy::Act(const std::vector<float>& x, const std::vector<float>& y) const {
  return RunAveraged(impl_, others_, PolicyImpl::Output::kAction, {x}, {y}).front();
}

std::vector<std::vector<float>> Policy::ActBatch(const std::vector<std::vector<float>>& xs,
                                                 const std::vector<std::vector<float>>& ys,
                                                 std::vector<float>* gates) const {
  return RunAveraged(impl_, others_, PolicyImpl::Output::kAction, xs, ys, gates);
}

int Policy::action_chunk() const { return Require(impl_).arch().network.action_chunk; }

const std::vector<int>& Policy::ensembled_actions() const {
  return Require(impl_).arch().network.ensembled_actions;
}

std::vector<std::vector<float>> Policy::ActChunkBatch(const std::vector<std::vector<float>>& xs,
                                                      const std::vector<std::vector<float>>& ys,
                                                      std::vector<float>* gates) const {
  return RunAveraged(impl_, others_, PolicyImpl::Output::kActionChunk, xs, ys, gates);
}

bool Policy::has_feature_gate() const { return Require(impl_).arch().has_gate(); }

float Policy::FeatureGate(const std::vector<float>& x, const std::vector<float>& y) const {
  return RunAveraged(impl_, others_, PolicyImpl::Output::kGate, {x}, {y}).front().front();
}

std::vector<float> Policy::PredictBeacon(const std::vector<float>& x,
                                         const std::vector<float>& y) const {
  return Require(impl_).Run(PolicyImpl::Output::kBeacon, {x}, {y}).front();
}

std::vector<float> Policy::Features(const std::vector<float>& x,
                                    const std::vector<float>& y) const {
  return Require(impl_).Run(PolicyImpl::Output::kFeatures, {x}, {y}).front();
}

std::vector<std::vector<float>> Policy::FeaturesBatch(
    const std::vector<std::vector<float>>& xs, const std::vector<std::vector<float>>& ys) const {
  return Require(impl_).Run(PolicyImpl::Output::kFeatures, xs, ys);
}

std::vector<std::vector<float>> Policy::ActionImageJacobian(const std::vector<float>& x,
                                                            const std::vector<float>& y) const {
  std::vector<std::vector<float>> sum = Require(impl_).ActionImageJacobian(x, y);
  if (others_.empty()) return sum;
  // The ensemble acts on its members' mean action: its gradient is their gradients' mean.
  for (const std::shared_ptr<PolicyImpl>& member : others_) {
    const std::vector<std::vector<float>> jacobian = member->ActionImageJacobian(x, y);
    for (size_t j = 0; j < sum.size(); ++j) {
      for (size_t i = 0; i < sum[j].size(); ++i) sum[j][i] += jacobian[j][i];
    }
  }
  const float members = static_cast<float>(others_.size() + 1);
  for (std::vector<float>& row : sum) {
    for (float& v : row) v /= members;
  }
  return sum;
}

}  // namespace recon::learn
