"""``identify_staged``: the staged fit of the modified Leuven model (its simulation-error
refinement included); the stages in order, on the training part of the record, scored on the rest.

1. derivatives: zero-phase Butterworth on the position, central differences (:mod:`.data`);
2. reversals and the presliding range, from the force transition after reversals (:mod:`.motion`);
3. sliding: Fc, Fs, Vs, δ, σ2 (and ``_neg`` levels) on steady sliding samples (:mod:`.sliding`);
4. presliding: W for Δ equally spaced up to the presliding range, N chosen by held-out presliding
   error unless given (:mod:`.presliding`);
5. σ1 and n, then all parameters but Δ, by simulation error (:mod:`.refine`);
6. the final model simulated over the whole record: training and held-out errors (:mod:`.report`).

The held-out part is the end of the record (``held_out`` of it); no stage sees it.
"""

from __future__ import annotations

import numbers
import time
from typing import Any, cast

import numpy as np

from .._checks import real_number
from .._core import MAX_ELEMENTS
from .._typing import BoolArray
from ..data.records import DataLike, as_motion_data
from ..data.segments import Segments, find_segments, transition_lengths
from ..data.signals import Derivatives, estimate_derivatives, noise_floor
from ..errors import DataError, InputError, shown
from ..progress import Progress, reporting
from ..simulation import simulate_position
from .presliding import CANDIDATE_ELEMENTS, fit_presliding
from .refine import WEIGHT_MARGIN, SimulationError, fit_transition, model_params, refine_jointly
from .report import IdentificationReport, IdentificationResult, Stage
from .sliding import fit_sliding

#: Sliding samples start this many presliding ranges after a reversal.
SLIDING_AFTER = 2.0
#: Presliding samples are those in this first share of the transition after a reversal (or the
#: start), where |Fh| is still well below g(v) and the state follows the position (z ≈ x).
PRESLIDING_SHARE = 0.3
#: Sliding samples must be steady: the speed changes by less than this share while the motion
#: covers one presliding range (|a|·range/v² below it), so the friction memory has caught up.
STEADY_SHARE = 0.1


def _check_options(elements: Any, held_out: Any, max_evaluations: Any, cutoff: Any, asymmetric: Any) -> None:
    if cutoff is not None:
        real_number(cutoff, "cutoff")  # its range is the filter's to check, against the data's rate
    if not isinstance(asymmetric, (bool, np.bool_)):
        raise InputError(
            f"`asymmetric` must be True or False, got {shown(asymmetric)!r:.80}",
            kind="wrong_type",
            field="asymmetric",
            value=asymmetric,
        )
    if elements is not None and (
        isinstance(elements, bool)
        or not isinstance(elements, numbers.Integral)
        or not 1 <= int(elements) <= MAX_ELEMENTS  # int() is exact for any Integral
    ):
        integer = isinstance(elements, numbers.Integral) and not isinstance(elements, bool)
        raise InputError(
            f"`elements` must be None or an integer in [1, {MAX_ELEMENTS}], got {shown(elements)!r}",
            kind="out_of_range" if integer else "not_integer",
            field="elements",
            value=elements,
            bound=(1 if int(elements) < 1 else MAX_ELEMENTS) if integer else None,
        )
    # numbers.Real declares no typed comparisons: compared as a float for the checker only.
    if (
        isinstance(held_out, bool)
        or not isinstance(held_out, numbers.Real)
        or not 0.0 <= cast(float, held_out) <= 0.5
    ):
        real = isinstance(held_out, numbers.Real) and not isinstance(held_out, bool)
        raise InputError(
            f"`held_out` must be a fraction in [0, 0.5], got {shown(held_out)!r}",
            kind="out_of_range" if real else "not_real",
            field="held_out",
            value=held_out,
            bound=(0.0 if cast(float, held_out) < 0.0 else 0.5) if real else None,
        )
    if (
        isinstance(max_evaluations, bool)
        or not isinstance(max_evaluations, numbers.Integral)
        or max_evaluations < 3
    ):
        integer = isinstance(max_evaluations, numbers.Integral) and not isinstance(max_evaluations, bool)
        raise InputError(
            f"`max_evaluations` must be an integer >= 3, got {shown(max_evaluations)!r}",
            kind="out_of_range" if integer else "not_integer",
            field="max_evaluations",
            value=max_evaluations,
            bound=3 if integer else None,
        )


def _presliding_range(segments: Segments, force: np.ndarray, noise: float, warnings: list[str]) -> float:
    lengths = transition_lengths(segments, force, noise)
    if lengths.size:
        return float(np.median(lengths))
    # No reversal reached sliding: the only transition left is the initial loading from rest.
    lengths = transition_lengths(segments, force, noise, from_start=True)
    if not lengths.size:
        raise DataError(
            "the presliding range cannot be estimated: after no reversal (nor after the start) does the "
            "force settle on a sliding level; the data must include moves long enough to slide",
            kind="not_identifiable",
            field="f",
        )
    warnings.append("presliding range estimated from the initial loading from rest only")
    # From rest the force rises by g, not 2g: the transition covers about half the range.
    return 2.0 * float(lengths[0])


def identify_staged(
    data: DataLike,
    *,
    elements: int | None = None,
    asymmetric: bool = False,
    cutoff: float | None = None,
    held_out: float = 0.25,
    max_evaluations: int = 30,
    progress: bool | Progress = False,
) -> IdentificationResult:
    """Fits the modified Leuven model to a log of position and force.

    ``data``: a :class:`MotionData`, a ``.csv`` (docs/data-and-reports.md#measured-data) or EMPS
    ``.mat`` path, or a mapping of columns ``t``, ``x``, ``f`` [, ``v``]. ``elements``: the number N
    of Maxwell-slip elements (default: chosen by held-out presliding error among 1..12).
    ``asymmetric``: fit ``Fc_neg``, ``Fs_neg`` too. ``cutoff``: the position filter's cutoff [Hz]
    (default a tenth of the Nyquist frequency). ``held_out``: the share of the record, at its end,
    kept for scoring. ``max_evaluations``: the budget of each simulation-error stage (least-squares
    function evaluations, Jacobians not counted). ``progress``: report the stages on stderr (True:
    a bar on a terminal, lines otherwise; or a :class:`~leuven_rt.progress.Progress`).

    Returns the parameters and an :class:`IdentificationReport`. Bad data raises
    :class:`DataError` (an :class:`InputError`).
    """
    began = time.perf_counter()
    _check_options(elements, held_out, max_evaluations, cutoff, asymmetric)
    record = as_motion_data(data)
    split = round(record.samples * (1.0 - held_out))
    training = record.slice(0, split)
    derivatives = estimate_derivatives(training, cutoff)
    noise = noise_floor(training.f)
    warnings: list[str] = []
    stages: list[Stage] = []

    segments = find_segments(training.x, derivatives.x)
    if segments.reversals == 0:
        warnings.append("no reversals in the data: presliding not identifiable beyond the initial loading")
    presliding_range = _presliding_range(segments, training.f, noise, warnings)

    sliding_rows = _sliding_rows(segments, derivatives, presliding_range)
    sliding = fit_sliding(derivatives.v[sliding_rows], training.f[sliding_rows], asymmetric)
    stages.append(Stage("sliding", sliding.rms, sliding.samples, sliding.condition, sliding.params()))

    inside = segments.travel <= PRESLIDING_SHARE * presliding_range
    check = (segments.segment_of() // 2) % 2 == 1
    candidates = CANDIDATE_ELEMENTS if elements is None else int(elements)
    presliding = fit_presliding(derivatives.x, derivatives.v, training.f, inside & ~check, inside & check,
                                presliding_range, candidates)  # fmt: skip
    # The regression assumes z follows x, which underestimates the weights near the transition;
    # model_params scales them up to balance Fs when they fall short, and the refinement goes on.
    weight_scale = max(
        1.0, WEIGHT_MARGIN * max(sliding.Fs, sliding.Fs_neg or 0.0) / float(np.sum(presliding.W))
    )
    stages.append(Stage("presliding", presliding.fit.rms, int(np.count_nonzero(inside)),
                        presliding.fit.condition,
                        {"elements": presliding.elements, "held_out_rms_by_elements": presliding.held_out_rms,
                         "weights_scaled_by": weight_scale}))  # fmt: skip

    sigma1 = max(presliding.viscous - sliding.sigma2, 0.0)
    start = model_params({**sliding.params(), "n": 2.0, "sigma1": sigma1}, presliding.W, presliding.Delta)
    with reporting(progress, "identify_staged") as reporter:
        stage = ["transition"]  # the stage the simulations count towards

        def tick() -> None:
            reporter.stage(stage[0], objective.evaluations, None, "simulations")

        objective = SimulationError(derivatives.x, training.dt, training.f, np.ones(split, dtype=bool), tick)
        transition = fit_transition(start, objective, max_evaluations)
        stages.append(Stage("transition", transition.rms, split, transition.condition,
                            {"sigma1": transition.params.sigma1, "n": transition.params.n}))  # fmt: skip
        stage[0] = "joint"
        joint = refine_jointly(transition.params, objective, max_evaluations)
        stages.append(Stage("joint", joint.rms, split, joint.condition,
                            {"simulations": objective.evaluations}))  # fmt: skip
    params = joint.params

    whole = estimate_derivatives(record, derivatives.cutoff)
    error = simulate_position(params, whole.x, record.dt) - record.f
    held = error[split:]
    if joint.condition > 1e8:
        warnings.append(f"the joint fit is poorly conditioned (condition {joint.condition:.3g}): "
                        "some parameters are not determined by this excitation")  # fmt: skip
    report = IdentificationReport(
        samples=record.samples, dt=record.dt, cutoff=derivatives.cutoff, noise_std=noise,
        reversals=segments.reversals, presliding_range=presliding_range,
        training_samples=split, held_out_samples=int(held.size),
        training_rms=float(np.sqrt(np.mean(error[:split] ** 2))),
        held_out_rms=float(np.sqrt(np.mean(held**2))) if held.size else float("nan"),
        stages=stages, warnings=warnings, seconds=time.perf_counter() - began,
    )  # fmt: skip
    return IdentificationResult(params=params, report=report)


def _sliding_rows(segments: Segments, derivatives: Derivatives, presliding_range: float) -> BoolArray:
    v, a = derivatives.v, derivatives.a
    steady = np.abs(a) * presliding_range <= STEADY_SHARE * v**2
    rows: BoolArray = (segments.travel > SLIDING_AFTER * presliding_range) & steady & (v != 0.0)
    return rows
