"""Parameters of the modified Leuven model: one validated, immutable set, with its JSON form.

The keys are those of docs/parameters.md#keys. Python coerces the types; the values are validated by
gms-core, once, at construction, so that Python and Rust accept exactly the same parameter sets. The
validated core object is kept on the instance and handed to every engine (:func:`core_params`), which
takes it without checking it again.
"""

from __future__ import annotations

import numbers
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, fields
from typing import Any

from . import _core
from ._checks import real_array
from .errors import ModelFileError, ParameterError, data_of, shown

#: gms-core's validated parameter set (``_core.CoreParams``), built from any object with the attributes
#: of :class:`Params`; looked up by name so that it types as ``Any`` whether or not _core.pyi lists it.
_CoreParams: Any = vars(_core)["CoreParams"]

#: Keys that every parameter set must give.
REQUIRED_KEYS = ("Fc", "Fs", "Vs", "delta", "n")


def _real(key: str, value: Any, index: int | None = None) -> float:
    """``value`` as a float; ``key`` names it, with its ``index`` in a sequence when it has one."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ParameterError(
            f"`{key}` must be a real number, got {shown(value)!r:.80}",
            kind="not_real",
            field=key,
            value=value,
            index=index,
        )
    try:
        return float(value)
    except OverflowError:  # an integer beyond the float range (a JSON file may hold one)
        raise ParameterError(
            f"`{key}` must be finite, got an integer of {len(str(value))} digits, beyond the float range",
            kind="not_finite_value",
            field=key,
            value=value,
            index=index,
        ) from None


def _reals(key: str, values: Any) -> tuple[float, ...]:
    if isinstance(values, (str, bytes, bytearray)) or (
        not isinstance(values, Sequence) and not hasattr(values, "__array__")
    ):
        raise ParameterError(
            f"`{key}` must be a sequence of real numbers, got {shown(values)!r:.80}",
            kind="not_real",
            field=key,
            value=values,
        )
    if hasattr(values, "__array__"):  # numpy and friends: the dtype says what the items are
        array = real_array(values, key, ParameterError)
        if array.ndim != 1:
            raise ParameterError(
                f"`{key}` must be a flat sequence of real numbers, got shape {array.shape}: "
                f"{shown(values)!r:.80}",
                kind="shape",
                field=key,
                expected="(N,)",
                got=array.shape,
            )
        items = array.tolist()
    else:
        items = list(values)
    if any(isinstance(item, (list, tuple)) for item in items):
        raise ParameterError(
            f"`{key}` must be a flat sequence of real numbers, got {shown(values)!r:.80}",
            kind="shape",
            field=key,
            value=values,
        )
    return tuple(_real(f"{key}[{index}]", item, index) for index, item in enumerate(items))


@dataclass(frozen=True, kw_only=True)
class Params:
    """Modified Leuven model parameters (SI units).

    Give the hysteresis either as Maxwell-slip elements (``W`` and ``Delta``, same length, at
    most ``MAX_ELEMENTS``) or as a linear spring ``sigma0`` (LuGre when ``n = 1``). ``W`` and
    ``Delta`` may be given as lists or tuples of real numbers (1-D arrays are accepted too); they
    are stored as tuples of floats.
    ``Fc_neg``/``Fs_neg``/``sigma2_neg`` (the levels and the viscous coefficient for v < 0)
    default to ``Fc``/``Fs``/``sigma2``; a value given is kept and written to the parameter file
    even when it equals its default, so that the file says what was given. Raises
    :class:`ParameterError` naming the key and showing what was expected and what came.
    """

    Fc: float
    Fs: float
    Vs: float
    delta: float
    n: float
    sigma1: float = 0.0
    sigma2: float = 0.0
    W: Sequence[float] | None = None
    """Maxwell-slip element weights [N]; stored as a tuple of floats."""
    Delta: Sequence[float] | None = None
    """Maxwell-slip break deflections [m]; stored as a tuple of floats."""
    Fc_neg: float | None = None
    Fs_neg: float | None = None
    sigma2_neg: float | None = None
    sigma0: float | None = None

    def __post_init__(self) -> None:
        for key in ("Fc", "Fs", "Vs", "delta", "n", "sigma1", "sigma2"):
            object.__setattr__(self, key, _real(key, getattr(self, key)))
        for key in ("Fc_neg", "Fs_neg", "sigma2_neg", "sigma0"):
            if getattr(self, key) is not None:
                object.__setattr__(self, key, _real(key, getattr(self, key)))
        if (self.W is None) != (self.Delta is None):
            given, missing = ("W", "Delta") if self.Delta is None else ("Delta", "W")
            raise ParameterError(
                f"`{given}` was given without `{missing}`: give both or neither",
                kind="missing_key",
                field=missing,
            )
        if self.W is not None and self.Delta is not None:
            object.__setattr__(self, "W", _reals("W", self.W))
            object.__setattr__(self, "Delta", _reals("Delta", self.Delta))
        # gms-core checks the values once (ParameterError naming the first rule broken); the
        # validated set is kept for the engines as a plain attribute, not a dataclass field, so
        # it stays out of repr, ==, hash, fields() and dataclasses.replace.
        object.__setattr__(self, "_validated", _CoreParams(self))

    def __getstate__(self) -> dict[str, Any]:
        """The fields only (for pickle and copy): the core object is rebuilt on restore."""
        return {field.name: getattr(self, field.name) for field in fields(self)}

    def __setstate__(self, state: dict[str, Any]) -> None:
        for key, value in state.items():
            object.__setattr__(self, key, value)
        object.__setattr__(self, "_validated", _CoreParams(self))

    @property
    def elements(self) -> int:
        """Number of Maxwell-slip elements N (0 for linear hysteresis)."""
        return 0 if self.W is None else len(self.W)

    @property
    def Fc_negative(self) -> float:
        """The Coulomb level for v < 0 (``Fc_neg``, or ``Fc`` when not given)."""
        return self.Fc if self.Fc_neg is None else self.Fc_neg

    @property
    def Fs_negative(self) -> float:
        """The static level for v < 0 (``Fs_neg``, or ``Fs`` when not given)."""
        return self.Fs if self.Fs_neg is None else self.Fs_neg

    @property
    def sigma2_negative(self) -> float:
        """The viscous coefficient for v < 0 (``sigma2_neg``, or ``sigma2`` when not given)."""
        return self.sigma2 if self.sigma2_neg is None else self.sigma2_neg

    def to_dict(self) -> dict[str, Any]:
        """The parameter-file form: keys of docs/parameters.md#keys, unset optional keys left out."""
        out: dict[str, Any] = {}
        for field in fields(self):
            value = getattr(self, field.name)
            if value is not None:
                out[field.name] = list(value) if isinstance(value, tuple) else value
        return out

    @classmethod
    def from_dict(cls, mapping: Mapping[str, Any]) -> Params:
        """Builds from a mapping with the keys of docs/parameters.md#keys; unknown or missing keys raise."""
        if not isinstance(mapping, Mapping):
            raise ParameterError(
                f"parameters must be a mapping, got {type(mapping).__name__}",
                kind="wrong_type",
                value=mapping,
            )
        known = {field.name for field in fields(cls)}
        unknown = sorted(set(mapping) - known, key=repr)
        if unknown:
            raise ParameterError(
                f"unknown parameter keys {unknown}; expected keys among {sorted(known)}",
                kind="unknown_key",
                field=str(unknown[0]),
                expected=sorted(known),
                got=sorted(mapping, key=repr),
            )
        missing = [key for key in REQUIRED_KEYS if key not in mapping]
        if missing:
            raise ParameterError(
                f"missing parameter keys {missing}",
                kind="missing_key",
                field=missing[0],
                expected=list(REQUIRED_KEYS),
                got=sorted(mapping, key=repr),
            )
        return cls(**mapping)

    def to_json(self) -> str:
        """The parameter file as JSON text, written by gms-file (the writer of the model file)."""
        return _core.parameter_file_to_json(self.to_dict())

    @classmethod
    def from_json(cls, text: str) -> Params:
        """Parses JSON text of a parameter file with gms-file, the reader the C library uses: a
        refusal raises :class:`~leuven_rt.errors.ModelFileError` naming the key."""
        if not isinstance(text, str):
            raise ParameterError(
                f"a parameter file's text must be a str, got {type(text).__name__}",
                kind="wrong_type",
                field="text",
                value=text,
            )
        return cls(**_core.parameter_file_from_json(text))

    def save(self, path: str | os.PathLike[str]) -> None:
        """Writes the parameter file, atomically: a failure leaves no partial file behind."""
        from ._output import write_text

        write_text(path, self.to_json() + "\n")

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Params:
        """Reads a parameter file (UTF-8 JSON); a file that cannot be read or decoded raises
        :class:`ParameterError` naming it; a text the reader refuses raises its
        :class:`~leuven_rt.errors.ModelFileError` under the file's name, with the same data."""
        try:
            with open(path, encoding="utf-8") as file:
                text = file.read()
        except UnicodeDecodeError as error:
            raise ParameterError(
                f"parameter file {path} is not UTF-8 text: {error}", kind="not_text", value=os.fspath(path)
            ) from None
        except OSError as error:
            raise ParameterError(
                f"cannot read parameter file {path}: {error.strerror or error}",
                kind="unreadable_file",
                value=os.fspath(path),
            ) from None
        try:
            return cls.from_json(text)
        except ModelFileError as error:
            # The reader's class, and where a syntax error is, are kept under the longer message.
            again = ModelFileError(f"{path}: {error}", **data_of(error))
            again.line, again.column = error.line, error.column
            raise again from None
        except ParameterError as error:
            raise ParameterError(f"{path}: {error}", **data_of(error)) from None


#: A parameter set: a :class:`Params`, or a mapping with its keys.
ParamsLike = Params | Mapping[str, Any]


def as_params(params: ParamsLike) -> Params:
    """Accepts a :class:`Params` or a mapping of its keys."""
    if isinstance(params, Params):
        return params
    if isinstance(params, Mapping):
        return Params.from_dict(params)
    raise ParameterError(
        f"`params` must be a leuven_rt.Params or a mapping, got {type(params).__name__}",
        kind="wrong_type",
        field="params",
        value=params,
    )


def core_params(params: ParamsLike) -> Any:
    """What the engine constructors take: the gms-core set validated when ``params`` became a
    :class:`Params` (a mapping is turned into one first), so it is not read or checked again."""
    return vars(as_params(params))["_validated"]
