"""The load curve against closed forms (one rod) and against the rod-by-rod sum written
here from MODEL.md §2-4 (the Cantor stages)."""
from fractions import Fraction

import numpy as np
import pytest

import cantact


def test_single_rod():
    # top 0.25, L = 1, E = 100, sigma_y = 1: k = 100, yields at 0.26, plateau 1
    c = cantact.load_curve(cantact.Rods([0.25], [1.0], E=100.0, Hstar=1.25, l0=1.0, h0=1.0))
    np.testing.assert_allclose(c.breakpoints, [0.25, 0.26], rtol=1e-15)
    assert c.first_contact == 0.25 and c.first_yield == pytest.approx(0.26, rel=1e-15)
    u = np.array([0.1, 0.25, 0.255, 0.26, 0.5, 1.0])
    np.testing.assert_allclose(c.force(u), [0, 0, 0.5, 1, 1, 1], rtol=1e-12, atol=1e-15)
    W = np.array([0, 0, 100 * 0.005**2 / 2, 0.005, 0.005 + 0.24, 0.005 + 0.74])
    np.testing.assert_allclose(c.work(u), W, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(c.dissipation(u), [0, 0, 0, 0, 0.24, 0.74], rtol=1e-12,
                               atol=1e-15)
    np.testing.assert_allclose(c.release([0.5]), [0.49], rtol=1e-14)
    np.testing.assert_allclose(c.inverse_work(W[2:]), u[2:], rtol=1e-12)
    # W near the top of the doubles, on the plateau of force 1 beyond W(0.26) = 0.005: the u
    # of W exactly (2 W overflowed: the last breakpoint 0.26 came back); with a plateau of 0.5
    # that u is beyond the doubles, refused
    big = [8.99e307, 1.7e308, np.finfo(float).max]
    exact = [float(Fraction(w) - Fraction(0.005) + Fraction(0.26)) for w in big]
    np.testing.assert_allclose(c.inverse_work(big), exact, rtol=1e-15)
    half = cantact.load_curve(cantact.Rods([0.25], [0.5], E=100.0, Hstar=1.25, l0=1.0, h0=1.0))
    with pytest.raises(cantact.OutsideModel, match="inverse_work.*not a finite number"):
        half.inverse_work([1.7e308])
    # after loading to 0.5: contact at 0.49, yield at 0.5
    a = cantact.load_curve(cantact.Rods([0.25], [1.0], E=100.0, Hstar=1.25, l0=1.0, h0=1.0),
                           after=0.5)
    np.testing.assert_allclose(a.breakpoints, [0.49, 0.5], rtol=1e-14)
    # units: h0 = 2, sigma_y = 3, l0 = 5 make u/h0 and P/(sigma_y l0)
    d = cantact.load_curve(cantact.Rods([0.5], [1.0], E=300.0, sigma_y=3.0, Hstar=2.5, h0=2.0,
                                        l0=5.0))
    np.testing.assert_allclose(d.force([1.0]), [300.0 * 0.01 / 15.0], rtol=1e-14)  # plateau


def test_cantor_stages_sum():
    fx, fz, H, E, N = 1.5, 1.3, 10.0, 500.0, 20
    s = cantact.Cantor(fx=fx, fz=fz, H=H, E=E, depth=N)
    c = cantact.load_curve(s)
    i = np.arange(N + 1)
    h = fz ** -i
    area = np.where(i < N, (1 - 1 / fx) * fx ** -i, fx ** -float(N))
    L = H - h
    eps_y = 1 / E

    def P(u):
        return sum(E * a * np.clip((u - t) / l, 0, eps_y) for t, a, l in zip(h, area, L))

    u = np.concatenate([c.breakpoints, np.geomspace(1e-9, 0.9 * H, 300)])
    ref = np.array([P(x) for x in u])
    np.testing.assert_allclose(c.force(u), ref, rtol=1e-12, atol=1e-13 * ref.max())
    assert c.first_yield == pytest.approx(h[-1] + eps_y * L[-1], rel=1e-14)
