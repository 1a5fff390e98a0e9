#pragma once

// The two ways a Gaussian head is scored (LossKind), on plain buffers. A head's output row is
// [mean (dim values) | log-variance (dim values)]. Internal to engine/learn (and its tests).

#include "engine/learn/learner.h"

namespace recon::learn {

/// Gaussian negative log-likelihood, summed over dimensions and averaged over the batch:
/// mean_b sum_d 0.5 * (log(2 pi) + v + (t - mean)^2 * exp(-v)), v = max(logvar, min_logvar[d])
/// (TrainConfig::nll_min_std and action_min_std; a log-variance held at its floor gets no
/// gradient). min_logvar holds one floor per dimension (-infinity: none); null = no floors.
/// If grad_head is not null, writes weight * dLoss/dhead into it (same layout as head).
float GaussianNll(const float* head, const float* target, int batch, int dim, float weight,
                  float* grad_head, const float* min_logvar = nullptr);

/// The authors' loss: mean over all batch * dim elements of (s - t)^2, where
/// s = mean + exp(0.5 * logvar) * noise is a reparameterised sample (noise: batch x dim).
float MseOfSample(const float* head, const float* target, const float* noise, int batch, int dim,
                  float weight, float* grad_head);

/// Dispatches on the kind; `noise` is only read for kMseSample, `min_logvar` only for kNll.
float HeadLoss(LossKind kind, const float* head, const float* target, const float* noise, int batch,
               int dim, float weight, float* grad_head, const float* min_logvar = nullptr);

/// Sum over the batch and dimensions of (mean - t)^2: the restart rule's error measure.
double SumSquaredMeanError(const float* head, const float* target, int batch, int dim);

}  // namespace recon::learn
