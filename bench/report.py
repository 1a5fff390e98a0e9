#!/usr/bin/env python3
"""Turns Google Benchmark JSON (+ the PyTorch reference and an optional full-figure run) into a
table on stdout and bench/results/latest.json, with each target and whether it is met."""
import argparse
import json
import os
import platform
import time

# Targets from the issues: name -> (limit, unit, direction).
TARGETS = {
    "BM_TrainStepDynamic2DExact": (2.0, "ms/step", "max"),
    "dynamic2d_full_figure": (900.0, "s", "max"),
}
# The arithmetic floor of one Dynamic 2D training step on one AVX2 core (64 MFLOP).
FLOOR_MS = 0.7


def median_ms(bench_file):
    with open(bench_file) as f:
        data = json.load(f)
    rows = {}
    for b in data["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
        rows[b["run_name"]] = b["real_time"] * scale
    return rows


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--benchmarks", nargs="+", required=True)
    p.add_argument("--pytorch")
    p.add_argument("--figure")
    p.add_argument("--out", required=True)
    a = p.parse_args()

    results = {}
    for f in a.benchmarks:
        for name, ms in median_ms(f).items():
            results[name] = {"value": ms, "unit": "ms"}
    reference_ms = None
    if a.pytorch:
        with open(a.pytorch) as f:
            reference_ms = json.load(f)["ms_per_step"]
        results["pytorch_reference_train_step"] = {"value": reference_ms, "unit": "ms"}
    if a.figure:
        with open(a.figure) as f:
            results["dynamic2d_full_figure"] = {"value": json.load(f)["wall_seconds"], "unit": "s"}

    print(f"\n{'benchmark':46s} {'value':>10s} {'unit':6s} {'target':>12s}  note")
    for name, r in sorted(results.items()):
        note = ""
        target = ""
        base = name.split("/")[0]
        if base in TARGETS:
            limit, unit, direction = TARGETS[base]
            ok = r["value"] <= limit if direction == "max" else r["value"] >= limit
            r["target"] = {"limit": limit, "direction": direction, "met": ok}
            target = f"<= {limit:g}"
            note = "met" if ok else "NOT MET"
        if base == "BM_TrainStepDynamic2DExact":
            r["steps_per_second"] = 1000.0 / r["value"]
            note += f"; {1000.0 / r['value']:.0f} steps/s, floor {FLOOR_MS} ms"
            if reference_ms:
                r["speedup_vs_pytorch"] = reference_ms / r["value"]
                note += f", {reference_ms / r['value']:.2f}x PyTorch"
        print(f"{name:46s} {r['value']:10.3f} {r['unit']:6s} {target:>12s}  {note}")

    out = {
        "generated": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
        "machine": {"cpus": os.cpu_count(), "platform": platform.platform()},
        "floor_ms_per_step": FLOOR_MS,
        "results": results,
    }
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    with open(a.out + ".tmp", "w") as f:
        json.dump(out, f, indent=2)
    os.replace(a.out + ".tmp", a.out)
    print(f"\nwrote {a.out}")


if __name__ == "__main__":
    main()
