#include "engine/learn/conv_stack.h"

#include "engine/learn/kernels.h"

namespace recon::learn {

namespace {

int64_t RoundUp(int64_t n) { return (n + 15) / 16 * 16; }

int64_t PlaneSize(const ConvLayer& c) { return static_cast<int64_t>(c.in_h) * c.in_w; }

// Number of wide positions up to and including the last valid output.
int WidePositions(const ConvLayer& c) { return (c.out_h - 1) * c.in_w + c.out_w; }

const float* LayerInput(const std::vector<ConvLayer>& convs, const ConvStackBuffers& buffers,
                        const float* const* images, size_t layer, int b) {
  if (layer == 0) return images[b];
  const ConvLayer& c = convs[layer];
  return buffers.layers[layer - 1].pooled.data() + b * c.in_channels * PlaneSize(c);
}

}  // namespace

void ConvStackBuffers::Resize(const std::vector<ConvLayer>& convs, int batch_size) {
  batch = batch_size;
  layers.resize(convs.size());
  for (size_t i = 0; i < convs.size(); ++i) {
    const ConvLayer& c = convs[i];
    ConvBuffers& l = layers[i];
    const int kk = c.kernel * c.kernel;
    l.conv_stride = RoundUp(static_cast<int64_t>(c.out_h) * c.in_w);
    // Rounded up so that gradient rows start on a cache line.
    l.grad_front = RoundUp(static_cast<int64_t>(c.kernel - 1) * c.in_w + (c.kernel - 1));
    l.grad_stride = RoundUp(l.grad_front + PlaneSize(c));
    l.taps.clear();
    for (int ch = 0; ch < c.in_channels; ++ch) {
      for (int ky = 0; ky < c.kernel; ++ky) {
        for (int kx = 0; kx < c.kernel; ++kx) {
          l.taps.push_back(ch * PlaneSize(c) + ky * c.in_w + kx);
        }
      }
    }
    l.grad_taps.clear();
    for (int oc = 0; oc < c.out_channels; ++oc) {
      for (int ky = 0; ky < c.kernel; ++ky) {
        for (int kx = 0; kx < c.kernel; ++kx) {
          l.grad_taps.push_back(oc * l.grad_stride + l.grad_front - (ky * c.in_w + kx));
        }
      }
    }
    const int64_t planes = static_cast<int64_t>(batch) * c.out_channels;
    const int64_t pooled = planes * c.pool_h * c.pool_w;
    l.conv.assign(planes * l.conv_stride, 0.0f);
    l.pooled.assign(pooled, 0.0f);
    l.arg.assign(pooled, 0.0f);
    l.grad_pooled.assign(pooled, 0.0f);
    // The pads are zeroed here once and never written: the pooling backward pass writes only
    // the out_h * in_w positions of each plane.
    l.grad_conv.assign(planes * l.grad_stride, 0.0f);
    l.weight_t.assign(static_cast<size_t>(c.in_channels) * c.out_channels * kk, 0.0f);
  }
}

void ConvStackForward(const std::vector<ConvLayer>& convs, const float* params,
                      const float* const* images, ConvStackBuffers& buffers) {
  const kernels::KernelTable& k = kernels::Kernels();
  for (size_t i = 0; i < convs.size(); ++i) {
    const ConvLayer& c = convs[i];
    ConvBuffers& l = buffers.layers[i];
    const int taps = c.in_channels * c.kernel * c.kernel;
    for (int b = 0; b < buffers.batch; ++b) {
      kernels::GemmNNArgs g;
      g.m = c.out_channels;
      g.n = WidePositions(c);
      g.k = taps;
      g.a = params + c.weight;
      g.a_sm = taps;
      g.a_sk = 1;
      g.b = LayerInput(convs, buffers, images, i, b);
      g.b_off = l.taps.data();
      g.c = l.conv.data() + b * c.out_channels * l.conv_stride;
      g.ldc = l.conv_stride;
      g.bias_m = params + c.bias;
      k.gemm_nn(g);
    }
    kernels::PoolArgs p;
    p.planes = buffers.batch * c.out_channels;
    p.rows = c.out_h;
    p.width = c.in_w;
    p.out_h = c.pool_h;
    p.out_w = c.pool_w;
    p.in_stride = l.conv_stride;
    p.in = l.conv.data();
    p.out = l.pooled.data();
    p.arg = l.arg.data();
    k.pool_relu_forward(p);
  }
}

void ConvStackBackward(const std::vector<ConvLayer>& convs, const float* params,
                       const float* const* images, ConvStackBuffers& buffers, float* grads,
                       float* grad_images) {
  const kernels::KernelTable& k = kernels::Kernels();
  for (size_t i = convs.size(); i-- > 0;) {
    const ConvLayer& c = convs[i];
    ConvBuffers& l = buffers.layers[i];
    const int kk = c.kernel * c.kernel;
    const int taps = c.in_channels * kk;

    kernels::PoolBackwardArgs p;
    p.planes = buffers.batch * c.out_channels;
    p.rows = c.out_h;
    p.width = c.in_w;
    p.out_h = c.pool_h;
    p.out_w = c.pool_w;
    p.grad_out = l.grad_pooled.data();
    p.out = l.pooled.data();
    p.arg = l.arg.data();
    p.grad_in = l.grad_conv.data() + l.grad_front;
    p.grad_in_stride = l.grad_stride;
    k.pool_relu_backward(p);

    for (int b = 0; b < buffers.batch; ++b) {
      const float* grad_planes = l.grad_conv.data() + b * c.out_channels * l.grad_stride;
      k.add_row_sums(grad_planes + l.grad_front, c.out_channels, c.out_h * c.in_w, l.grad_stride,
                     grads + c.bias);
      kernels::GemmNTArgs w;
      w.m = c.out_channels;
      w.k = taps;
      w.n = WidePositions(c);
      w.a = grad_planes + l.grad_front;
      w.lda = l.grad_stride;
      w.b = LayerInput(convs, buffers, images, i, b);
      w.b_off = l.taps.data();
      w.c = grads + c.weight;
      w.c_sm = taps;
      w.c_sk = 1;
      w.accumulate = true;
      k.gemm_nt(w);
    }
    if (i == 0 && grad_images == nullptr) continue;  // training needs none for the images

    const float* weight = params + c.weight;
    for (int ic = 0; ic < c.in_channels; ++ic) {
      for (int oc = 0; oc < c.out_channels; ++oc) {
        for (int t = 0; t < kk; ++t) {
          l.weight_t[(static_cast<size_t>(ic) * c.out_channels + oc) * kk + t] =
              weight[(static_cast<size_t>(oc) * c.in_channels + ic) * kk + t];
        }
      }
    }
    // The block's input: the previous block's output, or the images themselves.
    float* grad_input = i == 0 ? grad_images : buffers.layers[i - 1].grad_pooled.data();
    for (int b = 0; b < buffers.batch; ++b) {
      kernels::GemmNNArgs g;
      g.m = c.in_channels;
      g.n = static_cast<int>(PlaneSize(c));
      g.k = c.out_channels * kk;
      g.a = l.weight_t.data();
      g.a_sm = c.out_channels * kk;
      g.a_sk = 1;
      g.b = l.grad_conv.data() + b * c.out_channels * l.grad_stride;
      g.b_off = l.grad_taps.data();
      g.c = grad_input + b * c.in_channels * PlaneSize(c);
      g.ldc = PlaneSize(c);
      k.gemm_nn(g);
    }
  }
}

}  // namespace recon::learn
