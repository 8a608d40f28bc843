"""A Python process that used the library's threads exits cleanly: libcantact (and the OpenMP
runtime it brings) must stay mapped while the runtime's worker threads run, so Python's exit
cannot unload it under them (it did: exit -11, every time with OMP_WAIT_POLICY=ACTIVE, where
the workers spin between parallel regions instead of sleeping)."""
import os
import subprocess
import sys

import cantact

# An ensemble on two threads, then the end of the process: with the library unloaded at exit,
# 20 runs of 20 died with SIGSEGV under OMP_WAIT_POLICY=ACTIVE.
CHILD = """
import cantact
rc = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=6, fx_spread=0.1, seed=1)
en = cantact.ensemble(rc, V_star=[1e-3], realisations=4, threads=2)
assert (en.status == 0).all()
print("done")
"""
RUNS = 8


# Closing the handle as Python's exit does must leave the library mapped: the deterministic
# form of the crash above, which is a race (a process may exit before a worker next runs).
CLOSED = """
import os
import cantact
from cantact import _ffi
real = os.path.realpath(cantact.LIBRARY_PATH)
def mapped():
    with open("/proc/self/maps") as f:
        return any(os.path.realpath(line.split()[-1]) == real for line in f if "/" in line)
assert mapped(), "the library is not mapped after import"
_ffi.ffi.dlclose(_ffi.lib)
print("mapped" if mapped() else "unmapped")
"""


def test_loaded_never_to_be_unloaded():
    assert cantact._ffi.DLOPEN_FLAGS & cantact.ffi.RTLD_NODELETE
    env = dict(os.environ, CANTACT_LIBRARY=cantact.LIBRARY_PATH)
    p = subprocess.run([sys.executable, "-c", CLOSED], env=env, capture_output=True, text=True,
                       timeout=60)
    assert p.returncode == 0, p.stderr
    assert p.stdout == "mapped\n", "closing the handle unmapped libcantact: " + p.stdout


def test_exit_after_threads_is_clean():
    env = dict(os.environ, OMP_WAIT_POLICY="ACTIVE", CANTACT_LIBRARY=cantact.LIBRARY_PATH)
    env.pop("OMP_NUM_THREADS", None)
    failed = []
    for run in range(RUNS):
        p = subprocess.run([sys.executable, "-c", CHILD], env=env, capture_output=True,
                           text=True, timeout=60)
        if p.returncode != 0 or p.stdout != "done\n":
            failed.append((run, p.returncode, p.stderr.strip()[-200:]))
    assert not failed, f"{len(failed)} of {RUNS} processes did not exit cleanly: {failed}"
