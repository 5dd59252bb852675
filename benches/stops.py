"""How far the forces a log holds at its stops differ, per log with a velocity column: the spread
of the stops' means over the force between sliding in +x and in −x
(``leuven_rt.data.reconstruction.stops_and_spread``), and the samples the rounds weigh out as released
(below ``RELEASED``; docs/effects.md#the-motion-a-model-is-driven-by).

    python benches/stops.py FOLDER [FOLDER ...]

A folder's logs are its ``*.csv`` files (``t,x,f`` and ``v``; logs without ``v`` are skipped);
a second or two a log.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

from leuven_rt.data.reconstruction import RELEASED, released_at_stops, stops_and_spread
from leuven_rt.data.records import load_columns


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folders", nargs="+", type=Path)
    folders = parser.parse_args().folders
    for folder in folders:
        if not folder.is_dir():
            parser.error(f"FOLDER must be a folder of CSV logs, got {str(folder)!r}")
    print(f"| log | stops | spread / split | weighed out (below {RELEASED}) |")
    print("|---|---:|---:|---:|")
    for folder in folders:
        for path in sorted(folder.glob("*.csv")):
            columns = load_columns(path)
            if "v" not in columns:
                continue
            t, x, v, f = (columns[name] for name in ("t", "x", "v", "f"))
            dt = float(np.median(np.diff(t)))
            runs, spread = stops_and_spread(x, v, f, dt)
            out = int(np.count_nonzero(released_at_stops(x, v, f, dt)))
            shown = "too few stops" if math.isnan(spread) else f"{spread:.4f}"
            print(f"| {folder.name}/{path.stem} | {len(runs)} | {shown} | {out} of {x.size} |", flush=True)


if __name__ == "__main__":
    main()
