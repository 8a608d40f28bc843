"""Exceptions: every failure of the library raises one, carrying its status and message.

The rule of the module's boundary: no bare Python exception leaves a public call. Arguments
are checked before they reach C (_check.py) and say what is wrong; an allocation that fails
raises OutOfMemory naming the size asked for (memory() around the allocations of a request);
a number the library hands back must be finite where its status says it succeeded
(_check.finite_result). boundary() wraps every public function and method (__init__.py
applies it to everything the module exports) and turns whatever escaped those checks into the
module's classes (an exception of the caller's own progress callback excepted, raised as it
is): MemoryError into OutOfMemory, the errors of a bad argument (TypeError,
ValueError, OverflowError, LookupError, ArithmeticError) into InvalidInput (a TypeError into
InvalidType, an InvalidInput that is a TypeError too), both naming the call."""
import contextlib
import functools
import inspect

from ._ffi import ffi, lib

STATUS_NAMES = {
    lib.CT_OK: "CT_OK",
    lib.CT_EINVAL: "CT_EINVAL",
    lib.CT_ENOMEM: "CT_ENOMEM",
    lib.CT_ERANGE: "CT_ERANGE",
    lib.CT_ENOCONV: "CT_ENOCONV",
    lib.CT_EIO: "CT_EIO",
    lib.CT_ESKIPPED: "CT_ESKIPPED",
    lib.CT_EINTR: "CT_EINTR",
}


class Error(Exception):
    """A failure of cantact. .status is the library's status code (CT_EINVAL, ...),
    .status_name its name, .message the library's message (ct_error_message)."""

    def __init__(self, status, message):
        self.status = int(status)
        self.status_name = STATUS_NAMES.get(self.status, str(self.status))
        self.message = message
        super().__init__(f"{message} ({self.status_name}: {strerror(self.status)})")


class InvalidInput(Error, ValueError):
    """CT_EINVAL: a parameter or input outside its valid range (checked in Python before any
    pointer reaches C, or by the library)."""


class InvalidType(InvalidInput, TypeError):
    """CT_EINVAL: an argument of a type the call does not take (a TypeError as well, as
    Python's own)."""


class OutOfMemory(Error, MemoryError):
    """CT_ENOMEM."""


class OutsideModel(Error):
    """CT_ERANGE: the physics leaves the model (e.g. a crushed layer, u_max >= H*)."""


class NoConvergence(Error):
    """CT_ENOCONV: a solve did not meet its tolerance."""


class IOFailure(Error, OSError):
    """CT_EIO."""


class NotRun(Error):
    """CT_ESKIPPED: an earlier impact of the same speed failed."""


_CLASSES = {
    lib.CT_EINVAL: InvalidInput,
    lib.CT_ENOMEM: OutOfMemory,
    lib.CT_ERANGE: OutsideModel,
    lib.CT_ENOCONV: NoConvergence,
    lib.CT_EIO: IOFailure,
    lib.CT_ESKIPPED: NotRun,
}


def strerror(status):
    """The library's generic description of a status code."""
    return ffi.string(lib.ct_strerror(int(status))).decode()


def error(status, message):
    """The exception for a status and message."""
    return _CLASSES.get(int(status), Error)(status, message)


def check(status):
    """Raises the library's error when status is not CT_OK."""
    if status != lib.CT_OK:
        raise error(status, ffi.string(lib.ct_error_message()).decode(errors="replace"))


def invalid(message):
    """An InvalidInput raised in Python, before the library is called."""
    return InvalidInput(lib.CT_EINVAL, message)


def size_text(count, itemsize):
    """count items of itemsize bytes, as a one-line figure: "1000000000 x 272 bytes = 272 GB"."""
    total = count * itemsize
    for unit, scale in (("TB", 1e12), ("GB", 1e9), ("MB", 1e6), ("kB", 1e3)):
        if total >= scale:
            return f"{count} x {itemsize} bytes = {total / scale:.3g} {unit}"
    return f"{count} x {itemsize} bytes = {total} bytes"


def out_of_memory(what):
    """An OutOfMemory raised in Python: what names the request and its size."""
    return OutOfMemory(lib.CT_ENOMEM, f"{what}: out of memory")


@contextlib.contextmanager
def memory(what):
    """Turns a MemoryError of the block into OutOfMemory naming what (the request's size)."""
    try:
        yield
    except Error:
        raise
    except MemoryError:
        raise out_of_memory(what) from None


def not_finite(message):
    """The error for a number the library returned non-finite with a status of success: a
    figure beyond what doubles carry (or a defect), refused rather than handed back."""
    return OutsideModel(lib.CT_ERANGE, message)


# What a bad argument can raise inside Python, NumPy or cffi when no check named it first.
_ARGUMENT_ERRORS = (TypeError, ValueError, OverflowError, LookupError, ArithmeticError)


def boundary(fn, name=None):
    """fn, raising only the module's exceptions (see the module's docstring)."""
    if getattr(fn, "__cantact_boundary__", False):
        return fn
    name = name or f"cantact.{fn.__qualname__}"

    @functools.wraps(fn)
    def call(*args, **kwargs):
        try:
            return fn(*args, **kwargs)
        except Error:
            raise
        except BaseException as exc:
            if getattr(exc, "__cantact_callers__", False):
                raise  # raised by the caller's own callback (progress): as it is
            if not isinstance(exc, (MemoryError,) + _ARGUMENT_ERRORS):
                raise
            if isinstance(exc, MemoryError):
                detail = str(exc)
                raise out_of_memory(f"{name}" + (f" ({detail})" if detail else "")) from None
            cls = InvalidType if isinstance(exc, TypeError) else InvalidInput
            raise cls(lib.CT_EINVAL, f"{name}: {exc} ({type(exc).__name__})") from exc

    call.__cantact_boundary__ = True
    return call


def guard(obj):
    """obj with boundary() around it: a function, or a class's public methods, __init__,
    __call__ and properties (in place). Anything else is returned as it is."""
    if inspect.isfunction(obj):
        return boundary(obj)
    if not isinstance(obj, type) or issubclass(obj, BaseException):
        return obj
    for key, value in list(vars(obj).items()):
        if key.startswith("_") and key not in ("__init__", "__call__"):
            continue
        where = f"cantact.{obj.__name__}" + ("" if key == "__init__" else f".{key}")
        if isinstance(value, property):
            if value.fget is not None and not getattr(value.fget, "__cantact_boundary__", 0):
                setattr(obj, key, property(boundary(value.fget, where), value.fset,
                                           value.fdel, value.__doc__))
        elif isinstance(value, (staticmethod, classmethod)):
            setattr(obj, key, type(value)(boundary(value.__func__, where)))
        elif inspect.isfunction(value):
            setattr(obj, key, boundary(value, where))
    return obj
