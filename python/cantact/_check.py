"""Checks of Python arguments before they reach C: types, shapes, finiteness, ranges. Every
failure is an InvalidInput naming the argument, its value and what it must be.

One rule turns a number given into the double the library computes with (_double): a real
number (int, float, NumPy's, Fraction, Decimal; a 0-d array holds one) is the double nearest
to it, an integer must be one a double holds exactly (every integer up to 2^53 is; 2^53 + 1
is not: give such a number as a float to have it rounded), and a number beyond the range of
doubles (|x| >= 1.8e308, or a non-zero |x| below 4.9e-324) is refused naming it ("beyond
double precision") rather than made inf or 0. Arrays follow the same rule element by element,
whatever their dtype."""
import decimal
import math
import numbers
import os

import numpy as np

from ._errors import invalid, memory, not_finite, out_of_memory, size_text

# every integer of magnitude up to 2^53 is a double exactly; above, only some are
_EXACT = 2**53


def _int_text(i):
    """An integer as a message shows it: its digits, or how many there are when they are many
    (Python refuses to print more than 4300)."""
    a = abs(i)
    if a < 10**24:
        return str(i)
    d = max(1, int(a.bit_length() * 0.30102999566398120))
    while 10**d <= a:
        d += 1
    while d > 1 and 10**(d - 1) > a:
        d -= 1
    return f"{'-' if i < 0 else ''}an integer of {d} digits"


def _text(value):
    """value's repr on one line, cut short when long."""
    try:
        if isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_)):
            return _int_text(int(value))
        r = " ".join(repr(value).split())
    except Exception:  # a repr that fails is no reason to hide the argument's type
        r = f"<{type(value).__name__}>"
    return r if len(r) <= 80 else r[:60] + f"... ({type(value).__name__})"


def _where(name, index):
    """name[i, j] of an element (name alone for a 0-d array)."""
    return f"{name}[{', '.join(map(str, index))}]" if index else name


def _double(name, value):
    """The double a real number given stands for (the module's one rule, see above)."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]  # a 0-d array: the number it holds
    if isinstance(value, (bool, np.bool_)):
        raise invalid(f"{name} = {value!r}: must be a real number, got a bool")
    if isinstance(value, np.ndarray):
        raise invalid(f"{name}: must be one real number, got an array of shape {value.shape}")
    if isinstance(value, numbers.Integral):
        i = int(value)
        try:
            v = float(i)
        except OverflowError:
            raise invalid(f"{name} = {_int_text(i)}: beyond double precision "
                          "(|value| < 1.8e308)") from None
        if abs(i) > _EXACT and int(v) != i:
            raise invalid(f"{name} = {i}: an integer no double holds exactly (the nearest is "
                          f"{v!r}): give it as a float to have it rounded")
        return v
    if isinstance(value, (numbers.Real, decimal.Decimal)):
        try:
            with np.errstate(over="ignore", under="ignore"):
                v = float(value)
        except OverflowError:
            v = math.inf
        except (TypeError, ValueError, ArithmeticError) as exc:  # Decimal("sNaN")
            raise invalid(f"{name} = {_text(value)}: no double stands for it ({exc})") from None
        # a finite number made inf, or a non-zero one made 0: beyond what doubles carry
        if (math.isinf(v) and value != v) or (v == 0.0 and value != 0):
            raise invalid(f"{name} = {_text(value)}: beyond double precision "
                          "(4.9e-324 <= |value| < 1.8e308, or 0)")
        return v
    if isinstance(value, numbers.Complex):
        raise invalid(f"{name} = {_text(value)}: must be a real number, got a complex number")
    raise invalid(f"{name} = {_text(value)}: must be a real number, got "
                  f"{type(value).__name__}")


def real(name, value, lo=None, hi=None, lo_closed=False, hi_closed=False):
    """A finite real number (not a bool) with lo < value < hi (closed ends if asked)."""
    v = _double(name, value)
    if not math.isfinite(v):
        raise invalid(f"{name} = {v!r}: must be finite")
    if lo is not None and not (v >= lo if lo_closed else v > lo):
        raise invalid(f"{name} = {v!r}: must be {'>=' if lo_closed else '>'} {lo!r}")
    if hi is not None and not (v <= hi if hi_closed else v < hi):
        raise invalid(f"{name} = {v!r}: must be {'<=' if hi_closed else '<'} {hi!r}")
    return v


def integer(name, value, lo=None, hi=None):
    """An integer (not a bool) with lo <= value <= hi."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]  # a 0-d array: the number it holds
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise invalid(f"{name} = {_text(value)}: must be an integer")
    v = int(value)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        raise invalid(f"{name} = {_int_text(v)}: must satisfy {lo} <= {name} <= {hi}")
    return v


def flag(name, value):
    """True or False (a bool or NumPy's, nothing else)."""
    if not isinstance(value, (bool, np.bool_)):
        raise invalid(f"{name} = {_text(value)}: must be True or False")
    return bool(value)


def choice(name, value, options):
    """One of the keys of options; returns its value."""
    if not isinstance(value, str) or value not in options:
        raise invalid(f"{name} = {_text(value)}: must be one of "
                      f"{', '.join(map(repr, options))}")
    return options[value]


def _reals(name, value):
    """A float64 C-contiguous copy of value, any shape, if it holds real numbers (the module's
    rule, element by element): strings, booleans, complex numbers, other objects and ragged
    lists refused."""
    if isinstance(value, (str, bytes, bytearray, memoryview)):  # NumPy reads bytes as uint8
        raise invalid(f"{name}: must be a number or an array of numbers, got "
                      f"{'a string' if isinstance(value, str) else type(value).__name__}")
    if isinstance(value, np.ma.MaskedArray):  # NumPy would use the values under the mask
        masked = int(np.ma.count_masked(value))
        if masked:
            raise invalid(f"{name}: a masked array with {masked} masked values: give the "
                          "values to use (NaN where a grid point is missing)")
        value = value.data
    try:
        a = np.asarray(value)
    except MemoryError:
        raise _unreadable(name, value) from None
    except Exception as exc:  # ragged lists and the like
        raise invalid(f"{name}: not an array of numbers ({exc})") from None
    with memory(f"{name}: a copy of {a.size} numbers ({size_text(a.size, 8)})"):
        if a.dtype == object:
            out = np.empty(a.shape, dtype=np.float64)
            for index, x in np.ndenumerate(a):
                out[index] = _double(_where(name, index), x)
            return out
        kind = a.dtype.kind
        if kind == "b":
            raise invalid(f"{name}: must hold real numbers, got booleans")
        if kind not in "iuf":
            raise invalid(f"{name}: must hold real numbers, got dtype {a.dtype}")
        with np.errstate(over="ignore", under="ignore"):
            out = np.array(a, dtype=np.float64, order="C", copy=True)
        if kind in "iu" and a.dtype.itemsize * 8 > 53:  # 64-bit integers: exactly doubles?
            limit = 2.0 ** (a.dtype.itemsize * 8 - (1 if kind == "i" else 0))
            fits = (out < limit) & (out >= -limit)  # back to the integer type
            with np.errstate(invalid="ignore"):
                back = np.where(fits, out, 0.0).astype(a.dtype)
            inexact = ~fits | (back != a)
            if inexact.any():
                index = np.unravel_index(int(np.flatnonzero(inexact.reshape(-1))[0]), a.shape)
                _double(_where(name, index), int(a[index]))
        elif kind == "f" and a.dtype.itemsize > 8:  # long double: wider than the library's
            lost = (np.isinf(out) & np.isfinite(a)) | ((out == 0) & (a != 0))
            if lost.any():
                index = np.unravel_index(int(np.flatnonzero(lost.reshape(-1))[0]), a.shape)
                _double(_where(name, index), a[index])
        return out


def _unreadable(name, value):
    """The OutOfMemory of an argument too large to be read into an array."""
    try:
        n = f"{len(value)} numbers"
    except Exception:
        n = "its numbers"
    return out_of_memory(f"{name}: an array of {n}")


def array(name, value, positive=False, nonnegative=False, allow_empty=False, finite=True):
    """A 1-D float64 C-contiguous copy of a number or sequence of real numbers, all finite
    (and > 0 or >= 0 when asked; finite=False: any double, for the library to judge). A scalar
    becomes one element."""
    a = _reals(name, value)
    if a.ndim == 0:
        a = a.reshape(1)
    if a.ndim != 1:
        raise invalid(f"{name}: must be one-dimensional, got shape {a.shape}")
    if a.size == 0 and not allow_empty:
        raise invalid(f"{name}: must not be empty")
    if not finite:
        return a
    with memory(f"{name}: checking {a.size} numbers (a mask of {size_text(a.size, 1)})"):
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
    with memory(f"{name}: checking {a.size} numbers (a mask of {size_text(a.size, 1)})"):
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


def finite_result(name, values, computed=None, may_be_nan=False, where=None):
    """values (an array the library filled) as they are, unless an entry it computed with a
    status of success (computed: a mask of them, default all) is not finite: then OutsideModel
    naming the first, never a NaN or inf handed back as a result. may_be_nan: NaN is the
    library's documented "not computed" of this figure (an unchecked row's closed form); inf
    is refused still. where(index) names an entry's place (default name[index])."""
    a = np.asarray(values, dtype=np.float64)
    bad = np.isinf(a) if may_be_nan else ~np.isfinite(a)
    if computed is not None:
        bad = bad & computed
    if not bad.any():
        return values
    index = np.unravel_index(int(np.flatnonzero(bad.reshape(-1))[0]), a.shape)
    at = where(index) if where else _where(name, index)
    raise not_finite(f"{at} = {float(a[index])!r}: not a finite number (beyond what doubles "
                     "carry, or a defect): refused, not handed back as a result")
