"""ensemble() against the cantact program's realisations CSV (the same bits) and its
statistics against NumPy's (an independent implementation)."""
import csv

import numpy as np
import pytest

import cantact

SCENE = ("[surface]\ntype = random_cantor\nfx = 1.5\nfz = 1.3\nH = 10\ndepth = 7\n"
         "fx_spread = 0.2\nfz_spread = 0.1\ndistribution = {dist}\nseed = 11\n"
         "[material]\nE = 500\n[impact]\nV_star = 2e-4, 1e-3, 4e-3\nimpacts = 2\n"
         "[ensemble]\nrealisations = 12\n[output]\nwhat = realisations\n")


@pytest.mark.parametrize("dist", ["lognormal", "uniform"])
def test_samples_as_the_cli(run_cli, tmp_path, dist):
    scene = tmp_path / "e.ini"
    scene.write_text(SCENE.format(dist=dist))
    with open(run_cli("run", str(scene))) as f:
        first = f.readline()  # the scene's identity, for cantact merge
        assert first.startswith("# realisations of surface = random_cantor:")
        rows = list(csv.DictReader(f))
    s = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=7, fx_spread=0.2,
                             fz_spread=0.1, distribution=dist, seed=11)
    en = cantact.ensemble(s, V_star=[2e-4, 1e-3, 4e-3], impacts=2, realisations=12)
    assert len(rows) == en.e.size
    for row in rows:
        r = int(row["realisation"])
        q = [2e-4, 1e-3, 4e-3].index(float(row["V_star"]))
        i = int(row["impact"]) - 1
        assert row["e"] == "%.17g" % en.e[r, q, i]
        assert row["u_max_over_h0"] == "%.17g" % en.u_max_over_h0[r, q, i]
        assert row["V_star_crit"] == "%.17g" % en.V_star_crit[r, q, i]
        assert int(row["fx_clipped"]) == en.fx_clipped[r]
        assert int(row["fz_clipped"]) == en.fz_clipped[r]
    # one realisation alone is the same surface
    one = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=7, fx_spread=0.2,
                               fz_spread=0.1, distribution=dist, seed=11, realisation=5)
    r5 = cantact.restitution(one, V_star=[2e-4, 1e-3, 4e-3], impacts=2)
    assert r5.e.tobytes() == en.e[5].tobytes()


def test_stats_against_numpy():
    s = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=8, fx_spread=0.1, seed=3)
    en = cantact.ensemble(s, V_star=[3e-4, 2e-3], realisations=40, first=100, threads=2)
    assert en.realisations[0] == 100 and en.e.shape == (40, 2, 1)
    st = en.stats("e")
    x = en.e[:, :, 0]
    np.testing.assert_allclose(st["mean"][:, 0], x.mean(axis=0), rtol=1e-15)
    np.testing.assert_allclose(st["sd"][:, 0], x.std(axis=0, ddof=1), rtol=1e-12)
    np.testing.assert_allclose(st["sem"][:, 0], x.std(axis=0, ddof=1) / np.sqrt(40), rtol=1e-12)
    for k, p in (("q05", 0.05), ("q50", 0.5), ("q95", 0.95)):
        np.testing.assert_allclose(st[k][:, 0], np.quantile(x, p, axis=0), rtol=1e-15)
    assert (st["n"] == 40).all()
    # the thread count and split change no bit
    en1 = cantact.ensemble(s, V_star=[3e-4, 2e-3], realisations=40, first=100, threads=1,
                           split="rods")
    assert en1.e.tobytes() == en.e.tobytes()


def test_spread_zero_has_no_spread():
    s = cantact.RandomCantor(fx=1.5, fz=1.3, H=10, E=500, depth=6)
    st = cantact.ensemble(s, V_star=[1e-3], realisations=5).stats()
    assert st["sd"][0, 0] == 0.0
