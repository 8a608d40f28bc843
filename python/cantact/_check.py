"""Checks of Python arguments before they reach C: types, shapes, finiteness, ranges. Every
failure is an InvalidInput naming the argument, its value and what it must be."""
import math
import numbers
import os

import numpy as np

from ._errors import invalid


def real(name, value, lo=None, hi=None, lo_closed=False, hi_closed=False):
    """A finite real number (not a bool) with lo < value < hi (closed ends if asked)."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
        raise invalid(f"{name} = {value!r}: must be a real number")
    try:
        v = float(value)
    except OverflowError:  # an integer like 10**400: beyond doubles
        raise invalid(f"{name} = an integer of {len(str(abs(int(value))))} digits: beyond double "
                      "precision (|value| < 1.8e308)") from None
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


def _reals(name, value):
    """A float64 C-contiguous copy of value, any shape, if it holds real numbers: strings,
    booleans, complex numbers, objects and ragged lists refused."""
    if isinstance(value, (str, bytes)):
        raise invalid(f"{name}: must be a number or an array of numbers, got a string")
    try:
        a = np.asarray(value)
    except Exception as exc:  # ragged lists and the like
        raise invalid(f"{name}: not an array of numbers ({exc})") from None
    if a.dtype == object and all(isinstance(x, numbers.Integral) for x in a.flat):
        raise invalid(f"{name}: integers beyond double precision (|value| < 1.8e308)")
    if a.dtype == object or a.dtype.kind not in "biuf":
        raise invalid(f"{name}: must hold real numbers, got dtype {a.dtype}")
    if a.dtype.kind == "b":
        raise invalid(f"{name}: must hold real numbers, got booleans")
    return np.array(a, dtype=np.float64, order="C", copy=True)


def array(name, value, positive=False, nonnegative=False, allow_empty=False):
    """A 1-D float64 C-contiguous copy of a number or sequence of real numbers, all finite
    (and > 0 or >= 0 when asked). A scalar becomes one element."""
    a = _reals(name, value)
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


def real_array(name, value, ndims=(1, 2), nan_ndims=()):
    """A float64 C-contiguous copy of an array of real numbers with a number of dimensions in
    ndims (a scalar is refused), no dimension of length 0, all finite, except that NaN (a
    missing point) is allowed when its number of dimensions is in nan_ndims."""
    a = _reals(name, value)
    if a.ndim not in ndims:
        raise invalid(f"{name}: {a.ndim} dimensions (shape {a.shape}): must have "
                      f"{' or '.join(map(str, ndims))}")
    if a.size == 0:
        raise invalid(f"{name}: shape {a.shape}: must not be empty")
    bad = np.isinf(a) if a.ndim in nan_ndims else ~np.isfinite(a)
    if bad.any():
        k = np.unravel_index(int(np.flatnonzero(bad)[0]), a.shape)
        raise invalid(f"{name}[{', '.join(map(str, k))}] = {float(a[k])!r}: must be finite"
                      + (" (or NaN, a missing point)" if a.ndim in nan_ndims else ""))
    return a


def path(name, value):
    """A file name (str, bytes or os.PathLike; not empty, no NUL) as bytes for C."""
    try:
        p = os.fsencode(os.fspath(value))
    except TypeError:
        raise invalid(f"{name} = {value!r}: must be a path (str, bytes or os.PathLike), got "
                      f"{type(value).__name__}") from None
    if not p:
        raise invalid(f"{name} = {value!r}: must not be empty")
    if b"\0" in p:
        raise invalid(f"{name} = {value!r}: must not contain a NUL character")
    return p
