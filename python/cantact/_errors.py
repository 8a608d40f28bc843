"""Exceptions: every failure of the library raises one, carrying its status and message."""
from ._ffi import ffi, lib

STATUS_NAMES = {
    lib.CT_OK: "CT_OK",
    lib.CT_EINVAL: "CT_EINVAL",
    lib.CT_ENOMEM: "CT_ENOMEM",
    lib.CT_ERANGE: "CT_ERANGE",
    lib.CT_ENOCONV: "CT_ENOCONV",
    lib.CT_EIO: "CT_EIO",
    lib.CT_ESKIPPED: "CT_ESKIPPED",
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
