"""Cost of reading a CSV log (``leuven_rt.data.records.load_csv``) in each dialect it reads: a
generated log of t, x, f, v (1 million rows by default, numbers written with 10 significant
digits, about 51 MB) written with `,`, `;` and decimal commas, tabs, quoted names, and empty
trailing columns (rows ending in `,,`), each read in a subprocess of its own; prints the best
wall time of ``--repeat`` reads, µs per row, and whether the columns equal the plain file's.

    python benches/load_csv.py               # 1 000 000 rows
    python benches/load_csv.py --rows 3600000
"""

from __future__ import annotations

import argparse
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

DIALECTS = ("plain", "semicolon-decimal-comma", "tab", "quoted-names", "trailing-empty")


def write(rows: int, folder: Path) -> dict[str, Path]:
    t = np.arange(rows) * 1e-3
    rng = np.random.default_rng(0)
    x = 0.01 * np.sin(np.pi * t) + 1e-7 * rng.standard_normal(rows)
    table = np.column_stack((t, x, np.cos(t), np.gradient(x, 1e-3)))
    plain = folder / "plain.csv"
    np.savetxt(plain, table, delimiter=",", header="t,x,f,v", comments="", fmt="%.10g")
    lines = plain.read_text(encoding="utf-8").splitlines()
    texts = {
        "semicolon-decimal-comma": [line.replace(",", ";").replace(".", ",") for line in lines],
        "tab": [line.replace(",", "\t") for line in lines],
        "quoted-names": ['"t","x","f","v"', *lines[1:]],
        "trailing-empty": [line + ",," for line in lines],
    }
    paths = {"plain": plain}
    for name, text in texts.items():
        paths[name] = folder / f"{name}.csv"
        paths[name].write_text("\n".join(text) + "\n", encoding="utf-8")
    return paths


def read(path: Path, plain: Path, repeat: int) -> None:
    """In the subprocess: the best of ``repeat`` reads, and whether they equal the plain file's."""
    from leuven_rt.data.records import load_csv

    best = float("inf")
    for _ in range(repeat):
        began = time.perf_counter()
        columns = load_csv(path)
        best = min(best, time.perf_counter() - began)
    reference = load_csv(plain)
    same = sorted(columns) == sorted(reference) and all(
        np.array_equal(columns[k], reference[k]) for k in reference
    )
    rows = columns["t"].size
    print(f"{path.stem:24s} {best:7.2f} s  {1e6 * best / rows:6.2f} µs/row  same numbers: {same}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rows", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--read", nargs=2, help=argparse.SUPPRESS)  # the subprocess's own call
    arguments = parser.parse_args()
    if arguments.read:
        read(Path(arguments.read[0]), Path(arguments.read[1]), arguments.repeat)
        return
    with tempfile.TemporaryDirectory() as name:
        paths = write(arguments.rows, Path(name))
        print(f"{arguments.rows} rows of t,x,f,v ({paths['plain'].stat().st_size / 1e6:.0f} MB plain)")
        for dialect in DIALECTS:
            command = [sys.executable, __file__, "--read", str(paths[dialect]), str(paths["plain"])]
            subprocess.run([*command, "--repeat", str(arguments.repeat)], check=True)


if __name__ == "__main__":
    main()
