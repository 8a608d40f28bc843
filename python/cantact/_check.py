"""Checks of Python arguments before they reach C: types, shapes, finiteness, ranges. Every
failure is an InvalidInput naming the argument, its value and what it must be."""
import math
import numbers

import numpy as np

from ._errors import invalid


def real(name, value, lo=None, hi=None, lo_closed=False, hi_closed=False):
    """A finite real number (not a bool) with lo < value < hi (closed ends if asked)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise invalid(f"{name} = {value!r}: must be a real number")
    v = float(value)
    if not math.isfinite(v):
        raise invalid(f"{name} = {v!r}: must be finite")
    if lo is not None and not (v >= lo if lo_closed else v > lo):
        raise invalid(f"{name} = {v!r}: must be {'>=' if lo_closed else '>'} {lo!r}")
    if hi is not None and not (v <= hi if hi_closed else v < hi):
        raise invalid(f"{name} = {v!r}: must be {'<=' if hi_closed else '<'} {hi!r}")
    return v


def integer(name, value, lo=None, hi=None):
    """An integer (not a bool) with lo <= value <= hi."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise invalid(f"{name} = {value!r}: must be an integer")
    v = int(value)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        raise invalid(f"{name} = {v}: must satisfy {lo} <= {name} <= {hi}")
    return v


def choice(name, value, options):
    """One of the keys of options; returns its value."""
    if not isinstance(value, str) or value not in options:
        raise invalid(f"{name} = {value!r}: must be one of {', '.join(map(repr, options))}")
    return options[value]


def array(name, value, positive=False, nonnegative=False, allow_empty=False):
    """A 1-D float64 C-contiguous copy of a number or sequence of real numbers, all finite
    (and > 0 or >= 0 when asked). A scalar becomes one element."""
    if isinstance(value, (str, bytes)):
        raise invalid(f"{name}: must be a number or an array of numbers, got a string")
    try:
        a = np.asarray(value)
    except Exception as exc:  # ragged lists and the like
        raise invalid(f"{name}: not an array of numbers ({exc})") from None
    if a.dtype == object or a.dtype.kind not in "biuf":
        raise invalid(f"{name}: must hold real numbers, got dtype {a.dtype}")
    if a.dtype.kind == "b":
        raise invalid(f"{name}: must hold real numbers, got booleans")
    a = np.array(a, dtype=np.float64, order="C", copy=True)
    if a.ndim == 0:
        a = a.reshape(1)
    if a.ndim != 1:
        raise invalid(f"{name}: must be one-dimensional, got shape {a.shape}")
    if a.size == 0 and not allow_empty:
        raise invalid(f"{name}: must not be empty")
    bad = ~np.isfinite(a)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise invalid(f"{name}[{k}] = {a[k]!r}: must be finite")
    if positive and (a <= 0).any():
        k = int(np.flatnonzero(a <= 0)[0])
        raise invalid(f"{name}[{k}] = {a[k]!r}: must be > 0")
    if nonnegative and (a < 0).any():
        k = int(np.flatnonzero(a < 0)[0])
        raise invalid(f"{name}[{k}] = {a[k]!r}: must be >= 0")
    return a
