"""The ``leuven-rt`` command line."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path


def _demo(arguments: argparse.Namespace) -> int:
    from .demo import run_demo

    result = run_demo(Path(arguments.out))
    params = result.params
    print("Presliding-to-sliding scenario (position input, 10 kHz, implicit step)")
    print(f"  parameters: Fc = {params.Fc} N, Fs = {params.Fs} N, Vs = {params.Vs} m/s, "
          f"N = {params.elements} Maxwell-slip elements up to {max(params.Delta) * 1e6:.0f} µm")
    print(f"  samples: {result.samples}")
    print(f"  largest |F| while the amplitude stays below 5 µm (presliding): {result.presliding_peak:.3f} N")
    print(f"  median |F| over the last second (sliding): {result.sliding_force:.3f} N")
    print(f"  largest |F| overall: {result.peak_force:.3f} N")
    print(f"  figure: {result.figure}")
    return 0


def _accuracy(arguments: argparse.Namespace) -> int:
    from .accuracy import report

    print(report())
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``leuven-rt`` command."""
    parser = argparse.ArgumentParser(prog="leuven-rt", description=__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    demo = commands.add_parser("demo", help="simulate the presliding-to-sliding scenario, write figures")
    demo.add_argument("--out", default="out", help="folder for the figures (default: out)")
    demo.set_defaults(run=_demo)
    accuracy = commands.add_parser(
        "accuracy", help="RMS error of explicit and implicit steps against a 100x finer solution"
    )
    accuracy.set_defaults(run=_accuracy)
    arguments = parser.parse_args(argv)
    return int(arguments.run(arguments))


if __name__ == "__main__":
    sys.exit(main())
