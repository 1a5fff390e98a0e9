#pragma once

// The two ways a Gaussian head is scored (LossKind), on plain buffers. A head's output row is
// [mean (dim values) | log-variance (dim values)]. Internal to engine/learn (and its tests).

#include "engine/learn/learner.h"

namespace recon::learn {

/// Gaussian negative log-likelihood, summed over dimensions and averaged over the batch:
/// mean_b sum_d 0.5 * (log(2 pi) + logvar + (t - mean)^2 * exp(-logvar)).
/// If grad_head is not null, writes weight * dLoss/dhead into it (same layout as head).
float GaussianNll(const float* head, const float* target, int batch, int dim, float weight,
                  float* grad_head);

/// The authors' loss: mean over all batch * dim elements of (s - t)^2, where
/// s = mean + exp(0.5 * logvar) * noise is a reparameterised sample (noise: batch x dim).
float MseOfSample(const float* head, const float* target, const float* noise, int batch, int dim,
                  float weight, float* grad_head);

/// Dispatches on the kind; `noise` is only read for kMseSample.
float HeadLoss(LossKind kind, const float* head, const float* target, const float* noise, int batch,
               int dim, float weight, float* grad_head);

/// Sum over the batch and dimensions of (mean - t)^2: the restart rule's error measure.
double SumSquaredMeanError(const float* head, const float* target, int batch, int dim);

}  // namespace recon::learn
