"""Wall time of ``leuven_rt.diagnose`` on a generated log of about 30 000 samples with hidden
effects (target: under 30 s on a 2-core machine), and on the EMPS estimation set when present.

    python benches/diagnose.py
"""

from __future__ import annotations

import os
import time
from pathlib import Path

import leuven_rt as lr
from leuven_rt.discrepancy.hidden import make_hidden

TRUTH = ("coulomb", "viscous", "presliding_hysteresis", "position_dependence", "inertia")
EMPS = Path(__file__).resolve().parents[2].parent / "shared" / "data" / "emps" / "DATA_EMPS.mat"


def timed(data: object, label: str) -> None:
    began = time.perf_counter()
    diagnosis = lr.diagnose(data, "coulomb,viscous", progress=True)
    seconds = time.perf_counter() - began
    print(f"{label}: {diagnosis.samples} samples, {seconds:.1f} s; named {diagnosis.named_effects}; "
          f"rms {diagnosis.rms_before:.3g} -> {diagnosis.rms_after:.3g} N "
          f"({diagnosis.rms_after / diagnosis.noise_std:.2f}x the noise floor)")  # fmt: skip


def main() -> None:
    print(f"cores: {os.cpu_count()}")
    hidden = make_hidden(TRUTH, dt=2e-4)
    timed(hidden.data, f"generated, hidden {', '.join(TRUTH[2:])}")
    if EMPS.is_file():
        timed(EMPS, "EMPS DATA_EMPS.mat")
    else:
        print(f"EMPS skipped: {EMPS} is absent")


if __name__ == "__main__":
    main()
