"""Bad arguments raise cantact exceptions (never a crash, never a NaN result): one test per
class of bad input, Python's checks and the library's own (message and status carried)."""
import numpy as np
import pytest

import cantact

CT = cantact.lib


def cantor(**kw):
    args = dict(fx=1.5, fz=1.3, H=10, E=500)
    args.update(kw)
    return cantact.Cantor(**args)


def raises(exc, match, fn, *args, **kw):
    with pytest.raises(exc, match=match) as info:
        fn(*args, **kw)
    assert isinstance(info.value, cantact.Error)
    assert info.value.status in cantact._errors.STATUS_NAMES
    return info.value


def test_wrong_types():
    raises(cantact.InvalidInput, "fx = '1.5': must be a real number", cantor, fx="1.5")
    raises(cantact.InvalidInput, "fz = True: must be a real number", cantor, fz=True)
    raises(cantact.InvalidInput, "depth = 3.0: must be an integer", cantor, depth=3.0)
    raises(cantact.InvalidInput, "impacts = 1.5", cantact.restitution, cantor(),
           V_star=[1e-3], impacts=1.5)
    raises(cantact.InvalidInput, "must be a cantact surface", cantact.restitution, "cantor",
           V_star=[1e-3])
    raises(cantact.InvalidInput, "check = 1: must be True or False", cantact.restitution,
           cantor(), V_star=[1e-3], check=1)
    raises(cantact.InvalidInput, "got a string", cantact.restitution, cantor(), V_star="1e-3")
    raises(cantact.InvalidInput, "must hold real numbers", cantact.restitution, cantor(),
           V_star=[1e-3 + 1j])
    raises(cantact.InvalidInput, "got booleans", cantact.restitution, cantor(),
           V_star=np.array([True]))
    raises(cantact.InvalidInput, r"V_star\[1\] = None: must be a real number, got NoneType",
           cantact.restitution, cantor(),
           V_star=[1e-3, None])


def test_not_finite():
    raises(cantact.InvalidInput, "fx = nan: not a finite number", cantor, fx=float("nan"))
    raises(cantact.InvalidInput, "H = inf: not a finite number", cantor, H=float("inf"))
    raises(cantact.InvalidInput, r"V_star\[1\] = nan: must be finite", cantact.restitution,
           cantor(), V_star=[1e-3, np.nan])
    raises(cantact.InvalidInput, "rod 1: top = inf", cantact.Rods, [np.inf], [1.0], E=10,
           Hstar=2)
    raises(cantact.InvalidInput, r"u\[0\] = nan", cantact.series_load, cantor(), [np.nan])


def test_out_of_range():
    raises(cantact.InvalidInput, "fz = 2.0: must satisfy 1 < fz < 2", cantor, fz=2.0)
    raises(cantact.InvalidInput, "fx = 1.0: must satisfy fx > 1", cantor, fx=1.0)
    raises(cantact.InvalidInput, "E = 0.5: must be > sigma_y", cantor, E=0.5)
    raises(cantact.InvalidInput, r"V_star\[0\] = -0.001: must be > 0", cantact.restitution,
           cantor(), V_star=[-1e-3])
    raises(cantact.InvalidInput, "representation = segments: needs an integer surface.depth",
           cantor, representation="segments")
    raises(cantact.InvalidInput, "depth = 31", cantact.RandomCantor, fx=1.5, fz=1.3, H=10,
           E=500, depth=31)
    raises(cantact.InvalidInput, r"rod 2: top = 2: must be < H\* = 2", cantact.Rods, [0, 2.0],
           [1, 1], E=10, Hstar=2)
    raises(cantact.InvalidInput, r"rod 1: area = 0: must be finite and > 0", cantact.Rods, [0],
           [0.0], E=10, Hstar=2)
    raises(cantact.InvalidInput, "threads = 2000", cantor, threads=2000)
    raises(cantact.InvalidInput, "tolerance = 1e-20", cantact.table, cantor(),
           V_star=(1e-5, 1e-2), tolerance=1e-20)
    # the library's own range checks, with its message: a uniform spread of 1 or more
    e = raises(cantact.InvalidInput, "spread", cantact.RandomCantor, fx=1.5, fz=1.3, H=10,
               E=500, depth=4, distribution="uniform", fx_spread=1.5)
    assert e.status == CT.CT_EINVAL and e.status_name == "CT_EINVAL"


def test_wrong_shapes_and_sizes():
    raises(cantact.InvalidInput, r"must be one-dimensional, got shape \(2, 2\)",
           cantact.restitution, cantor(), V_star=[[1e-3, 2e-3], [3e-3, 4e-3]])
    raises(cantact.InvalidInput, "must not be empty", cantact.restitution, cantor(), V_star=[])
    raises(cantact.InvalidInput, "not an array of numbers", cantact.restitution, cantor(),
           V_star=[[1e-3], [1e-3, 2e-3]])
    raises(cantact.InvalidInput, "1 and 2 rods: must be as many", cantact.Rods, [0], [1, 1],
           E=10, Hstar=2)
    raises(cantact.InvalidInput, "V_star = 0.01:1e-05: expected from:to with 0 < from < to",
           cantact.table, cantor(), V_star=(1e-2, 1e-5))
    raises(cantact.InvalidInput, r"V_star = 0.001: expected from:to \(two numbers",
           cantact.table, cantor(), V_star=[1e-3])


def test_conflicting_or_missing_arguments():
    raises(cantact.InvalidInput, "either V_star or mass and speed", cantact.restitution,
           cantor(), V_star=[1e-3], mass=1.0)
    raises(cantact.InvalidInput, "needs V_star, or both mass and speed", cantact.restitution,
           cantor(), speed=[1.0])
    raises(cantact.InvalidInput, "quadrature = simpsons: must be breakpoints, trapezoid, "
           "simpson, gauss or closed", cantact.restitution, cantor(), V_star=[1e-3],
           quadrature="simpsons")
    raises(cantact.InvalidInput, "ensembles are of random surfaces", cantact.ensemble, cantor(),
           V_star=[1e-3], realisations=2)
    raises(cantact.InvalidInput, "give V_star", cantact.load_curve, cantor())
    raises(cantact.InvalidInput, "deterministic Cantor surface", cantact.law_restitution,
           cantact.Rods([0], [1], E=10, Hstar=2), V_star=[1e-3])
    raises(cantact.InvalidInput, "with mass 1e-300 gives V\\* = 0.0", cantact.restitution,
           cantor(), mass=1e-300, speed=[1e-200])


def test_library_failures_carry_status_and_message():
    e = raises(cantact.OutsideModel, "crushed", cantact.restitution, cantor(), V_star=[1e-3, 1.0])
    assert e.status == CT.CT_ERANGE and "impact 1" in e.message
    e = raises(cantact.NoConvergence, "max_nodes = 3", cantact.table, cantor(),
               V_star=(1e-5, 1e-2), max_nodes=3)
    assert e.status == CT.CT_ENOCONV
    # a penetration too small to resolve on very stiff rods
    stiff = cantact.Rods([0.5], [1.0], E=1e12, sigma_y=1e9, Hstar=0.5 + 1e-9, l0=1.0,
                         h0=1.0)
    raises(cantact.Error, "", cantact.restitution, stiff, V_star=[1e-30, 1e-3])
    # ct_strerror through the module
    assert cantact.strerror(CT.CT_ENOMEM) == "out of memory"


def test_read_table_refuses_other_files(tmp_path):
    p = tmp_path / "x.csv"
    p.write_text("a,b\n1,2\n")
    raises(cantact.InvalidInput, "x.csv:1: expected the header", cantact.read_table, p)
    p.write_text("V_star,e,de_dlnV_star\n1,1,0\n2,0.5,0\n")
    raises(cantact.InvalidInput, "not a cantact table", cantact.read_table, p)
    p.write_text("# interpolation = linear\n# V_star_crit = 0.1\n# nodes = 2\n"
                 "V_star,e,de_dlnV_star\n1,1,0\n0.5,0.5,0\n")
    raises(cantact.InvalidInput, "x.csv:6: V_star = 0.5: must be > 0 and above the previous",
           cantact.read_table, p)


def test_hostile_round_four():
    """Integers beyond doubles, a flat profile, and Profile's messages naming what was given
    (issue 24's hostile pass): cantact.InvalidInput, never OverflowError or a made-up e."""
    for kw in (dict(fx=10**400, fz=1.3, H=10, E=500), dict(fx=1.5, fz=1.3, H=10**400, E=500)):
        with pytest.raises(cantact.InvalidInput, match="beyond double precision"):
            cantact.Cantor(**kw)
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    with pytest.raises(cantact.InvalidInput, match="beyond double precision"):
        cantact.restitution(s, V_star=[10**400])
    # a flat line levels to its rounding residue (1e-23 m): no roughness, not an e of 0.30
    with pytest.raises(cantact.InvalidInput, match="no roughness"):
        cantact.Profile(z=np.full(50, 1e-7), dx=1e-6, E=2e11, sigma_y=4e8, H=10)
    z, x = np.sin(np.arange(40.0)) * 1e-7, np.arange(40.0) * 1e-6
    with pytest.raises(cantact.InvalidInput, match="not both"):
        cantact.Profile(z=z, x=x, dx=1e-6, E=2e11, sigma_y=4e8, H=10)
    with pytest.raises(cantact.InvalidInput, match="dy is for a grid"):
        cantact.Profile(z=z, dx=1e-6, dy=1e-6, E=2e11, sigma_y=4e8, H=10)
    with pytest.raises(cantact.InvalidInput, match=r"missing: dy\)"):
        cantact.Profile(z=z.reshape(4, 10), dx=1e-6, E=2e11, sigma_y=4e8, H=10)


def test_unknown_keys_say_the_nearest():
    """A slip in a key's name is answered with the nearest key (the library's words, the same as
    the program's), naming the kinds that take it when the surface's own does not."""
    with pytest.raises(cantact.InvalidInput, match=r"surface\.fzz: unknown key \(did you mean "
                                                   r"surface\.fz\?\)"):
        cantact.Surface("cantor", fx=1.5, fzz=1.3, H=10, E=500)
    with pytest.raises(cantact.InvalidInput, match=r"surface\.uint: unknown key \(did you mean "
                                                   r"surface\.unit\? only for surface\.type = "
                                                   r"profile or rods\)"):
        cantact.Surface("cantor", uint="mm")
    with pytest.raises(cantact.InvalidInput) as info:
        cantact.Surface("cantor", colour="red")
    assert "did you mean" not in str(info.value)
