// Kernels for x86-64 with AVX2 + FMA (16 registers of 8 floats). Compiled with -mavx2 -mfma;
// only called after the CPU was checked (kernels.cc).
#define RECON_KERNELS_NS avx2
#define RECON_KERNELS_NAME "avx2"
#define RECON_KERNELS_WIDTH 8
#define RECON_KERNELS_NN_MR 6
#define RECON_KERNELS_NN_NV 2
#define RECON_KERNELS_NT_MR 3
#define RECON_KERNELS_NT_KR 3
#include "engine/learn/kernels_impl.h"
