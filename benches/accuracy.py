"""Prints the explicit-vs-implicit accuracy tables: ``python benches/accuracy.py``.

The numbers come from :func:`leuven_rt.studies.accuracy.full_report` (velocity- and force-driven);
docs/benchmarks.md#accuracy-of-the-step quotes this output.
"""

from __future__ import annotations

import time

from leuven_rt.studies.accuracy import full_report


def main() -> None:
    start = time.perf_counter()
    print(full_report())
    print(f"\n({time.perf_counter() - start:.2f} s)")


if __name__ == "__main__":
    main()
