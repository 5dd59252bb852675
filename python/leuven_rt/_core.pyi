"""Type stubs of the Rust extension (crates/gms-py)."""

from collections.abc import Sequence
from typing import Any, Literal, Protocol, final

import numpy as np
from numpy.typing import NDArray
from typing_extensions import Self, disjoint_base

__all__ = [
    "ERROR_KINDS",
    "MAX_ELEMENTS",
    "MAX_HARMONICS",
    "MAX_ITERATIONS",
    "MAX_RIPPLES",
    "MODEL_FILE_FORMAT",
    "MODEL_FILE_VERSION",
    "CompensatorEngine",
    "ConcurrentUseError",
    "CoreLevel",
    "CoreParams",
    "CorePositionForce",
    "DivergenceError",
    "Engine",
    "InputError",
    "MassEngine",
    "ModelFileError",
    "OnlineIdentifier",
    "ParameterError",
    "__version__",
    "check_params",
    "model_file_from_json",
    "model_file_from_object",
    "model_file_load",
    "model_file_to_json",
    "parameter_file_from_json",
    "parameter_file_to_json",
    "sensitivities",
    "simulate_sets",
    "slip_responses",
]

__version__: str
MAX_ELEMENTS: int
MAX_ITERATIONS: int
MAX_RIPPLES: int
MAX_HARMONICS: int
ERROR_KINDS: list[str]
MODEL_FILE_FORMAT: str
MODEL_FILE_VERSION: int

_Scheme = Literal["implicit", "explicit"]
_Mode = Literal["feedforward", "observer"]

class _ObjectInit:
    """The errors' ``__init__`` is ``object.__init__`` at run time (``BaseException.__init__``
    refuses keywords); ``__new__`` takes the arguments. A base of its own, so that type checkers
    check calls against ``__new__``."""

    def __init__(self) -> None: ...

class _ErrorData(_ObjectInit):
    """The data every error of the package carries (docs/errors.md#error-data)."""

    kind: str | None
    field: str | None
    value: Any
    bound: Any
    index: int | None
    sample: int | None
    channel: int | None
    expected: Any
    got: Any
    def __new__(
        cls,
        message: str,
        /,
        *,
        kind: str | None = None,
        field: str | None = None,
        value: object = None,
        bound: object = None,
        index: int | None = None,
        sample: int | None = None,
        channel: int | None = None,
        expected: object = None,
        got: object = None,
    ) -> Self: ...

class ParameterError(_ErrorData, ValueError): ...
class InputError(_ErrorData, ValueError): ...
class DivergenceError(_ErrorData, ValueError): ...
class ConcurrentUseError(_ErrorData, RuntimeError): ...

class ModelFileError(ParameterError):
    """The file reader's refusal: ``field`` is the key path; ``line`` and ``column`` place a
    syntax error."""

    line: int | None
    column: int | None

class _ParamsLike(Protocol):
    """What the extension reads from a parameter set: the attributes of ``leuven_rt.Params``."""

    @property
    def Fc(self) -> float: ...
    @property
    def Fs(self) -> float: ...
    @property
    def Vs(self) -> float: ...
    @property
    def delta(self) -> float: ...
    @property
    def n(self) -> float: ...
    @property
    def sigma1(self) -> float: ...
    @property
    def sigma2(self) -> float: ...
    @property
    def Fc_neg(self) -> float | None: ...
    @property
    def Fs_neg(self) -> float | None: ...
    @property
    def sigma2_neg(self) -> float | None: ...
    @property
    def sigma0(self) -> float | None: ...
    @property
    def W(self) -> Any: ...
    @property
    def Delta(self) -> Any: ...

@final
class CoreParams:
    """A parameter set validated once; every engine takes it in place of a ``Params``."""

    def __new__(cls, params: _ParamsLike) -> Self: ...
    @property
    def elements(self) -> int: ...

class _RippleLike(Protocol):
    """What the extension reads from a ripple: the attributes of ``leuven_rt.level.Ripple``."""

    @property
    def period(self) -> float: ...
    @property
    def cos(self) -> Any: ...
    @property
    def sin(self) -> Any: ...

class _SeriesLike(Protocol):
    """What the extension reads from a level or a position force: the attributes of
    ``leuven_rt.level.PositionLevel`` and ``leuven_rt.level.PositionForce``."""

    @property
    def middle(self) -> float: ...
    @property
    def half_stroke(self) -> float: ...
    @property
    def trend(self) -> Any: ...
    @property
    def ripples(self) -> Any: ...

@final
class CoreLevel:
    """A position-dependent level validated once; the compensator and the runs take it."""

    def __new__(cls, level: _SeriesLike | CoreLevel) -> Self: ...
    def factor(self, x: NDArray[np.float64]) -> NDArray[np.float64]: ...
    @property
    def ripples(self) -> int: ...

@final
class CorePositionForce:
    """A position force validated once; the compensator and the runs take it."""

    def __new__(cls, force: _SeriesLike | CorePositionForce) -> Self: ...
    def force(self, x: NDArray[np.float64]) -> NDArray[np.float64]: ...
    @property
    def ripples(self) -> int: ...

def check_params(params: _ParamsLike | CoreParams) -> None: ...
def model_file_from_json(text: str) -> dict[str, Any]: ...
def model_file_from_object(object: Any) -> dict[str, Any]: ...
def model_file_load(path: str) -> dict[str, Any]: ...
def model_file_to_json(object: Any) -> str: ...
def parameter_file_from_json(text: str) -> dict[str, Any]: ...
def parameter_file_to_json(object: Any) -> str: ...
def slip_responses(x: NDArray[np.float64], delta: NDArray[np.float64]) -> NDArray[np.float64]: ...
def sensitivities(
    params: _ParamsLike | CoreParams,
    signal: NDArray[np.float64],
    dt: float,
    position: bool,
    scheme: _Scheme,
    rows: NDArray[np.int64] | NDArray[np.uint64],
) -> tuple[NDArray[np.float64], NDArray[np.float64], list[str]]: ...
def simulate_sets(
    params: Sequence[_ParamsLike | CoreParams],
    signal: NDArray[np.float64],
    dt: float,
    position: bool,
    scheme: _Scheme,
) -> NDArray[np.float64]: ...

@disjoint_base
class Engine:
    def __new__(
        cls, params: _ParamsLike | CoreParams, channels: int = 1, scheme: _Scheme | None = None
    ) -> Self: ...
    @property
    def params(self) -> Any: ...
    @property
    def channels(self) -> int: ...
    @property
    def elements(self) -> int: ...
    @property
    def scheme(self) -> _Scheme: ...
    def step(self, v: float, dt: float) -> float: ...
    def step_position(self, x: float, dt: float) -> float: ...
    def reset(self) -> None: ...
    def _step_channels(
        self, input: NDArray[np.float64], dt: float, position: bool
    ) -> NDArray[np.float64]: ...
    def _run(
        self, input: NDArray[np.float64], dt: float, position: bool, out: NDArray[np.float64]
    ) -> None: ...
    def _run_position_level(
        self,
        input: NDArray[np.float64],
        dt: float,
        level: _SeriesLike | CoreLevel | None,
        position_force: _SeriesLike | CorePositionForce | None,
        out: NDArray[np.float64],
    ) -> None: ...
    def _run_level(
        self,
        v: NDArray[np.float64],
        x: NDArray[np.float64],
        dt: float,
        level: _SeriesLike | CoreLevel | None,
        position_force: _SeriesLike | CorePositionForce | None,
        out: NDArray[np.float64],
    ) -> None: ...
    def _run_position_deflection(
        self, x: NDArray[np.float64], dt: float
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]: ...
    def _get_state(
        self,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]: ...
    def _set_state(
        self,
        z: NDArray[np.float64],
        zeta: NDArray[np.float64],
        last: NDArray[np.float64],
        has_last: NDArray[np.bool_],
    ) -> None: ...

@disjoint_base
class CompensatorEngine:
    def __new__(
        cls,
        params: _ParamsLike | CoreParams,
        dt: float,
        mode: _Mode,
        level: _SeriesLike | CoreLevel | None = None,
        position_force: _SeriesLike | CorePositionForce | None = None,
        x: float | None = None,
    ) -> Self: ...
    def step(self, input: float) -> float: ...
    def step_trajectory(self, v: float, x: float) -> float: ...
    def set_position(self, x: float) -> None: ...
    @property
    def position(self) -> float | None: ...
    def set_params(self, params: _ParamsLike | CoreParams) -> None: ...
    def reset(self) -> None: ...
    @property
    def output(self) -> float: ...
    @property
    def params(self) -> Any: ...
    @property
    def dt(self) -> float: ...
    @property
    def mode(self) -> _Mode: ...
    @property
    def elements(self) -> int: ...
    def _state(self) -> tuple[float, list[float], float | None]: ...

@disjoint_base
class MassEngine:
    def __new__(
        cls,
        params: _ParamsLike | CoreParams,
        mass: float,
        stiffness: float | None = None,
        drive_speed: float | None = None,
        channels: int = 1,
        scheme: _Scheme | None = None,
    ) -> Self: ...
    @property
    def params(self) -> Any: ...
    @property
    def mass(self) -> float: ...
    @property
    def stiffness(self) -> float: ...
    @property
    def drive_speed(self) -> float: ...
    @property
    def channels(self) -> int: ...
    @property
    def elements(self) -> int: ...
    @property
    def scheme(self) -> _Scheme: ...
    def step(self, u: float, dt: float) -> tuple[float, float, float]: ...
    def _run(self, u: NDArray[np.float64], dt: float) -> NDArray[np.float64]: ...
    def _place(self, x: NDArray[np.float64], v: NDArray[np.float64]) -> None: ...
    def _get_state(
        self,
    ) -> tuple[
        NDArray[np.float64],
        NDArray[np.float64],
        NDArray[np.float64],
        NDArray[np.float64],
        NDArray[np.float64],
    ]: ...
    def _set_state(
        self,
        x: NDArray[np.float64],
        v: NDArray[np.float64],
        anchor: NDArray[np.float64],
        z: NDArray[np.float64],
        zeta: NDArray[np.float64],
    ) -> None: ...

@disjoint_base
class OnlineIdentifier:
    def __new__(
        cls,
        delta: list[float],
        initial: list[float],
        forgetting: float,
        initial_covariance: float,
        max_trace: float,
    ) -> Self: ...
    @property
    def elements(self) -> int: ...
    @property
    def Delta(self) -> list[float]: ...
    @property
    def covariance_trace(self) -> float: ...
    @property
    def covariance_resets(self) -> int: ...
    def update(self, x: float, v: float, f: float) -> float: ...
    def predict(self, x: float, v: float) -> float: ...
    def reset(self) -> None: ...
    def _run(
        self, x: NDArray[np.float64], v: NDArray[np.float64], f: NDArray[np.float64]
    ) -> NDArray[np.float64]: ...
    def _estimate(self) -> NDArray[np.float64]: ...
    def _covariance(self) -> NDArray[np.float64]: ...
