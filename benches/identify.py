"""Wall time of ``leuven_rt.identify`` on ``make_data(seed=0)`` (31 166 samples, presliding and a
Stribeck curve, no velocity column), from the baseline ``coulomb,viscous``, with its progress on
stderr: each run's wall and CPU time and the load average, then the median.

Target (the "one model" issue): at most 10 s on a 2-core machine. The machine's load shows in
the wall time (the CPU time is the process's own, all threads), so the load average is printed
with every run.

    python benches/identify.py [--runs 3] [--quiet]
"""

from __future__ import annotations

import argparse
import os
import statistics
import time

import leuven_rt as lr
from leuven_rt.data.synthetic import make_data

TARGET = 10.0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3, help="runs (default 3)")
    parser.add_argument("--quiet", action="store_true", help="no progress on stderr")
    arguments = parser.parse_args()
    log = make_data(seed=0)
    print(f"identify make_data(seed=0): {log.data.samples} samples, {os.cpu_count()} cores")
    walls = []
    for run in range(arguments.runs):
        began, cpu = time.perf_counter(), time.process_time()
        result = lr.identify(log.data, progress=not arguments.quiet)
        wall, cpu = time.perf_counter() - began, time.process_time() - cpu
        walls.append(wall)
        rms = lr.predict(result.model, log.data).rms / log.noise_std
        named = ", ".join(result.diagnosis.named_effects)
        print(f"run {run + 1}: {wall:.2f} s wall, {cpu:.2f} s CPU, load average {os.getloadavg()[0]:.2f}; "
              f"named {named}; file rms {rms:.3f}x the noise", flush=True)  # fmt: skip
    median = statistics.median(walls)
    verdict = "met" if median <= TARGET else "missed"
    print(f"median {median:.2f} s over {len(walls)} runs (target {TARGET:g} s: {verdict})")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
