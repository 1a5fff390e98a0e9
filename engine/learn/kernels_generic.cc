// Kernels for any CPU: 128-bit vectors (SSE2 on x86-64, NEON on arm64), no FMA.
#define RECON_KERNELS_NS generic
#define RECON_KERNELS_NAME "generic"
#define RECON_KERNELS_WIDTH 4
#define RECON_KERNELS_NN_MR 6
#define RECON_KERNELS_NN_NV 2
#define RECON_KERNELS_NT_MR 3
#define RECON_KERNELS_NT_KR 3
#include "engine/learn/kernels_impl.h"
