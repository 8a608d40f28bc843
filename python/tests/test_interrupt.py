"""Long calls stopped by Ctrl-C, and their progress (python/cantact/_work.py).

A child process starts a call that would run for half a minute or more, sends itself SIGINT
from a timer a second later and measures how long the KeyboardInterrupt takes to come out of
the call: under a second, while without the library's interrupt flag the call would only
return when done. Its length comes from its own progress at the signal (done of total, the
time so far). A progress callback (or the bar) changes no result, bit for bit."""
import json
import os
import subprocess
import sys
import threading

import numpy as np
import pytest

import cantact

CHILD = r"""
import json, os, signal, sys, threading, time
import numpy as np
import cantact

what = sys.argv[1]
log = []
sent = {}


def progress(done, total):
    log.append((time.monotonic(), done, total))


def ctrl_c():
    sent["at"] = time.monotonic()
    os.kill(os.getpid(), signal.SIGINT)
    time.sleep(20)  # a watchdog: still here, the call went on after Ctrl-C
    print(json.dumps({"ignored": True}), flush=True)
    os._exit(0)


V = np.geomspace(1e-4, 1e-2, 5)
if what == "restitution":
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500, depth=19, representation="segments")
    call = lambda: cantact.restitution(s, V_star=np.geomspace(1e-4, 1e-2, 150000),
                                       progress=progress)
elif what == "ensemble":
    s = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=12, fx_spread=0.1,
                             fz_spread=0.05)
    call = lambda: cantact.ensemble(s, V_star=V, impacts=2, realisations=60000,
                                    progress=progress)
else:
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500, depth=14, representation="segments")
    call = lambda: cantact.table(s, V_star=(1e-5, 1e-2), tolerance=1e-8, progress=progress)
start = time.monotonic()
timer = threading.Timer(1.0, ctrl_c)
timer.daemon = True
timer.start()
try:
    call()
    out = {"finished": time.monotonic() - start}
except KeyboardInterrupt:
    now = time.monotonic()
    seen = [x for x in log if x[0] <= sent["at"]]
    t, done, total = seen[-1] if seen else (start, 0, 1)
    out = {"latency": now - sent["at"], "running": sent["at"] - start, "done": done,
           "total": total}
print(json.dumps(out))
"""


def interrupted(what):
    """The child's report of one call interrupted after a second."""
    try:  # the child's own watchdog ends it 20 s after Ctrl-C: this is for a child that hangs
        p = subprocess.run([sys.executable, "-c", CHILD, what], capture_output=True, text=True,
                           timeout=300, env=os.environ)
    except subprocess.TimeoutExpired:
        pytest.fail(f"{what}: the child hung")
    assert p.returncode == 0, p.stderr
    out = json.loads(p.stdout)
    assert "ignored" not in out, f"{what}: still running 20 s after Ctrl-C"
    assert "latency" in out, f"{what}: finished in {out['finished']:.1f} s, not interrupted"
    print(f"{what}: KeyboardInterrupt {out['latency'] * 1000:.0f} ms after SIGINT, "
          f"{out['done']} of {out['total']} done in {out['running']:.2f} s")
    return out


@pytest.mark.parametrize("what", ["restitution", "ensemble", "table"])
def test_ctrl_c_stops_a_long_call_within_a_second(what):
    # a machine loaded far beyond its cores can keep any thread waiting for a second: a slow
    # answer is tried twice more (a call that ignored Ctrl-C would run on for tens of seconds)
    for _ in range(3):
        out = interrupted(what)
        if out["latency"] < 1.0:
            break
    assert out["latency"] < 1.0
    if what != "table":  # a table's total grows round by round: its own length is unknown
        assert out["done"] < out["total"]  # stopped in the middle
        assert out["running"] * out["total"] / max(out["done"], 1) >= 30.0


def cantor():
    return cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500, depth=16, representation="segments")


def same(a, b):
    return np.asarray(a).tobytes() == np.asarray(b).tobytes()


class Log:
    def __init__(self):
        self.calls = []

    def __call__(self, done, total):
        self.calls.append((done, total))


def test_progress_changes_no_bit(capfd):
    s = cantor()
    # enough checked rows for the closed-form batch to be reported in slices (over 1024 on
    # 131071 rods with two threads)
    V = np.geomspace(1e-4, 1e-2, 1100)
    plain = cantact.restitution(s, V_star=V)
    log = Log()
    seen = cantact.restitution(s, V_star=V, progress=log)
    barred = cantact.restitution(s, V_star=V, progress=True)
    for name, _, _ in cantact.ROW_FIELDS:
        if hasattr(plain, name):
            assert same(getattr(plain, name), getattr(seen, name)), name
            assert same(getattr(plain, name), getattr(barred, name)), name
    done = [d for d, _ in log.calls]
    assert len(done) >= 2 and done == sorted(set(done)) and done[-1] == V.size
    assert all(t == V.size for _, t in log.calls)
    err = capfd.readouterr().err
    assert err.startswith("\rrestitution: [") and err.endswith(f"({V.size}/{V.size} speeds)\n")

    r = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=8, fx_spread=0.1,
                             fz_spread=0.05)
    kw = dict(V_star=np.geomspace(1e-4, 1e-2, 7), impacts=2, realisations=30, threads=2)
    a = cantact.ensemble(r, **kw)
    log = Log()
    b = cantact.ensemble(r, **kw, progress=log)
    for name in ("e", "u_max_over_h0", "V_star_crit", "status"):
        assert same(getattr(a, name), getattr(b, name)), name
    assert [d for d, _ in log.calls] == list(range(1, 31))

    c = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500, depth=8, representation="segments")
    t1 = cantact.table(c, V_star=(1e-4, 1e-2), tolerance=1e-7)
    log = Log()
    t2 = cantact.table(c, V_star=(1e-4, 1e-2), tolerance=1e-7, progress=log)
    for name in ("V_star", "e", "slope"):
        assert same(getattr(t1, name), getattr(t2, name)), name
    assert t1.info == t2.info
    assert log.calls[-1] == (t1.info["evaluations"], t1.info["evaluations"])
    assert all(d <= t for d, t in log.calls)


def test_progress_argument():
    s = cantor()
    for bad in (3, "yes", [1]):
        with pytest.raises(cantact.InvalidInput, match="progress"):
            cantact.restitution(s, V_star=[1e-3], progress=bad)

    class Enough(Exception):
        pass

    def stop(done, total):
        raise Enough(done)

    # the callback's own exception stops the call and comes out as it is, a ValueError too
    with pytest.raises(Enough):
        cantact.restitution(s, V_star=np.geomspace(1e-4, 1e-2, 3000), progress=stop)
    with pytest.raises(ValueError, match="^mine$") as info:
        cantact.ensemble(cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=6),
                         V_star=[1e-3], realisations=50,
                         progress=lambda d, t: (_ for _ in ()).throw(ValueError("mine")))
    assert not isinstance(info.value, cantact.Error)


def test_from_another_thread():
    """Away from the main thread (where no KeyboardInterrupt arrives) the call runs in place,
    its progress and errors as on the main thread."""
    s = cantor()
    out = {}

    def work():
        log = Log()
        out["r"] = cantact.restitution(s, V_star=[1e-4, 1e-3], progress=log)
        out["calls"] = log.calls
        try:
            cantact.restitution(s, V_star=[10.0])
        except cantact.Error as exc:
            out["error"] = exc

    t = threading.Thread(target=work)
    t.start()
    t.join()
    assert out["calls"][-1] == (2, 2)
    assert same(out["r"].e, cantact.restitution(s, V_star=[1e-4, 1e-3]).e)
    assert isinstance(out["error"], cantact.OutsideModel)
    assert "crushed" in out["error"].message
