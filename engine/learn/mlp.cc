#include "engine/learn/mlp.h"

#include <cmath>
#include <cstring>

#include "engine/learn/kernels.h"

namespace recon::learn {

namespace {

void Activate(Activation activation, float* values, int64_t count) {
  if (activation == Activation::kRelu) {
    // NaN passes through (as in PyTorch) so that it reaches the loss and is reported.
    for (int64_t i = 0; i < count; ++i) {
      values[i] = (values[i] > 0.0f || std::isnan(values[i])) ? values[i] : 0.0f;
    }
  } else if (activation == Activation::kTanh) {
    for (int64_t i = 0; i < count; ++i) values[i] = std::tanh(values[i]);
  }
}

// grad *= activation'(pre-activation), expressed through the stored output.
void ApplyActivationGrad(Activation activation, const float* out, float* grad, int64_t count) {
  if (activation == Activation::kRelu) {
    for (int64_t i = 0; i < count; ++i) grad[i] = out[i] > 0.0f ? grad[i] : 0.0f;
  } else if (activation == Activation::kTanh) {
    for (int64_t i = 0; i < count; ++i) grad[i] *= 1.0f - out[i] * out[i];
  }
}

}  // namespace

void MlpBuffers::Resize(const std::vector<LinearLayer>& layers, int batch_size) {
  batch = batch_size;
  out.resize(layers.size());
  grad.resize(layers.size());
  for (size_t i = 0; i < layers.size(); ++i) {
    out[i].assign(static_cast<size_t>(batch) * layers[i].out, 0.0f);
    grad[i].assign(static_cast<size_t>(batch) * layers[i].out, 0.0f);
  }
}

void MlpForward(const std::vector<LinearLayer>& layers, const float* params, const float* input,
                MlpBuffers& buffers) {
  const kernels::KernelTable& k = kernels::Kernels();
  const float* in = input;
  for (size_t i = 0; i < layers.size(); ++i) {
    const LinearLayer& layer = layers[i];
    kernels::GemmNTArgs g;
    g.m = buffers.batch;
    g.k = layer.out;
    g.n = layer.in;
    g.a = in;
    g.lda = layer.in;
    g.b = params + layer.weight;
    g.ldb = layer.in;
    g.c = buffers.out[i].data();
    g.c_sm = layer.out;
    g.c_sk = 1;
    g.bias_k = params + layer.bias;
    k.gemm_nt(g);
    Activate(layer.activation, buffers.out[i].data(),
             static_cast<int64_t>(buffers.batch) * layer.out);
    in = buffers.out[i].data();
  }
}

void MlpBackward(const std::vector<LinearLayer>& layers, const float* params, const float* input,
                 const float* grad_output, MlpBuffers& buffers, float* grads, float* grad_input) {
  const kernels::KernelTable& k = kernels::Kernels();
  const int batch = buffers.batch;
  std::memcpy(buffers.grad.back().data(), grad_output, sizeof(float) * batch * layers.back().out);
  for (size_t i = layers.size(); i-- > 0;) {
    const LinearLayer& layer = layers[i];
    float* g = buffers.grad[i].data();
    ApplyActivationGrad(layer.activation, buffers.out[i].data(), g,
                        static_cast<int64_t>(batch) * layer.out);
    const float* in = i == 0 ? input : buffers.out[i - 1].data();
    // Bias: column sums of g over the batch.
    float* grad_bias = grads + layer.bias;
    for (int b = 0; b < batch; ++b) {
      const float* row = g + static_cast<int64_t>(b) * layer.out;
      for (int o = 0; o < layer.out; ++o) grad_bias[o] += row[o];
    }
    // Weights: dW[o][j] += sum_b g[b][o] * in[b][j].
    kernels::GemmNNArgs w;
    w.m = layer.out;
    w.n = layer.in;
    w.k = batch;
    w.a = g;
    w.a_sm = 1;
    w.a_sk = layer.out;
    w.b = in;
    w.ldb = layer.in;
    w.c = grads + layer.weight;
    w.ldc = layer.in;
    w.accumulate = true;
    k.gemm_nn(w);
    // Input: d_in[b][j] = sum_o g[b][o] * W[o][j].
    float* d_in = i == 0 ? grad_input : buffers.grad[i - 1].data();
    if (d_in == nullptr) continue;
    kernels::GemmNNArgs x;
    x.m = batch;
    x.n = layer.in;
    x.k = layer.out;
    x.a = g;
    x.a_sm = layer.out;
    x.a_sk = 1;
    x.b = params + layer.weight;
    x.ldb = layer.in;
    x.c = d_in;
    x.ldc = layer.in;
    k.gemm_nn(x);
  }
}

}  // namespace recon::learn
