"""The ``leuven-rt`` command line.

Every command that writes files checks all of its output paths before it starts (never an input
file, no existing file unless ``--force``, a folder that exists or can be made, a figure format
matplotlib writes) and writes them atomically: see :mod:`leuven_rt._output`. A refusal prints
``leuven-rt <command>: error: <message>`` on one line and exits with status 2.

The commands that read a log (``identify``, ``diagnose``, ``predict``) take ``--columns`` (the
log's own column names) and ``--units`` (linear or rotary), and print each warning of the loader
(resampling, units that look wrong) as ``leuven-rt <command>: warning: <message>`` on stderr.
``identify`` and ``diagnose`` report their progress on stderr (:mod:`leuven_rt.progress`: a bar on
a terminal, timestamped lines otherwise), never on stdout; ``--quiet`` silences it.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
import warnings
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from . import __version__
from .errors import (
    ConcurrentUseError,
    DivergenceError,
    InputError,
    ParameterError,
    ResamplingWarning,
    StackOverflowError,
    UnitsWarning,
)

if TYPE_CHECKING:
    from .data.records import MotionData
    from .progress import Progress

#: The documented errors (docs/errors.md): each ends a command with its one-line message and
#: status 2. Anything else is a bug, and keeps its traceback.
DOCUMENTED = (ParameterError, InputError, DivergenceError, StackOverflowError, ConcurrentUseError)

FORCE_HELP = "replace output files that exist (an input file is never overwritten)"


LOG_HELP = "the log: a .csv with columns t,x,f[,v] (SI units; see --columns) or an EMPS .mat file"


def plain_text(text: str) -> str:
    """A docstring's reStructuredText as a terminal shows it: roles such as ``:mod:`` and
    double-backquoted literals lose their markup, and keep their text."""
    return re.sub(r":[a-z]+:`~?([^`]+)`", r"\1", text).replace("``", "")


class EffectNames:
    """The names of the effect catalogue, for the ``--baseline`` help (argparse's ``%(effects)s``).
    Looked up when the help is printed, not when the parser is built: the catalogue needs the
    ``analysis`` extra, which ``leuven-rt --version`` and the lean core do not."""

    def __str__(self) -> str:
        try:
            from .fitting.structure import CATALOGUE
        except ImportError:  # the analysis extra is not installed
            return "the effects of docs/effects.md (with leuven-rt[analysis])"
        return ", ".join(CATALOGUE)


def _baseline(parser: argparse.ArgumentParser, what: str) -> None:
    """The ``--baseline`` option: ``what`` the effects are, and the names it takes."""
    option = parser.add_argument(
        "--baseline", default="coulomb,viscous", help=f"{what} (comma-separated, among %(effects)s)"
    )
    vars(option)["effects"] = EffectNames()  # argparse expands %(name)s from the option's attributes


def _add_log_options(parser: argparse.ArgumentParser, units: str | None = "linear") -> None:
    """``--columns`` and ``--units`` (default ``units``), for the commands that read a log."""
    parser.add_argument(
        "--columns",
        help="the log's column for each of t, x, f and optionally v, e.g. t=time,x=q7,f=q7_tau_J,v=dq7 "
        "(default: columns named t, x, f, v)",
    )
    parser.add_argument(
        "--units",
        choices=("linear", "rotary"),
        default=units,
        help="the kind of axis: linear (m, m/s, N) or rotary (rad, rad/s, N·m); default: "
        + (units or "the model file's"),
    )


def _load(arguments: argparse.Namespace) -> MotionData:
    """The log of ``arguments.data``, by ``--columns`` and ``--units``; the loader's warnings are
    printed as one line each on stderr (and stay in the record's ``notes``)."""
    from .data.records import as_motion_data, parse_column_map

    columns = None if arguments.columns is None else parse_column_map(arguments.columns)
    with warnings.catch_warnings():
        # Printed below as the command's own lines, instead of Python's file:line form.
        warnings.simplefilter("ignore", ResamplingWarning)
        warnings.simplefilter("ignore", UnitsWarning)
        record = as_motion_data(arguments.data, columns=columns, units=arguments.units)
    for note in record.notes:
        print(f"leuven-rt {arguments.command}: warning: {note}", file=sys.stderr)
    return record


def _folder_outputs(out: str, names: Sequence[str], force: bool) -> Path:
    """Checks the folder ``--out`` and the files a command will write into it, before the work."""
    from ._output import check_folder, check_outputs

    folder = check_folder(out, "--out")
    check_outputs([("--out file", folder / name, True) for name in names], force=force)
    return folder


def _demo(arguments: argparse.Namespace) -> int:
    from .studies.demo import FILES, run_demo, run_loop, run_story

    out = _folder_outputs(arguments.out, FILES, arguments.force)
    print(run_demo(out).text())
    print()
    print(run_story(out, progress=True).text())
    print()
    print(run_loop(progress=True).text())
    return 0


def _progress(arguments: argparse.Namespace) -> Progress:
    """The progress reporter of a long command: on stderr, nothing with ``--quiet``."""
    from .progress import Progress

    return Progress(f"leuven-rt {arguments.command}", "off" if arguments.quiet else "auto")


def _diagnose(arguments: argparse.Namespace) -> int:
    from ._output import check_outputs
    from .discrepancy import diagnose

    if arguments.plot is not None:
        check_outputs([("--plot", arguments.plot, True)], inputs=[arguments.data], force=arguments.force)
    record = _load(arguments)
    with _progress(arguments) as report:
        diagnosis = diagnose(record, arguments.baseline, progress=report)
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
    from .discrepancy import identify

    outputs: list[tuple[str, str, bool]] = [("-o/--output", arguments.output, False)]
    if arguments.report is not None:
        outputs.append(("--report", arguments.report, False))
    targets = check_outputs(outputs, inputs=[arguments.data], force=arguments.force)
    record = _load(arguments)
    with _progress(arguments) as report:
        result = identify(record, arguments.baseline, progress=report)
    texts = [result.model.to_json() + "\n", result.diagnosis.to_json() + "\n"]
    # Both files or neither: each is written beside its target and renamed once both are complete.
    write_files([(target, text_writer(text)) for target, text in zip(targets, texts, strict=False)])
    if not arguments.quiet:
        print(result.summary())
        print(f"model file ({record.units}): {arguments.output}")
    for warning in result.warnings if arguments.quiet else ():
        print(f"leuven-rt identify: warning: {warning}", file=sys.stderr)
    return 0


def _predict(arguments: argparse.Namespace) -> int:
    from ._output import check_outputs
    from .modelfile import ModelFile
    from .prediction import predict

    outputs: list[tuple[str, str, bool]] = [("-o/--output", arguments.output, False)]
    if arguments.plot is not None:
        outputs.append(("--plot", arguments.plot, True))
    target = check_outputs(outputs, inputs=[arguments.model, arguments.data], force=arguments.force)[0]
    model = ModelFile.load(arguments.model)
    if arguments.units is not None and arguments.units != model.units:
        raise InputError(
            f"`--units` is {arguments.units!r}, but the model file {arguments.model} is {model.units!r}",
            kind="units_mismatch",
            field="--units",
            value=arguments.units,
            expected=model.units,
        )
    arguments.units = model.units
    prediction = predict(model, _load(arguments), cutoff=arguments.cutoff)
    # The target was checked before the work; force here: only a file made meanwhile can be in the way.
    prediction.to_csv(target, force=True)
    if arguments.plot is not None:
        prediction.plot(arguments.plot, force=True)
    if arguments.json:
        print(json.dumps(prediction.to_dict()))
    else:
        print(prediction.summary())
        print(f"prediction: {arguments.output}")
    return 0


def _control(arguments: argparse.Namespace) -> int:
    from .studies.closed_loop import FILE, run

    out = _folder_outputs(arguments.out, [FILE], arguments.force)
    with _progress(arguments) as report:
        text = run(out, progress=report)
    print(text)
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``leuven-rt`` command."""
    parser = argparse.ArgumentParser(prog="leuven-rt", description=plain_text(__doc__ or ""))
    parser.add_argument("--version", action="version", version=f"leuven-rt {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    demo = commands.add_parser(
        "demo",
        help="simulate the presliding-to-sliding scenario, then diagnose a log with hidden effects, then "
        "identify a simulated stage from its log and compensate it in closed loop; write figures",
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
        "identify",
        help="fit the friction model a log supports and write its model file (.csv t,x,f[,v] or EMPS .mat)",
    )
    identify.add_argument("data", help=LOG_HELP)
    identify.add_argument(
        "-o", "--output", required=True, help="where to write the model file (JSON, docs/data-and-reports.md)"
    )
    identify.add_argument("--report", help="also write the diagnosis report here (JSON)")
    _baseline(identify, "effects the model starts from")
    identify.add_argument("--force", action="store_true", help=FORCE_HELP)
    identify.add_argument(
        "--quiet", action="store_true", help="no progress (on stderr) and no summary, only the warnings"
    )
    _add_log_options(identify)
    identify.set_defaults(run=_identify)
    diagnose = commands.add_parser(
        "diagnose",
        help="name the catalogue effects a friction model misses in a log, and how much each helps",
    )
    diagnose.add_argument("data", help=LOG_HELP)
    _baseline(diagnose, "effects already in the model")
    diagnose.add_argument(
        "--json",
        action="store_true",
        help="print the JSON report of docs/data-and-reports.md#diagnosis-report (progress stays on stderr)",
    )
    diagnose.add_argument("--quiet", action="store_true", help="no progress (on stderr)")
    diagnose.add_argument(
        "--plot", help="write the residual figure here (.png, .pdf, .svg, … : any format matplotlib writes)"
    )
    diagnose.add_argument("--force", action="store_true", help=FORCE_HELP)
    _add_log_options(diagnose)
    diagnose.set_defaults(run=_diagnose)
    predict = commands.add_parser(
        "predict",
        help="a model's force along a log's motion, next to the measured force: write t,f,f_model,friction",
    )
    predict.add_argument("model", help="the model file (or a plain parameter file) to run")
    predict.add_argument("data", help=LOG_HELP)
    predict.add_argument("-o", "--output", required=True, help="where to write the prediction (CSV)")
    predict.add_argument(
        "--json",
        action="store_true",
        help='print {"rms", "rms_causal", "samples", "units", "reconstruction", "warnings"} as JSON',
    )
    predict.add_argument(
        "--cutoff",
        type=float,
        help="the low-pass cutoff [Hz] of the motion signal, in place of the model file's "
        "(its acceleration's own cutoff is kept)",
    )
    predict.add_argument(
        "--plot", help="also draw the measured and predicted force here (.png, .pdf, .svg, …)"
    )
    predict.add_argument("--force", action="store_true", help=FORCE_HELP)
    _add_log_options(predict, units=None)  # the model file says its units; --units only confirms them
    predict.set_defaults(run=_predict)
    control = commands.add_parser(
        "control",
        help="closed-loop proof: PID on a simulated stage with none/Coulomb/Leuven compensation, hand-set "
        "and identified from a log of the stage",
    )
    control.add_argument("--out", default="out", help="folder for the figure (default: out)")
    control.add_argument("--force", action="store_true", help=FORCE_HELP)
    control.add_argument("--quiet", action="store_true", help="no progress of the identification (on stderr)")
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
