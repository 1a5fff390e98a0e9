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
    # Issue 3: the simulated cell.
    "tabletop_camera_64x64_fps": (200.0, "frames/s", "min"),
    "tabletop_demo_realtime_factor": (50.0, "x", "min"),
    "bintransfer_demo_realtime_factor": (50.0, "x", "min"),
    "tabletop_step_overhead": (10.0, "%", "max"),
    "bintransfer_step_overhead": (10.0, "%", "max"),
    # The session store (store_bench): benchmark medians, compared by benchmark name.
    "BM_CommitEpisode150x64x64": (20.0, "ms", "max"),
    "BM_OpenSession100": (1000.0, "ms", "max"),
    "BM_LoadDataset100": (2000.0, "ms", "max"),
    # Issue 5: the studio at 1280 x 800, headless, camera live.
    "studio_frames_per_second": (30.0, "frames/s", "min"),
    "studio_frames_per_second_while_training": (30.0, "frames/s", "min"),
    "studio_frames_per_second_playing_rollouts": (30.0, "frames/s", "min"),
    # Issue 14: a teacher's wait from "Train" to "Rollouts done", 4 demonstrations, 2 cores.
    "studio_train_to_rollouts_4_demos": (90.0, "s", "max"),
    # Issue 6: DWM1001 beacons (uwb_bench).
    "uwb_lec_lines_per_second": (100000.0, "lines/s", "min"),
    "uwb_pty_line_to_reading_median": (2000.0, "us", "max"),
    # Issue 18: what a policy looks at, on 2 cores.
    "probe_tabletop_10x10_two_methods": (20.0, "s", "max"),
    "BM_SaliencyGradient64": (50.0, "ms", "max"),
}
# Rates the cell benchmarks report as counters: result name -> (benchmark, counter, unit).
COUNTERS = {
    "tabletop_camera_64x64_fps": ("BM_TabletopCamera64/real_time", "frames_per_second", "frames/s"),
    "tabletop_demo_realtime_factor":
        ("BM_TabletopRecordDemonstration/real_time", "sim_s_per_s", "x"),
    "bintransfer_demo_realtime_factor": ("BM_RecordDemonstration", "sim_s_per_s", "x"),
    # Informational (no target): the memory a loaded 100-episode tabletop session takes.
    "store_dataset_100_peak_rss":
        ("BM_LoadDataset100/iterations:1/real_time", "peak_rss_MB", "MB"),
    "store_dataset_100_footprint":
        ("BM_LoadDataset100/iterations:1/real_time", "dataset_MB", "MB"),
    "studio_frames_per_second":
        ("BM_StudioFrame1280x800/min_time:2.000/real_time", "frames_per_second", "frames/s"),
    "studio_frames_per_second_while_training":
        ("BM_StudioFrameWhileTraining/min_time:2.000/real_time", "frames_per_second", "frames/s"),
    "studio_frames_per_second_playing_rollouts":
        ("BM_StudioFramePlayingRollouts/min_time:2.000/real_time", "frames_per_second",
         "frames/s"),
    "studio_train_to_rollouts_4_demos":
        ("BM_StudioTrainToRolloutsFourDemos/iterations:1/repeats:1/real_time",
         "train_to_rollouts_s", "s"),
    "probe_tabletop_10x10_two_methods":
        ("BM_ProbeTabletop10x10TwoMethods/iterations:1/real_time", "probe_s", "s"),
    # Informational (no target): whole rollouts from each of the bowl's places, 5 x 5 grid.
    "outcome_probe_tabletop_5x5_two_methods":
        ("BM_OutcomeProbeTabletop5x5TwoMethods/iterations:1/real_time", "outcome_probe_s", "s"),
    "uwb_lec_lines_per_second": ("BM_LecParseLines", "lines_per_s", "lines/s"),
    "uwb_tlv_frames_per_second": ("BM_TlvParseFrames", "frames_per_s", "frames/s"),
    "uwb_pty_line_to_reading_median":
        ("BM_PtyLineToReadingLatency/iterations:2000/real_time", "median_latency_us", "us"),
    "uwb_pty_line_to_reading_p99":
        ("BM_PtyLineToReadingLatency/iterations:2000/real_time", "p99_latency_us", "us"),
}
# Our stepping against a bare mj_step loop on the same model: (ours, bare) benchmark names.
OVERHEADS = {
    "tabletop_step_overhead": ("BM_TabletopArmStep", "BM_TabletopBareMjStep"),
    "bintransfer_step_overhead": ("BM_BinTransferStep", "BM_BareMjStep"),
}
# The arithmetic floor of one Dynamic 2D training step on one AVX2 core (64 MFLOP).
FLOOR_MS = 0.7


def medians(bench_file):
    """Median wall time (ms) and median counters of each benchmark in a Google Benchmark file."""
    with open(bench_file) as f:
        data = json.load(f)
    rows, counters = {}, {}
    # A benchmark that runs once (minutes of training) has no aggregates: its one run stands.
    aggregated = {b["run_name"] for b in data["benchmarks"] if b.get("aggregate_name")}
    for b in data["benchmarks"]:
        if b.get("aggregate_name") != "median" and (
                b.get("run_type") != "iteration" or b["run_name"] in aggregated):
            continue
        scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
        rows[b["run_name"]] = b["real_time"] * scale
        counters[b["run_name"]] = {k: v for k, v in b.items() if k.endswith("_per_s")
                                   or k.endswith("_per_second") or k.endswith("_MB")
                                   or k.endswith("_us") or k.endswith("_s")
                                   or k.endswith("_success")}
    return rows, counters


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--benchmarks", nargs="+", required=True)
    p.add_argument("--pytorch")
    p.add_argument("--figure")
    p.add_argument("--out", required=True)
    a = p.parse_args()

    results = {}
    counters = {}
    for f in a.benchmarks:
        rows, file_counters = medians(f)
        counters.update(file_counters)
        for name, ms in rows.items():
            results[name] = {"value": ms, "unit": "ms"}
    for name, (bench, counter, unit) in COUNTERS.items():
        if counter in counters.get(bench, {}):
            results[name] = {"value": counters[bench][counter], "unit": unit}
    for name, (ours, bare) in OVERHEADS.items():
        rate = lambda b: counters.get(b, {}).get("mj_steps_per_s")
        if rate(ours) and rate(bare):
            results[name] = {"value": 100.0 * (1.0 - rate(ours) / rate(bare)), "unit": "%",
                             "mj_steps_per_s": rate(ours), "bare_mj_steps_per_s": rate(bare)}
    reference_ms = None
    tabletop_reference_ms = None
    if a.pytorch:
        with open(a.pytorch) as f:
            reference = json.load(f)
        reference_ms = reference["ms_per_step"]
        results["pytorch_reference_train_step"] = {"value": reference_ms, "unit": "ms"}
        tabletop_reference_ms = reference.get("tabletop_ms_per_step")
        if tabletop_reference_ms:
            results["pytorch_reference_tabletop_step"] = {"value": tabletop_reference_ms,
                                                          "unit": "ms"}
    if a.figure:
        with open(a.figure) as f:
            results["dynamic2d_full_figure"] = {"value": json.load(f)["wall_seconds"], "unit": "s"}

    width = max([46] + [len(name) for name in results])  # run names can be long
    print(f"\n{'benchmark':{width}s} {'value':>10s} {'unit':6s} {'target':>12s}  note")
    for name, r in sorted(results.items()):
        note = ""
        target = ""
        base = name.split("/")[0]
        if base in TARGETS:
            limit, unit, direction = TARGETS[base]
            ok = r["value"] <= limit if direction == "max" else r["value"] >= limit
            r["target"] = {"limit": limit, "direction": direction, "met": ok}
            target = f"{'<=' if direction == 'max' else '>='} {limit:g}"
            note = "met" if ok else "NOT MET"
        if base == "BM_TrainStepDynamic2DExact":
            r["steps_per_second"] = 1000.0 / r["value"]
            note += f"; {1000.0 / r['value']:.0f} steps/s, floor {FLOOR_MS} ms"
            if reference_ms:
                r["speedup_vs_pytorch"] = reference_ms / r["value"]
                note += f", {reference_ms / r['value']:.2f}x PyTorch"
        if base == "BM_TrainStepTabletop" and tabletop_reference_ms:
            r["speedup_vs_pytorch"] = tabletop_reference_ms / r["value"]
            note += f"{tabletop_reference_ms / r['value']:.2f}x PyTorch's same step"
        print(f"{name:{width}s} {r['value']:10.3f} {r['unit']:6s} {target:>12s}  {note}")

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
