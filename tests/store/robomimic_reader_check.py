#!/usr/bin/python3
"""Reads RECON Studio's robomimic files the way robomimic's training code reads a dataset, with
h5py (Debian's python3-h5py), and fails loudly on anything robomimic would trip over:

- the file opens read-only with swmr=True, libver="latest" (robomimic's default);
- data.attrs["env_args"] is JSON with env_name, type and env_kwargs;
- data.attrs["total"] equals the sum of every demo's num_samples;
- demos are data/demo_N, sortable by int(name[5:]);
- mask/<key> lists demo names as bytes that decode to existing demos;
- every demo has actions (N, A), rewards (N,), dones (N,) with dones[-1] == 1, and obs/<key>
  (and next_obs/<key> when required) with N rows; every demo has the first demo's obs keys and
  shapes (robomimic takes shape metadata from one demo);
- image keys (4-D) are uint8 (N, H, W, 3), which robomimic's image processing expects.

Usage: robomimic_reader_check.py FILE [--require-next-obs]. Prints a one-line summary.
"""
import json
import sys

import h5py
import numpy as np


def fail(message):
    print("robomimic check FAILED: " + message, file=sys.stderr)
    sys.exit(1)


def main():
    path = sys.argv[1]
    require_next_obs = "--require-next-obs" in sys.argv[2:]
    with h5py.File(path, "r", swmr=True, libver="latest") as f:
        if "data" not in f:
            fail("no group 'data'")
        data = f["data"]
        env_meta = json.loads(data.attrs["env_args"])
        for key in ("env_name", "type", "env_kwargs"):
            if key not in env_meta:
                fail("env_args has no '%s'" % key)
        demos = list(data.keys())
        if not demos:
            fail("no demonstrations")
        demos = [demos[i] for i in np.argsort([int(name[5:]) for name in demos])]
        masks = {}
        for key in f.get("mask", {}):
            masks[key] = [elem.decode("utf-8") for elem in np.array(f["mask/" + key][:])]
            for name in masks[key]:
                if name not in data:
                    fail("mask/%s names %s, which is not in data" % (key, name))
        first = data[demos[0]]
        obs_shapes = {k: first["obs/" + k].shape[1:] for k in sorted(first["obs"])}
        action_dim = first["actions"].shape[1]
        total = 0
        for name in demos:
            demo = data[name]
            n = int(demo.attrs["num_samples"])
            total += n
            if demo["actions"].shape != (n, action_dim):
                fail("%s/actions has shape %s" % (name, demo["actions"].shape))
            for key in ("rewards", "dones"):
                if demo[key].shape != (n,):
                    fail("%s/%s has shape %s" % (name, key, demo[key].shape))
            if demo["dones"][()][-1] != 1:
                fail("%s/dones does not end with 1" % name)
            groups = ["obs", "next_obs"] if require_next_obs else ["obs"]
            for group in groups:
                if group not in demo:
                    fail("%s has no %s" % (name, group))
                for key, shape in obs_shapes.items():
                    array = demo[group + "/" + key][()]
                    if array.shape != (n,) + shape:
                        fail("%s/%s/%s has shape %s" % (name, group, key, array.shape))
                    if array.ndim == 4 and (array.dtype != np.uint8 or array.shape[-1] != 3):
                        fail("%s/%s/%s is an image but not uint8 HWC RGB" % (name, group, key))
                    if not np.all(np.isfinite(array.astype(np.float64))):
                        fail("%s/%s/%s holds non-finite values" % (name, group, key))
        if int(data.attrs["total"]) != total:
            fail("data.attrs['total'] is %d, the demos hold %d" % (int(data.attrs["total"]), total))
        images = [k for k, s in obs_shapes.items() if len(s) == 3]
        print("robomimic check OK: %s: %d demos, %d samples, obs %s (images %s), actions %d, "
              "masks %s, env %s" % (path, len(demos), total, sorted(obs_shapes), images,
                                     action_dim, {k: len(v) for k, v in masks.items()},
                                     env_meta["env_name"]))


if __name__ == "__main__":
    main()
