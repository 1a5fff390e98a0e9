// The kernels of kernels.h as one template over the SIMD width. Included once by each
// kernels_<isa>.cc, which defines:
//   RECON_KERNELS_NS      a namespace name unique to that translation unit
//   RECON_KERNELS_NAME    the table's name ("generic", "avx2", "avx512")
//   RECON_KERNELS_WIDTH   floats per vector register (4, 8, 16)
//   RECON_KERNELS_NN_MR, RECON_KERNELS_NN_NV, RECON_KERNELS_NT_MR, RECON_KERNELS_NT_KR
//                         register-block sizes (rows x vectors; rows x dot products) that fit the
//                         register file of that instruction set.
//
// The same inline code is compiled with different instruction-set flags in several translation
// units, so everything here has internal linkage and uses no standard-library templates: the
// linker must never pick an AVX-512 copy of a shared inline function for generic code.
// No include guard on purpose: each kernels_<isa>.cc includes this exactly once.

#include <cstdint>

#if defined(__AVX2__) || defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "engine/learn/kernels.h"

namespace recon::learn::kernels::RECON_KERNELS_NS {
namespace {

constexpr int kW = RECON_KERNELS_WIDTH;
constexpr int kNnMr = RECON_KERNELS_NN_MR;
constexpr int kNnNv = RECON_KERNELS_NN_NV;
constexpr int kNtMr = RECON_KERNELS_NT_MR;
constexpr int kNtKr = RECON_KERNELS_NT_KR;

#include "engine/learn/kernels_vector.h"

// ---------------------------------------------------------------------------------------------
// C = A * B, register-blocked: MR rows of C times NV vectors of columns stay in registers while
// the k loop streams rows of B.

template <int MR, int NV, bool kPartial>
inline void NnBlock(const GemmNNArgs& g, int m0, int n0, int tail) {
  V acc[MR][NV];
#pragma GCC unroll 8
  for (int i = 0; i < MR; ++i) {
#pragma GCC unroll 8
    for (int j = 0; j < NV; ++j) {
      V v = V{};
      if (g.accumulate) v = LoadN<kPartial>(g.c + (m0 + i) * g.ldc + n0 + j * kW, tail);
      if (g.bias_m) v += g.bias_m[m0 + i];
      if (g.bias_n) v += LoadN<kPartial>(g.bias_n + n0 + j * kW, tail);
      acc[i][j] = v;
    }
  }
  const float* a = g.a + m0 * g.a_sm;
  const int64_t a_sm = g.a_sm;
  for (int l = 0; l < g.k; ++l) {
    const float* brow = g.b + (g.b_off ? g.b_off[l] : l * g.ldb) + n0;
    V bv[NV];
#pragma GCC unroll 8
    for (int j = 0; j < NV; ++j) bv[j] = LoadN<kPartial>(brow + j * kW, tail);
    const float* al = a + l * g.a_sk;
#pragma GCC unroll 8
    for (int i = 0; i < MR; ++i) {
      const V av = V{} + al[i * a_sm];
#pragma GCC unroll 8
      for (int j = 0; j < NV; ++j) acc[i][j] += av * bv[j];
    }
  }
#pragma GCC unroll 8
  for (int i = 0; i < MR; ++i) {
#pragma GCC unroll 8
    for (int j = 0; j < NV; ++j) {
      StoreN<kPartial>(g.c + (m0 + i) * g.ldc + n0 + j * kW, acc[i][j], tail);
    }
  }
}

// Rows left over after full blocks of kNnMr: pick the block height at compile time.
template <int R, int NV, bool kPartial>
inline void NnRemainderRows(const GemmNNArgs& g, int m0, int rows, int n0, int tail) {
  if constexpr (R > 0) {
    if (rows == R) {
      NnBlock<R, NV, kPartial>(g, m0, n0, tail);
    } else {
      NnRemainderRows<R - 1, NV, kPartial>(g, m0, rows, n0, tail);
    }
  }
}

template <int NV, bool kPartial>
inline void NnColumnChunk(const GemmNNArgs& g, int n0, int tail) {
  int m0 = 0;
  for (; m0 + kNnMr <= g.m; m0 += kNnMr) NnBlock<kNnMr, NV, kPartial>(g, m0, n0, tail);
  NnRemainderRows<kNnMr - 1, NV, kPartial>(g, m0, g.m - m0, n0, tail);
}

void GemmNN(const GemmNNArgs& g) {
  // Column chunks outermost: the k rows of one chunk of B stay in L1 across all row blocks.
  int n0 = 0;
  for (; n0 + kNnNv * kW <= g.n; n0 += kNnNv * kW) NnColumnChunk<kNnNv, false>(g, n0, 0);
  for (; n0 + kW <= g.n; n0 += kW) NnColumnChunk<1, false>(g, n0, 0);
  if (n0 < g.n) NnColumnChunk<1, true>(g, n0, g.n - n0);
}

// ---------------------------------------------------------------------------------------------
// C(i, l) = A_i . B_l: MR x KR dot products accumulate in vector registers over n, then reduce.

template <int MR, int KR>
inline void NtBlock(const GemmNTArgs& g, int m0, int k0) {
  V acc[MR][KR];
  const float* ar[MR];
  const float* br[KR];
#pragma GCC unroll 8
  for (int i = 0; i < MR; ++i) {
    ar[i] = g.a + (m0 + i) * g.lda;
#pragma GCC unroll 8
    for (int j = 0; j < KR; ++j) acc[i][j] = V{};
  }
#pragma GCC unroll 8
  for (int j = 0; j < KR; ++j) br[j] = g.b + (g.b_off ? g.b_off[k0 + j] : (k0 + j) * g.ldb);
  int n = 0;
  for (; n + kW <= g.n; n += kW) {
    V av[MR], bv[KR];
#pragma GCC unroll 8
    for (int i = 0; i < MR; ++i) av[i] = Load(ar[i] + n);
#pragma GCC unroll 8
    for (int j = 0; j < KR; ++j) bv[j] = Load(br[j] + n);
#pragma GCC unroll 8
    for (int i = 0; i < MR; ++i) {
#pragma GCC unroll 8
      for (int j = 0; j < KR; ++j) acc[i][j] += av[i] * bv[j];
    }
  }
  if (n < g.n) {
    const int tail = g.n - n;
    V av[MR], bv[KR];
#pragma GCC unroll 8
    for (int i = 0; i < MR; ++i) av[i] = LoadN<true>(ar[i] + n, tail);
#pragma GCC unroll 8
    for (int j = 0; j < KR; ++j) bv[j] = LoadN<true>(br[j] + n, tail);
#pragma GCC unroll 8
    for (int i = 0; i < MR; ++i) {
#pragma GCC unroll 8
      for (int j = 0; j < KR; ++j) acc[i][j] += av[i] * bv[j];
    }
  }
#pragma GCC unroll 8
  for (int i = 0; i < MR; ++i) {
#pragma GCC unroll 8
    for (int j = 0; j < KR; ++j) {
      float* c = g.c + (m0 + i) * g.c_sm + (k0 + j) * g.c_sk;
      float base = g.accumulate ? *c : 0.0f;
      if (g.bias_k) base += g.bias_k[k0 + j];
      *c = base + HSum(acc[i][j]);
    }
  }
}

template <int MR, int R>
inline void NtRemainderCols(const GemmNTArgs& g, int m0, int k0, int cols) {
  if constexpr (R > 0) {
    if (cols == R) {
      NtBlock<MR, R>(g, m0, k0);
    } else {
      NtRemainderCols<MR, R - 1>(g, m0, k0, cols);
    }
  }
}

template <int MR, int KR>
inline void NtRowBlock(const GemmNTArgs& g, int m0) {
  int k0 = 0;
  for (; k0 + KR <= g.k; k0 += KR) NtBlock<MR, KR>(g, m0, k0);
  NtRemainderCols<MR, KR - 1>(g, m0, k0, g.k - k0);
}

template <int R, int KR>
inline void NtRemainderRows(const GemmNTArgs& g, int m0, int rows) {
  if constexpr (R > 0) {
    if (rows == R) {
      NtRowBlock<R, KR>(g, m0);
    } else {
      NtRemainderRows<R - 1, KR>(g, m0, rows);
    }
  }
}

template <int MR, int KR>
inline void GemmNTShaped(const GemmNTArgs& g) {
  int m0 = 0;
  for (; m0 + MR <= g.m; m0 += MR) NtRowBlock<MR, KR>(g, m0);
  NtRemainderRows<MR - 1, KR>(g, m0, g.m - m0);
}

void GemmNT(const GemmNTArgs& g) { GemmNTShaped<kNtMr, kNtKr>(g); }

// ---------------------------------------------------------------------------------------------
// Max-pool 2x2 + ReLU, kW outputs at a time: the even and odd columns of two input rows are
// the four candidates. NaN wins every comparison (as in PyTorch), so that a NaN produced inside
// the network reaches the loss and is reported as divergence instead of being pooled away.

void PoolReluForward(const PoolArgs& p) {
  const int64_t out_plane = static_cast<int64_t>(p.out_h) * p.out_w;
  const V zero = V{};
  for (int plane = 0; plane < p.planes; ++plane) {
    const float* in = p.in + plane * p.in_stride;
    float* out = p.out + plane * out_plane;
    float* arg = p.arg + plane * out_plane;
    for (int y = 0; y < p.out_h; ++y) {
      const float* r0 = in + 2 * y * p.width;
      const float* r1 = r0 + p.width;
      for (int x0 = 0; x0 < p.out_w; x0 += kW) {
        const int valid = Min(kW, p.out_w - x0);
        const int lo = Min(2 * valid, kW), hi = Max(2 * valid - kW, 0);
        const V a0 = LoadPart(r0 + 2 * x0, lo), a1 = LoadPart(r0 + 2 * x0 + kW, hi);
        const V b0 = LoadPart(r1 + 2 * x0, lo), b1 = LoadPart(r1 + 2 * x0 + kW, hi);
        const V v0 = Evens(a0, a1), v1 = Odds(a0, a1), v2 = Evens(b0, b1), v3 = Odds(b0, b1);
        V m = v0, index = zero;
        auto take = [&](V v, float code) {
          const auto wins = (v > m) | (v != v);
          m = wins ? v : m;
          index = wins ? zero + code : index;
        };
        take(v1, 1.0f);
        take(v2, 2.0f);
        take(v3, 3.0f);
        const auto nan0 = v0 != v0;
        m = nan0 ? v0 : m;
        index = nan0 ? zero : index;
        StorePart(out + y * p.out_w + x0, ((m > zero) | (m != m)) ? m : zero, valid);
        StorePart(arg + y * p.out_w + x0, index, valid);
      }
    }
  }
}

void PoolReluBackward(const PoolBackwardArgs& p) {
  const int64_t out_plane = static_cast<int64_t>(p.out_h) * p.out_w;
  const V zero = V{};
  for (int plane = 0; plane < p.planes; ++plane) {
    const float* grad_out = p.grad_out + plane * out_plane;
    const float* out = p.out + plane * out_plane;
    const float* arg = p.arg + plane * out_plane;
    float* gi = p.grad_in + plane * p.grad_in_stride;
    for (int y = 0; y < p.out_h; ++y) {
      float* g0 = gi + 2 * y * p.width;
      float* g1 = g0 + p.width;
      for (int x0 = 0; x0 < p.out_w; x0 += kW) {
        const int valid = Min(kW, p.out_w - x0);
        const int64_t o = static_cast<int64_t>(y) * p.out_w + x0;
        const V a = LoadPart(arg + o, valid);
        const V g = LoadPart(out + o, valid) > zero ? LoadPart(grad_out + o, valid) : zero;
        const V ga = a == zero ? g : zero, gb = a == zero + 1.0f ? g : zero;
        const V gc = a == zero + 2.0f ? g : zero, gd = a == zero + 3.0f ? g : zero;
        const int lo = Min(2 * valid, kW), hi = Max(2 * valid - kW, 0);
        StorePart(g0 + 2 * x0, InterleaveLo(ga, gb), lo);
        StorePart(g0 + 2 * x0 + kW, InterleaveHi(ga, gb), hi);
        StorePart(g1 + 2 * x0, InterleaveLo(gc, gd), lo);
        StorePart(g1 + 2 * x0 + kW, InterleaveHi(gc, gd), hi);
      }
      for (int x = 2 * p.out_w; x < p.width; ++x) g0[x] = g1[x] = 0.0f;
    }
    for (int64_t i = 2 * static_cast<int64_t>(p.out_h) * p.width;
         i < static_cast<int64_t>(p.rows) * p.width; ++i) {
      gi[i] = 0.0f;
    }
  }
}

// ---------------------------------------------------------------------------------------------

void Adam(const AdamArgs& args) {
  // Locals and restrict: otherwise every store could alias `args` and the loop stays scalar.
  const int64_t n = args.size;
  float* __restrict param = args.param;
  const float* __restrict grad = args.grad;
  float* __restrict exp_avg = args.exp_avg;
  float* __restrict exp_avg_sq = args.exp_avg_sq;
  const float beta1 = args.beta1, beta2 = args.beta2, eps = args.eps;
  const float one_minus_beta1 = 1.0f - beta1, one_minus_beta2 = 1.0f - beta2;
  const float step_size = args.lr / args.bias_correction1;
  const float bias_correction2_sqrt = args.bias_correction2_sqrt;
  for (int64_t i = 0; i < n; ++i) {
    const float g = grad[i];
    const float m = exp_avg[i] * beta1 + g * one_minus_beta1;
    const float v = exp_avg_sq[i] * beta2 + g * g * one_minus_beta2;
    exp_avg[i] = m;
    exp_avg_sq[i] = v;
    const float denom = __builtin_sqrtf(v) / bias_correction2_sqrt + eps;
    param[i] -= step_size * (m / denom);
  }
}

void AddRowSums(const float* x, int rows, int n, int64_t ld, float* out) {
  for (int r = 0; r < rows; ++r) {
    const float* row = x + r * ld;
    V acc = V{};
    int i = 0;
    for (; i + kW <= n; i += kW) acc += Load(row + i);
    if (i < n) acc += LoadPart(row + i, n - i);
    out[r] += HSum(acc);
  }
}

bool AllFinite(const float* x, int64_t n) {
  // x * 0 is 0 for finite x and NaN for inf or NaN, so one NaN check at the end suffices.
  V acc = V{};
  int64_t i = 0;
  for (; i + kW <= n; i += kW) acc += Load(x + i) * 0.0f;
  float s = HSum(acc);
  for (; i < n; ++i) s += x[i] * 0.0f;
  return s == 0.0f;
}

}  // namespace

const KernelTable& Table() {
  static const KernelTable table = {RECON_KERNELS_NAME, &GemmNN, &GemmNT,     &PoolReluForward,
                                    &PoolReluBackward,  &Adam,   &AddRowSums, &AllFinite};
  return table;
}

}  // namespace recon::learn::kernels::RECON_KERNELS_NS
