#!/usr/bin/env python3
"""The reference point for our training speed: a plain PyTorch loop of the authors' Dynamic 2D
network and recipe (REFERENCE.md section 2), on one thread, batch 20, Exact placement.

Written for this benchmark from the published description (not the authors' code). Prints one
JSON object: {"ms_per_step": ..., "steps": ..., "torch": version}.
"""
import json
import sys
import time

import torch
import torch.nn as nn
import torch.nn.functional as F

torch.set_num_threads(1)
torch.manual_seed(0)


class Features(nn.Module):
    """The authors' CNN; `flat` is what its two blocks leave of the image (400 for 32 x 32, the
    tabletop's 16 x 13 x 13 for 64 x 64)."""

    def __init__(self, flat=400):
        super().__init__()
        self.conv1 = nn.Conv2d(3, 6, 5)
        self.conv2 = nn.Conv2d(6, 16, 5)
        self.fc1 = nn.Linear(flat, 120)
        self.fc2 = nn.Linear(120, 60)
        self.fc3 = nn.Linear(60, 6)

    def forward(self, y):
        h = F.max_pool2d(F.relu(self.conv1(y)), 2)
        h = F.max_pool2d(F.relu(self.conv2(h)), 2)
        h = torch.flatten(h, 1)
        return self.fc3(F.relu(self.fc2(F.relu(self.fc1(h)))))


class Head(nn.Module):
    """Two hidden layers, then mean and log-variance."""

    def __init__(self, n_in, hidden, n_out, second_act):
        super().__init__()
        self.l1 = nn.Linear(n_in, hidden)
        self.l2 = nn.Linear(hidden, hidden)
        self.mean = nn.Linear(hidden, n_out)
        self.logvar = nn.Linear(hidden, n_out)
        self.second_act = second_act

    def forward(self, h):
        h = self.second_act(self.l2(torch.tanh(self.l1(h))))
        return self.mean(h), self.logvar(h)


def sample_mse(mean, logvar, target):
    sample = mean + torch.exp(0.5 * logvar) * torch.randn_like(mean)
    return F.mse_loss(sample, target)


def ms_per_step(step, steps, warmup):
    for _ in range(warmup):
        step()
    start = time.perf_counter()
    for _ in range(steps):
        step()
    return 1000.0 * (time.perf_counter() - start) / steps


def nll(mean, logvar, target):
    return (0.5 * (logvar + (target - mean) ** 2 * torch.exp(-logvar))).sum(1).mean()


def tabletop_ms_per_step(steps):
    """The tabletop recipe's step (BM_TrainStepTabletop): RECON (Play), x 7, u 7 in chunks of 10,
    a (512, 512) policy, Gaussian NLL, pixels scaled to 0-1, batch 20 of demos and 20 of play."""
    n, chunk = 480, 10
    images = torch.randint(0, 256, (n, 3, 64, 64)).float() / 255.0
    play_images = torch.randint(0, 256, (40, 3, 64, 64)).float() / 255.0
    robot = torch.randn(n, 7)
    actions = torch.randn(n, 7 * chunk)
    beacons = torch.randn(n, 2)
    play_beacons = torch.randn(40, 2)
    features = Features(16 * 13 * 13)
    policy = Head(13, 512, 7 * chunk, torch.relu)
    beacon = Head(6, 16, 2, torch.tanh)
    params = list(features.parameters()) + list(policy.parameters()) + list(beacon.parameters())
    optimizer = torch.optim.Adam(params, lr=4e-4)

    def step():
        idx = torch.randint(0, n, (20,))
        pidx = torch.randint(0, 40, (20,))
        phi = features(images[idx])
        u_mean, u_logvar = policy(torch.cat([robot[idx], phi], 1))
        b_mean, b_logvar = beacon(phi)
        p_mean, p_logvar = beacon(features(play_images[pidx]))
        loss = (nll(u_mean, u_logvar, actions[idx]) / chunk + nll(b_mean, b_logvar, beacons[idx]) +
                nll(p_mean, p_logvar, play_beacons[pidx]))
        optimizer.zero_grad()
        loss.backward()
        optimizer.step()

    return ms_per_step(step, steps, warmup=20)


def main():
    steps = int(sys.argv[1]) if len(sys.argv) > 1 else 1000
    n = 100  # 10 demos x 10 steps
    images = torch.randint(225, 256, (n, 3, 32, 32)).float()
    robot = torch.randn(n, 2)
    actions = torch.randn(n, 2)
    beacons = torch.randn(n, 2) * 7

    features = Features()
    policy = Head(8, 32, 2, torch.relu)
    beacon = Head(6, 16, 2, torch.tanh)
    params = list(features.parameters()) + list(policy.parameters()) + list(beacon.parameters())
    optimizer = torch.optim.Adam(params, lr=4e-4)

    def step():
        idx = torch.randint(0, n, (20,))
        phi = features(images[idx])
        u_mean, u_logvar = policy(torch.cat([robot[idx], phi], 1))
        b_mean, b_logvar = beacon(phi)
        loss = 1.0 * sample_mse(u_mean, u_logvar, actions[idx]) + 1.2 * sample_mse(
            b_mean, b_logvar, beacons[idx])
        optimizer.zero_grad()
        loss.backward()
        optimizer.step()

    print(json.dumps({"ms_per_step": ms_per_step(step, steps, warmup=100), "steps": steps,
                      "tabletop_ms_per_step": tabletop_ms_per_step(max(50, steps // 10)),
                      "torch": torch.__version__}))


if __name__ == "__main__":
    main()
