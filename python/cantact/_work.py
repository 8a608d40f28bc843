"""Long library calls (a sweep, an ensemble, a table) that Ctrl-C stops, and their progress.

The library stops such a call between blocks of its work once the flag its spec points to
(`interrupt`) is set, and returns CT_EINTR (cantact.h). Python runs its SIGINT handler in the
main thread only, between bytecodes: never while the main thread waits inside a C call, and
in ABI mode a callback cannot ask for it (PyErr_CheckSignals). So the call runs in a worker
thread while the main thread waits for it in short sleeps; a KeyboardInterrupt (or any other
exception) raised in the main thread while it waits sets the flag, waits for the worker to stop
(a fraction of a second: the library's blocks) and is raised. Nothing process-wide is changed:
no signal handler is installed. Called from a thread other than the main one (where no
KeyboardInterrupt arrives), the call runs in place.

progress: None or False, nothing; True, a bar on standard error; a callable, called as
progress(done, total) from the thread doing the work (the worker, or one of the library's
threads, one at a time). An exception it raises stops the call and is raised from it, as it
is."""
import sys
import threading

from ._errors import error, invalid
from ._ffi import ffi, lib

# How long the main thread sleeps between looks at the worker: the most a Ctrl-C waits to be
# seen when the signal went to another thread.
_POLL_SECONDS = 0.05


class _Bar:
    """A progress bar on standard error: '\\r' and the bar, redrawn when its percentage
    changes; a newline at the end when one was drawn."""

    def __init__(self, what, unit):
        self.what, self.unit = what, unit
        self.shown = None

    def __call__(self, done, total):
        pct = int(100 * done / total) if total else 100
        if (pct, total) == self.shown:
            return
        self.shown = (pct, total)
        fill = pct * 40 // 100
        sys.stderr.write(f"\r{self.what}: [{'#' * fill}{' ' * (40 - fill)}] {pct:3d}% "
                         f"({done}/{total} {self.unit})")
        sys.stderr.flush()

    def close(self):
        if self.shown is not None:
            sys.stderr.write("\n")
            sys.stderr.flush()


def _callers(exc):
    """Marks an exception raised by the caller's own callback: the module's boundary lets it
    through as it is."""
    try:
        exc.__cantact_callers__ = True
    except AttributeError:  # an exception without a __dict__: raised as it is all the same
        pass
    return exc


class Work:
    """One long call: its interrupt flag (flag, for the spec's interrupt) and its progress
    (callback, for the spec's progress: NULL when none). what names the call on the bar, unit
    what done and total count."""

    def __init__(self, progress, what, unit):
        if progress is None or progress is False:
            self._user = None
        elif progress is True:
            self._user = _Bar(what, unit)
        elif callable(progress):
            self._user = progress
        else:
            raise invalid(f"progress = {progress!r}: must be True, False, None or a callable "
                          "progress(done, total)")
        self.flag = ffi.new("int *")
        self._raised = None
        self.callback = ffi.NULL if self._user is None else ffi.callback(
            "ct_progress_fn", self._tick)

    def _tick(self, done, total, ctx):
        if self._raised is not None:
            return
        try:
            self._user(int(done), int(total))
        except BaseException as exc:  # the caller's: stop the work, raise it afterwards
            self._raised = exc
            self.flag[0] = 1

    def run(self, call):
        """call() (a library call that reads this flag, returning its status) in a worker
        thread; its error raised as the module's exception, a KeyboardInterrupt as itself."""
        out = {}
        finished = threading.Event()

        def work():
            try:  # the message is the worker's: ct_error_message is per thread
                out["status"] = call()
                out["message"] = ffi.string(lib.ct_error_message()).decode(errors="replace")
            except BaseException as exc:  # raised in the caller's thread below
                out["raised"] = exc
            finally:
                finished.set()

        try:
            if threading.current_thread() is not threading.main_thread():
                work()
            else:
                # an Event, not Thread.join: a join that a KeyboardInterrupt breaks can leave
                # is_alive() False while the thread still runs (Python 3.11)
                threading.Thread(target=work, name="cantact", daemon=True).start()
                try:
                    while not finished.wait(_POLL_SECONDS):
                        pass
                except BaseException:  # Ctrl-C (or any exception) while it runs: stop it
                    self.flag[0] = 1
                    while not finished.is_set():
                        try:
                            finished.wait(_POLL_SECONDS)
                        except BaseException:  # another Ctrl-C: it is stopping already
                            pass
                    raise
        finally:
            if isinstance(self._user, _Bar):
                self._user.close()
        if self._raised is not None:
            raise _callers(self._raised)
        if "raised" in out:
            raise out["raised"]
        st = out["status"]
        if st == lib.CT_EINTR:  # the flag was set, and not by Ctrl-C here: another thread's
            raise KeyboardInterrupt
        if st != lib.CT_OK:
            raise error(st, out["message"])
