"""The exceptions of leuven_rt; all are ``ValueError`` subclasses.

They are defined in the Rust extension, so that the core and the Python modules raise the same
classes.
"""

from ._core import DivergenceError, InputError, ParameterError

__all__ = ["DivergenceError", "InputError", "ParameterError"]
