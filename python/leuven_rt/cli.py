"""The ``leuven-rt`` command line."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

from . import __version__


def _demo(arguments: argparse.Namespace) -> int:
    from .studies.demo import run_demo, run_story

    print(run_demo(Path(arguments.out)).text())
    print()
    print(run_story(Path(arguments.out), progress=True).text())
    return 0


def _diagnose(arguments: argparse.Namespace) -> int:
    from .discrepancy import diagnose
    from .errors import InputError

    try:
        diagnosis = diagnose(arguments.data, arguments.baseline, progress=not arguments.json)
    except InputError as error:  # bad data or effect names: the message says what and where
        print(f"leuven-rt diagnose: error: {error}", file=sys.stderr)
        return 2
    if arguments.plot:
        from .discrepancy.plot import plot_diagnosis

        plot_diagnosis(diagnosis, arguments.plot)
    print(diagnosis.to_json() if arguments.json else diagnosis.story())
    return 0


def _accuracy(arguments: argparse.Namespace) -> int:
    from .studies.accuracy import full_report

    print(full_report())
    return 0


def _figures(arguments: argparse.Namespace) -> int:
    from .studies.figures import write_figures

    for report in write_figures(Path(arguments.out), quick=arguments.quick):
        print("\n".join(report.lines))
        print(f"  figure: {report.path}\n")
    return 0


def _identify(arguments: argparse.Namespace) -> int:
    from .errors import InputError
    from .identification import identify

    try:
        result = identify(
            arguments.data,
            elements=arguments.elements,
            asymmetric=arguments.asymmetric,
            cutoff=arguments.cutoff,
            held_out=arguments.held_out,
            progress=not arguments.quiet,
        )
    except InputError as error:  # bad data or options: the message says what and where
        print(f"leuven-rt identify: error: {error}", file=sys.stderr)
        return 2
    result.params.save(arguments.output)
    if arguments.report:
        Path(arguments.report).write_text(result.report.to_json() + "\n", encoding="utf-8")
    if not arguments.quiet:
        print(result.report.summary())
        print(f"parameters: {arguments.output}")
    for warning in result.report.warnings if arguments.quiet else ():
        print(f"warning: {warning}", file=sys.stderr)
    return 0


def _control(arguments: argparse.Namespace) -> int:
    from .studies.closed_loop import run

    print(run(Path(arguments.out)))
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``leuven-rt`` command."""
    parser = argparse.ArgumentParser(prog="leuven-rt", description=__doc__)
    parser.add_argument("--version", action="version", version=f"leuven-rt {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    demo = commands.add_parser(
        "demo",
        help="simulate the presliding-to-sliding scenario, then diagnose a log with hidden effects; "
        "write figures",
    )
    demo.add_argument("--out", default="out", help="folder for the figures (default: out)")
    demo.set_defaults(run=_demo)
    accuracy = commands.add_parser(
        "accuracy",
        help="RMS error of explicit and implicit steps against a 100x finer solution, "
        "velocity- and force-driven",
    )
    accuracy.set_defaults(run=_accuracy)
    figures = commands.add_parser(
        "figures", help="reproduce the paper's Figs. 1, 4/5 and the free response, print their numbers"
    )
    figures.add_argument("--out", default="out", help="folder for the PNGs (default: out)")
    figures.add_argument("--quick", action="store_true", help="two coarser step sizes for Fig. 1 (for tests)")
    figures.set_defaults(run=_figures)
    identify = commands.add_parser(
        "identify", help="fit the model to a log of position and force (.csv t,x,f[,v] or EMPS .mat)"
    )
    identify.add_argument(
        "data", help="the log: a .csv with columns t,x,f[,v] (SI units) or an EMPS .mat file"
    )
    identify.add_argument("-o", "--output", required=True, help="where to write the parameter file (JSON)")
    identify.add_argument("--report", help="also write the identification report here (JSON)")
    identify.add_argument(
        "--elements", type=int, help="number of Maxwell-slip elements (default: chosen from the data)"
    )
    identify.add_argument("--asymmetric", action="store_true", help="fit Fc_neg and Fs_neg as well")
    identify.add_argument(
        "--cutoff", type=float, help="cutoff of the position filter [Hz] (default: Nyquist/10)"
    )
    identify.add_argument("--held-out", type=float, default=0.25, help="share of the record kept for scoring")
    identify.add_argument("--quiet", action="store_true", help="no progress bar and no summary")
    identify.set_defaults(run=_identify)
    diagnose = commands.add_parser(
        "diagnose",
        help="name the catalogue effects a friction model misses in a log, and how much each helps",
    )
    diagnose.add_argument(
        "data", help="the log: a .csv with columns t,x,f[,v] (SI units) or an EMPS .mat file"
    )
    diagnose.add_argument(
        "--baseline", default="coulomb,viscous", help="effects already in the model (comma-separated)"
    )
    diagnose.add_argument(
        "--json",
        action="store_true",
        help="print the JSON report of docs/data-and-reports.md#diagnosis-report (no progress bar)",
    )
    diagnose.add_argument("--plot", help="write the residual figure to this PNG")
    diagnose.set_defaults(run=_diagnose)
    control = commands.add_parser(
        "control", help="closed-loop proof: PID on a simulated stage with none/Coulomb/Leuven compensation"
    )
    control.add_argument("--out", default="out", help="folder for the figure (default: out)")
    control.set_defaults(run=_control)
    arguments = parser.parse_args(argv)
    return int(arguments.run(arguments))


if __name__ == "__main__":
    sys.exit(main())
