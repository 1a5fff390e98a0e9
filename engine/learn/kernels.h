#pragma once

// The numeric kernels the learner runs on: two small-matrix products, max-pool + ReLU and a fused
// Adam update, all on plain float buffers. They are compiled once per instruction set
// (kernels_generic.cc, kernels_avx2.cc, kernels_avx512.cc from one template, kernels_impl.h)
// and the best one the CPU supports is picked at start-up.
//
// Why not LibTorch's operators: for the authors' networks at batch 20 a training step is a few
// dozen tiny operations, and LibTorch spends more time dispatching, allocating and recording
// autograd nodes for them than computing (2.1-2.4 ms per step against about 0.5 ms here; see
// bench/learn_bench.cc). Convolutions run as matrix products whose "rows" are shifted views of
// the input plane, so no im2col copy is made.

#include <cstdint>
#include <string>
#include <vector>

namespace recon::learn::kernels {

/// C = [C] + [bias] + A * B with A (m x k) addressed by strides (A(i, l) = a[i * a_sm + l * a_sk])
/// and row l of B (length n) at b + b_off[l] (or b + l * ldb if b_off is null). C is row-major
/// with leading dimension ldc.
struct GemmNNArgs {
  int m = 0, n = 0, k = 0;
  const float* a = nullptr;
  int64_t a_sm = 0, a_sk = 0;
  const float* b = nullptr;
  const int64_t* b_off = nullptr;
  int64_t ldb = 0;
  float* c = nullptr;
  int64_t ldc = 0;
  const float* bias_m = nullptr;  ///< added to row i of C (length m), or null
  const float* bias_n = nullptr;  ///< added to column j of C (length n), or null
  bool accumulate = false;        ///< add to C instead of overwriting it
};

/// Dot-product form: C(i, l) = [C(i, l)] + [bias_k[l]] + sum_j A(i, j) * B_l(j), where row i of A
/// (length n) is at a + i * lda and row l of B at b + b_off[l] (or b + l * ldb if b_off is null);
/// C(i, l) = c[i * c_sm + l * c_sk].
struct GemmNTArgs {
  int m = 0, k = 0, n = 0;
  const float* a = nullptr;
  int64_t lda = 0;
  const float* b = nullptr;
  const int64_t* b_off = nullptr;
  int64_t ldb = 0;
  float* c = nullptr;
  int64_t c_sm = 0, c_sk = 0;
  const float* bias_k = nullptr;
  bool accumulate = false;
};

/// 2x2 max-pool (floor) followed by ReLU over `planes` planes of `rows` x `width` values (row
/// stride `width`, plane stride `in_stride`), of which the first `2 * out_w` columns and
/// `2 * out_h` rows are pooled. Output planes are compact (out_h x out_w); `arg` records which of
/// the four inputs won (0..3, row-major; stored as float so that it loads like the data), for
/// the backward pass.
struct PoolArgs {
  int planes = 0, rows = 0, width = 0, out_h = 0, out_w = 0;
  int64_t in_stride = 0;
  const float* in = nullptr;
  float* out = nullptr;
  float* arg = nullptr;
};

/// Backward of PoolArgs: writes the gradient of every input position of each plane (zero where
/// nothing was pooled, including the columns beyond 2 * out_w) from the gradient of the pooled
/// ReLU outputs. Reads `out` (the forward result) to apply the ReLU mask.
struct PoolBackwardArgs {
  int planes = 0, rows = 0, width = 0, out_h = 0, out_w = 0;
  const float* grad_out = nullptr;
  const float* out = nullptr;
  const float* arg = nullptr;
  float* grad_in = nullptr;
  int64_t grad_in_stride = 0;
};

/// One Adam step over flat buffers, exactly PyTorch's formula (no weight decay, no amsgrad).
struct AdamArgs {
  int64_t size = 0;
  float* param = nullptr;
  const float* grad = nullptr;
  float* exp_avg = nullptr;
  float* exp_avg_sq = nullptr;
  float lr = 0, beta1 = 0, beta2 = 0, eps = 0;
  float bias_correction1 = 1, bias_correction2_sqrt = 1;
};

/// The kernels of one instruction set.
struct KernelTable {
  const char* name;
  void (*gemm_nn)(const GemmNNArgs&);
  void (*gemm_nt)(const GemmNTArgs&);
  void (*pool_relu_forward)(const PoolArgs&);
  void (*pool_relu_backward)(const PoolBackwardArgs&);
  void (*adam)(const AdamArgs&);
  /// Sum of each of `rows` rows of length n (row stride ld), added to out[i].
  void (*add_row_sums)(const float* x, int rows, int n, int64_t ld, float* out);
  /// True if every value is finite.
  bool (*all_finite)(const float* x, int64_t n);
};

/// The table in use: the best the CPU supports, or the one named by RECON_KERNELS
/// ("generic", "avx2", "avx512") if set.
const KernelTable& Kernels();

/// Names of the tables this build and CPU can run, best last (tests run each).
std::vector<std::string> AvailableKernels();
/// Switches the table in use (tests and benchmarks only: not while another thread trains).
/// Returns false if `name` is not available.
bool UseKernels(const std::string& name);

}  // namespace recon::learn::kernels
