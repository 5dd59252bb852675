"""The ``leuven-rt`` command line.

Every command that writes files checks all of its output paths before it starts (never an input
file, no existing file unless ``--force``, a folder that exists or can be made, a figure format
matplotlib writes) and writes them atomically: see :mod:`leuven_rt._output`. A refusal prints
``leuven-rt <command>: error: <message>`` on one line and exits with status 2.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path

from . import __version__
from .errors import ConcurrentUseError, DivergenceError, InputError, ParameterError, StackOverflowError

#: The documented errors (docs/errors.md): each ends a command with its one-line message and
#: status 2. Anything else is a bug, and keeps its traceback.
DOCUMENTED = (ParameterError, InputError, DivergenceError, StackOverflowError, ConcurrentUseError)

FORCE_HELP = "replace output files that exist (an input file is never overwritten)"


def _folder_outputs(out: str, names: Sequence[str], force: bool) -> Path:
    """Checks the folder ``--out`` and the files a command will write into it, before the work."""
    from ._output import check_folder, check_outputs

    folder = check_folder(out, "--out")
    check_outputs([("--out file", folder / name, True) for name in names], force=force)
    return folder


def _demo(arguments: argparse.Namespace) -> int:
    from .studies.demo import FILES, run_demo, run_story

    out = _folder_outputs(arguments.out, FILES, arguments.force)
    print(run_demo(out).text())
    print()
    print(run_story(out, progress=True).text())
    return 0


def _diagnose(arguments: argparse.Namespace) -> int:
    from ._output import check_outputs
    from .discrepancy import diagnose

    if arguments.plot is not None:
        check_outputs([("--plot", arguments.plot, True)], inputs=[arguments.data], force=arguments.force)
    diagnosis = diagnose(arguments.data, arguments.baseline, progress=not arguments.json)
    if arguments.plot is not None:
        from .discrepancy.plot import plot_diagnosis

        plot_diagnosis(diagnosis, arguments.plot)
    print(diagnosis.to_json() if arguments.json else diagnosis.story())
    return 0


def _accuracy(arguments: argparse.Namespace) -> int:
    from .studies.accuracy import full_report

    print(full_report())
    return 0


def _figures(arguments: argparse.Namespace) -> int:
    from .studies.figures import FILES, write_figures

    out = _folder_outputs(arguments.out, FILES, arguments.force)
    for report in write_figures(out, quick=arguments.quick):
        print("\n".join(report.lines))
        print(f"  figure: {report.path}\n")
    return 0


def _identify(arguments: argparse.Namespace) -> int:
    from ._output import check_outputs, text_writer, write_files
    from .identification import identify

    outputs: list[tuple[str, str, bool]] = [("-o/--output", arguments.output, False)]
    if arguments.report is not None:
        outputs.append(("--report", arguments.report, False))
    targets = check_outputs(outputs, inputs=[arguments.data], force=arguments.force)
    result = identify(
        arguments.data,
        elements=arguments.elements,
        asymmetric=arguments.asymmetric,
        cutoff=arguments.cutoff,
        held_out=arguments.held_out,
        progress=not arguments.quiet,
    )
    texts = [result.params.to_json() + "\n", result.report.to_json() + "\n"]
    # Both files or neither: each is written beside its target and renamed once both are complete.
    write_files([(target, text_writer(text)) for target, text in zip(targets, texts, strict=False)])
    if not arguments.quiet:
        print(result.report.summary())
        print(f"parameters: {arguments.output}")
    for warning in result.report.warnings if arguments.quiet else ():
        print(f"warning: {warning}", file=sys.stderr)
    return 0


def _control(arguments: argparse.Namespace) -> int:
    from .studies.closed_loop import FILE, run

    print(run(_folder_outputs(arguments.out, [FILE], arguments.force)))
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
    demo.add_argument("--force", action="store_true", help=FORCE_HELP)
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
    figures.add_argument("--force", action="store_true", help=FORCE_HELP)
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
    identify.add_argument("--force", action="store_true", help=FORCE_HELP)
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
    diagnose.add_argument(
        "--plot", help="write the residual figure here (.png, .pdf, .svg, … : any format matplotlib writes)"
    )
    diagnose.add_argument("--force", action="store_true", help=FORCE_HELP)
    diagnose.set_defaults(run=_diagnose)
    control = commands.add_parser(
        "control", help="closed-loop proof: PID on a simulated stage with none/Coulomb/Leuven compensation"
    )
    control.add_argument("--out", default="out", help="folder for the figure (default: out)")
    control.add_argument("--force", action="store_true", help=FORCE_HELP)
    control.set_defaults(run=_control)
    arguments = parser.parse_args(argv)
    try:
        return int(arguments.run(arguments))
    except DOCUMENTED as error:  # a refusal: the message says what and where, no traceback
        message = " ".join(str(error).split())  # one line
        print(f"leuven-rt {arguments.command}: error: {message}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
