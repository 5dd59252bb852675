"""The numba peers of benches/peers.py compute the library's step: otherwise the ratios of
docs/benchmarks.md would compare two different things. The bench itself refuses to print a ratio
for a peer that disagrees with ``leuven_rt.simulate`` by more than 1e-12 (implicit) or 1e-6
(explicit, past its stability limit at the bench's parameters), relative to the largest force;
here it runs small, with a channel count that leaves channels outside the batch kernel's groups
of eight, and the one-channel rows (LuGre by velocity and by position, Leuven with a
position-dependent level)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("numba", reason="the peers are numba loops: pip install 'leuven-rt[bench]'")

PEERS = Path(__file__).resolve().parents[2] / "benches" / "peers.py"


@pytest.mark.timeout(300)
def test_every_peer_agrees_with_the_library() -> None:
    run = subprocess.run([sys.executable, str(PEERS), "--quick"], capture_output=True, text=True, check=False)
    assert run.returncode == 0, run.stderr
    rows = [
        line for line in run.stdout.splitlines() if line.startswith("| LuGre") or line.startswith("| Leuven")
    ]
    # Four batch rows and three one-channel rows.
    assert len(rows) == 7, run.stdout
