"""Cost of ``leuven_rt.diagnose`` against the length of the log: wall time, µs per sample and peak
memory for generated logs of 30 000 to 3.6 million samples (a one-hour log at 1 kHz), and the
wall time on the EMPS estimation set when present.

The logs come from :func:`leuven_rt.discrepancy.hidden.make_hidden` with the hidden effects
presliding_hysteresis, position_dependence and inertia (baseline coulomb, viscous; a logged
velocity), sampled at 5 kHz: a longer log is a longer run (the excitation repeated with fresh
random draws), as a long log is, 3.6 million samples 12 minutes of motion. Above
``Settings.rounds_samples`` (65 536) the rounds name effects on a sample of the log and the
written file is fitted on all of it (docs/effects.md#long-records). Each size runs in a
subprocess of its own (the log generated and saved first by another), so that the peak resident
memory (``ru_maxrss``) is that of one diagnose: the interpreter and its libraries included;
progress goes to stderr.

    python benches/diagnose.py                    # 30k, 100k, 300k, 1M, 3.6M samples and EMPS
    python benches/diagnose.py --quick            # 30k and 100k samples (CI-sized)
    python benches/diagnose.py --sizes 30000,1e6  # chosen sizes
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

TRUTH = ("coulomb", "viscous", "presliding_hysteresis", "position_dependence", "inertia")
BASELINE = "coulomb,viscous"
#: The logs' step [s] and the position's quantization [m].
STEP, QUANTIZATION = 2e-4, 1e-9
SIZES = (30_000, 100_000, 300_000, 1_000_000, 3_600_000)
QUICK = (30_000, 100_000)
EMPS = Path(__file__).resolve().parents[2] / "shared" / "data" / "emps" / "DATA_EMPS.mat"


def generate(samples: int, path: Path) -> None:
    from leuven_rt.discrepancy.hidden import make_hidden

    hidden = make_hidden(TRUTH, dt=STEP, quantization=QUANTIZATION, with_velocity=True, samples=samples)
    data = hidden.data
    assert data.v is not None
    np.savez(path, t=data.t, x=data.x, f=data.f, v=data.v)


def run(source: str) -> dict[str, object]:
    """One diagnose, in this process: of the saved log ``source``, or of EMPS when ``source`` is
    a .mat file."""
    import leuven_rt as lr
    from leuven_rt.data.records import MotionData

    data: object
    if source.endswith(".npz"):
        with np.load(source) as saved:
            data = MotionData(saved["t"], saved["x"], saved["f"], saved["v"])
    else:
        data = Path(source)
    began = time.perf_counter()
    diagnosis = lr.diagnose(data, BASELINE, progress=True)
    seconds = time.perf_counter() - began
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # kB on Linux
    return {
        "samples": diagnosis.samples, "seconds": seconds, "peak_mb": peak,
        "named": diagnosis.named_effects, "noise_ratio": diagnosis.rms_after / diagnosis.noise_std,
    }  # fmt: skip


def measure(argument: str) -> dict[str, object]:
    done = subprocess.run([sys.executable, __file__, "--one", argument], check=True,
                          stdout=subprocess.PIPE, text=True)  # fmt: skip
    result: dict[str, object] = json.loads(done.stdout.strip().splitlines()[-1])
    return result


def main() -> None:
    parser = argparse.ArgumentParser(
        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter
    )
    parser.add_argument("--quick", action="store_true", help="30k and 100k samples only")
    parser.add_argument("--sizes", help="comma-separated sizes in samples, e.g. 30000,1e6 (no EMPS)")
    parser.add_argument("--one", help=argparse.SUPPRESS)
    parser.add_argument("--generate", nargs=2, help=argparse.SUPPRESS)
    arguments = parser.parse_args()
    if arguments.generate:
        generate(int(arguments.generate[0]), Path(arguments.generate[1]))
        return
    if arguments.one:
        print(json.dumps(run(arguments.one)))
        return
    print(f"cores: {os.cpu_count()}; load average {os.getloadavg()[0]:.1f}; hidden {', '.join(TRUTH[2:])}; "
          f"baseline {BASELINE}; {1 / STEP:g} Hz")  # fmt: skip
    print("| samples | diagnose [s] | µs per sample | peak memory [MB] | named | final rms / noise | load |")
    print("|---:|---:|---:|---:|---|---:|---:|")
    with tempfile.TemporaryDirectory() as folder:
        sizes = QUICK if arguments.quick else SIZES
        if arguments.sizes:
            sizes = tuple(int(float(size)) for size in arguments.sizes.split(","))
        for size in sizes:
            path = Path(folder) / f"log{size}.npz"
            subprocess.run([sys.executable, __file__, "--generate", str(size), str(path)], check=True)
            r = measure(str(path))
            samples, seconds = int(str(r["samples"])), float(str(r["seconds"]))
            peak, ratio = float(str(r["peak_mb"])), float(str(r["noise_ratio"]))
            named = ", ".join(map(str, r["named"]))  # type: ignore[call-overload]
            cost = 1e6 * seconds / samples
            print(
                f"| {samples:,} | {seconds:.1f} | {cost:.0f} | {peak:.0f} | {named} | {ratio:.2f} | "
                f"{os.getloadavg()[0]:.1f} |",
                flush=True,
            )
            path.unlink()
    if arguments.quick or arguments.sizes:
        return
    if EMPS.is_file():
        r = measure(str(EMPS))
        seconds = float(str(r["seconds"]))
        print(f"EMPS DATA_EMPS.mat: {r['samples']} samples, {seconds:.1f} s, named {r['named']}")
    else:
        print(f"EMPS skipped: {EMPS} is absent")


if __name__ == "__main__":
    main()
