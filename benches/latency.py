"""Step latency of the friction compensator in Rust, C and Python: ``python benches/latency.py``.

- Rust: ``cargo run --release -p gms-ffi --example latency -- --json`` (10⁶ steps per mode,
  N = 10, each step timed with ``Instant``; plus the most evaluations of Fh any step took and
  the bound 2N + 1);
- C: crates/gms-ffi/benches/latency.c compiled with gcc -O2 against the release
  ``libgms_ffi.a``, the same measurement with ``clock_gettime``;
- Python: ``leuven_rt.Compensator.step`` in a Python ``for`` loop, measured like
  benches/bench.py (batches of 100 calls; the median of the per-call averages), and each call
  timed on its own for the tail.

Input everywhere: 1 kHz samples of v = 10 mm/s·sin(2π·5 Hz·t) (feedforward) or its integral
(observer). Prints a markdown table. Takes about a minute; ``--quick`` skips nothing but runs
the Python part on fewer calls.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import leuven_rt

ROOT = Path(__file__).resolve().parent.parent
FFI = ROOT / "crates" / "gms-ffi"
DT = 1e-3
ELEMENTS = 10
PARAMS = leuven_rt.Params(
    Fc=1.0, Fs=1.5, Vs=1e-3, delta=2.0, n=2.0, sigma1=30.0, sigma2=0.4,
    W=[0.2] * ELEMENTS, Delta=[1e-6 * i for i in range(1, ELEMENTS + 1)],
)  # fmt: skip


def inputs(mode: str, samples: int) -> list[float]:
    v = 0.01 * np.sin(2.0 * np.pi * 5.0 * np.arange(samples) * DT)
    return (v if mode == "feedforward" else np.cumsum(v * DT)).tolist()


def cargo(*arguments: str) -> str:
    return subprocess.run(["cargo", *arguments], cwd=ROOT, check=True, capture_output=True, text=True).stdout


def rust() -> list[dict[str, float | str]]:
    output = cargo("run", "--release", "-q", "-p", "gms-ffi", "--example", "latency", "--", "--json")
    return [json.loads(line) for line in output.splitlines()]


def c() -> list[dict[str, float | str]]:
    cargo("build", "--release", "-q", "-p", "gms-ffi", "--lib")
    metadata = json.loads(cargo("metadata", "--format-version", "1", "--no-deps"))
    library = Path(metadata["target_directory"]) / "release" / "libgms_ffi.a"
    if shutil.which("gcc") is None:
        raise SystemExit("gcc is needed for the C benchmark")
    with tempfile.TemporaryDirectory() as folder:
        binary = Path(folder) / "latency"
        subprocess.run(
            ["gcc", "-std=c11", "-O2", "-I", str(FFI / "include"), str(FFI / "benches" / "latency.c"),
             str(library), "-lm", "-lpthread", "-ldl", "-lgcc_s", "-lc", "-o", str(binary)],
            check=True,
        )  # fmt: skip
        output = subprocess.run([str(binary)], check=True, capture_output=True, text=True).stdout
    return [json.loads(line) for line in output.splitlines()]


def python(mode: str, calls: int, batch: int = 100) -> dict[str, float | str]:
    """Per-call time of ``step`` in a Python loop: batched median (like bench.py) and the
    distribution of single calls (each timed with perf_counter_ns, whose own cost is included)."""
    values = inputs(mode, calls)
    compensator = leuven_rt.Compensator(PARAMS, DT, mode)
    step = compensator.step
    for value in values[:10_000]:
        step(value)
    compensator.reset()
    clock = time.perf_counter_ns
    averages: list[float] = []
    for start in range(0, calls, batch):
        chunk = values[start : start + batch]
        begin = clock()
        for value in chunk:
            step(value)
        averages.append((clock() - begin) / len(chunk))
    compensator.reset()
    singles = np.empty(calls)
    for index, value in enumerate(values):
        begin = clock()
        step(value)
        singles[index] = clock() - begin
    overhead = np.empty(10_000)
    for index in range(overhead.size):
        begin = clock()
        overhead[index] = clock() - begin
    return {
        "language": "python",
        "mode": mode,
        "steps": calls,
        "elements": ELEMENTS,
        "batched_median_ns": statistics.median(averages),
        "median_ns": float(np.median(singles)),
        "p999_ns": float(np.quantile(singles, 0.999)),
        "max_ns": float(singles.max()),
        "clock_overhead_ns": float(np.median(overhead)),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="Python part on 10^5 calls instead of 10^6")
    args = parser.parse_args()
    calls = 100_000 if args.quick else 1_000_000
    started = time.perf_counter()
    rows = rust() + c() + [python(mode, calls) for mode in ("feedforward", "observer")]
    load = ", ".join(f"{value:.2f}" for value in os.getloadavg())
    print(f"# compensator step latency, N = {ELEMENTS}, dt = 1 ms, implicit step")
    print()
    print(f"machine: {os.cpu_count()} cores; load average {load}; not a real-time kernel, so the max")
    print("includes preemption by the OS and other processes")
    print()
    print(
        "| language | mode | steps | median | p99.9 | max | median per step, batches of 100 "
        "| clock read (included) | most Fh evaluations (bound 2N + 1) |"
    )
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for row in rows:
        evaluations = (
            f"{row['most_evaluations']} ({row['evaluation_bound']})"
            if "most_evaluations" in row
            else "same solver"
        )
        print(
            f"| {row['language']} | {row['mode']} | {row['steps']:,} | {row['median_ns']:.0f} ns | "
            f"{row['p999_ns']:.0f} ns | {float(row['max_ns']) / 1e3:.1f} µs | "
            f"{row['batched_median_ns']:.1f} ns | {row['clock_overhead_ns']:.0f} ns | {evaluations} |"
        )
    print()
    for row in rows:
        if row["language"] == "python":
            met = "met" if float(row["batched_median_ns"]) < 1000 else "NOT met"
            print(
                f"Python `Compensator.step` ({row['mode']}) in a for loop: {row['batched_median_ns']:.0f} ns "
                f"per call, median of batches of 100 (target < 1 µs: {met})"
            )
    print(f"total time: {time.perf_counter() - started:.0f} s")


if __name__ == "__main__":
    sys.exit(main())
