// Vector helpers of the kernels: the vector type of the translation unit's width, loads and
// stores (masked for tails), lane permutations and a reproducible horizontal sum. Included by
// kernels_impl.h inside its per-instruction-set anonymous namespace, after kW is defined; the
// same rules apply (internal linkage, no standard-library templates). No include guard.

typedef float V __attribute__((vector_size(kW * 4)));
typedef float VU __attribute__((vector_size(kW * 4), aligned(4), may_alias));

inline V Load(const float* p) { return *reinterpret_cast<const VU*>(p); }
inline void Store(float* p, V v) { *reinterpret_cast<VU*>(p) = v; }

// Tails (fewer than kW values) go through masked loads and stores so that no kernel reads or
// writes past the end of a row: buffers need no padding and garbage never enters a reduction.
inline V LoadPart(const float* p, int n) {
#if defined(__AVX512F__)
  return reinterpret_cast<V>(_mm512_maskz_loadu_ps(static_cast<__mmask16>((1u << n) - 1), p));
#elif defined(__AVX2__)
  const __m256i mask =
      _mm256_cmpgt_epi32(_mm256_set1_epi32(n), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  return reinterpret_cast<V>(_mm256_maskload_ps(p, mask));
#else
  V v = V{};
  for (int i = 0; i < n; ++i) v[i] = p[i];
  return v;
#endif
}

inline void StorePart(float* p, V v, int n) {
#if defined(__AVX512F__)
  _mm512_mask_storeu_ps(p, static_cast<__mmask16>((1u << n) - 1), reinterpret_cast<__m512>(v));
#elif defined(__AVX2__)
  const __m256i mask =
      _mm256_cmpgt_epi32(_mm256_set1_epi32(n), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  _mm256_maskstore_ps(p, mask, reinterpret_cast<__m256>(v));
#else
  for (int i = 0; i < n; ++i) p[i] = v[i];
#endif
}

template <bool kPartial>
inline V LoadN(const float* p, int n) {
  if constexpr (kPartial) {
    return LoadPart(p, n);
  } else {
    return Load(p);
  }
}

template <bool kPartial>
inline void StoreN(float* p, V v, int n) {
  if constexpr (kPartial) {
    StorePart(p, v, n);
  } else {
    Store(p, v);
  }
}

inline int Min(int a, int b) { return a < b ? a : b; }
inline int Max(int a, int b) { return a > b ? a : b; }

// Lane permutations, as templates so that only the branch of this width is instantiated.
// Evens/Odds: the even/odd elements of the concatenation [a, b].
template <typename T>
inline T Evens(T a, T b) {
  constexpr int kLanes = sizeof(T) / sizeof(float);
  if constexpr (kLanes == 16) {
    return __builtin_shufflevector(a, b, 0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
  } else if constexpr (kLanes == 8) {
    return __builtin_shufflevector(a, b, 0, 2, 4, 6, 8, 10, 12, 14);
  } else {
    return __builtin_shufflevector(a, b, 0, 2, 4, 6);
  }
}

template <typename T>
inline T Odds(T a, T b) {
  constexpr int kLanes = sizeof(T) / sizeof(float);
  if constexpr (kLanes == 16) {
    return __builtin_shufflevector(a, b, 1, 3, 5, 7, 9, 11, 13, 15, 17, 19, 21, 23, 25, 27, 29, 31);
  } else if constexpr (kLanes == 8) {
    return __builtin_shufflevector(a, b, 1, 3, 5, 7, 9, 11, 13, 15);
  } else {
    return __builtin_shufflevector(a, b, 1, 3, 5, 7);
  }
}

// InterleaveLo/Hi: the first/second half of a0 b0 a1 b1 a2 b2 ...
template <typename T>
inline T InterleaveLo(T a, T b) {
  constexpr int kLanes = sizeof(T) / sizeof(float);
  if constexpr (kLanes == 16) {
    return __builtin_shufflevector(a, b, 0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23);
  } else if constexpr (kLanes == 8) {
    return __builtin_shufflevector(a, b, 0, 8, 1, 9, 2, 10, 3, 11);
  } else {
    return __builtin_shufflevector(a, b, 0, 4, 1, 5);
  }
}

template <typename T>
inline T InterleaveHi(T a, T b) {
  constexpr int kLanes = sizeof(T) / sizeof(float);
  if constexpr (kLanes == 16) {
    return __builtin_shufflevector(a, b, 8, 24, 9, 25, 10, 26, 11, 27, 12, 28, 13, 29, 14, 30, 15,
                                   31);
  } else if constexpr (kLanes == 8) {
    return __builtin_shufflevector(a, b, 4, 12, 5, 13, 6, 14, 7, 15);
  } else {
    return __builtin_shufflevector(a, b, 2, 6, 3, 7);
  }
}

// Tree reduction through half-width vectors (a fixed order, so results are reproducible).
typedef float F2 __attribute__((vector_size(8)));
typedef float F4 __attribute__((vector_size(16)));
typedef float F8 __attribute__((vector_size(32)));

// A template so that only the branch of this width is instantiated.
template <typename T>
inline float HSumT(T v) {
  constexpr int kLanes = sizeof(T) / sizeof(float);
  F4 v4;
  if constexpr (kLanes == 16) {
    const F8 v8 = __builtin_shufflevector(v, v, 0, 1, 2, 3, 4, 5, 6, 7) +
                  __builtin_shufflevector(v, v, 8, 9, 10, 11, 12, 13, 14, 15);
    v4 = __builtin_shufflevector(v8, v8, 0, 1, 2, 3) + __builtin_shufflevector(v8, v8, 4, 5, 6, 7);
  } else if constexpr (kLanes == 8) {
    v4 = __builtin_shufflevector(v, v, 0, 1, 2, 3) + __builtin_shufflevector(v, v, 4, 5, 6, 7);
  } else {
    static_assert(kLanes == 4, "unsupported vector width");
    v4 = v;
  }
  const F2 v2 = __builtin_shufflevector(v4, v4, 0, 1) + __builtin_shufflevector(v4, v4, 2, 3);
  return v2[0] + v2[1];
}

inline float HSum(V v) { return HSumT(v); }
