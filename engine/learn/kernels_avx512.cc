// Kernels for x86-64 with AVX-512F (32 registers of 16 floats). Compiled with -mavx512f;
// only called after the CPU was checked (kernels.cc).
#define RECON_KERNELS_NS avx512
#define RECON_KERNELS_NAME "avx512"
#define RECON_KERNELS_WIDTH 16
#define RECON_KERNELS_NN_MR 6
#define RECON_KERNELS_NN_NV 4
#define RECON_KERNELS_NT_MR 4
#define RECON_KERNELS_NT_KR 5
#include "engine/learn/kernels_impl.h"
