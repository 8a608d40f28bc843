#!/usr/bin/env python3
"""The paper's asymptotic law (docs/model.md section 6, Eqs. 33, 34, 36-38) evaluated in
120-digit decimal arithmetic: the closed forms written as printed, term by term, whose
cancellations (terms of order 1 whose sum is of order eps_y, or eps_y^2 for the unloading
work) cost nothing at this precision. It shares no code with cantact. Every parameter is the
exact value of the double given (Decimal(float)); alpha = ln fx / ln fz, beta = 1/(fx fz),
c = (fx - 1) beta / (1 - beta), K = 1 - c, in the units l0 = h0 = sigma_y = 1 (E = E/sigma_y,
H = H*/h0).

For each case: u_max of the impact of energy W (the loading work, Eq. 39) by bisection to 1e-60
relative, then e = sqrt(W_unload / W_load) (Eqs. 40-41) for the law as printed and for its
consistent variant (docs/model.md section 6); and the forces: loading at u_max, unloading from
u_max on each branch of Eq. 38.

Also the series (Series below), its u_max and e.

Usage: laws_reference.py            prints the C tables of tests/test_laws.c (asym_reference,
                                    series_reference, SERIES_ELASTIC_NEAR_UMAX)
"""
from decimal import Decimal as D, getcontext

getcontext().prec = 120


class Law:
    def __init__(self, fx, fz, E, H):
        self.fx, self.fz, self.H = D(fx), D(fz), D(H)
        self.eps = 1 / D(E)
        self.a = self.fx.ln() / self.fz.ln()
        beta = 1 / (self.fx * self.fz)
        self.c = (self.fx - 1) * beta / (1 - beta)
        self.K = 1 - self.c

    def chi(self, x):
        return (x - self.H * self.eps) / (1 - self.eps)  # Eq. 30

    def load(self, x):
        """Eq. 33 below the first yield, Eq. 34 above it."""
        a, e, H, fx = self.a, self.eps, self.H, self.fx
        chi = self.chi(x)
        if chi <= 0:
            return self.K * x ** (1 + a) / (e * fx * H)
        br = x * (x ** a - chi ** a) - self.c * (x ** (1 + a) - chi ** (1 + a))
        return br / (e * H * fx) + chi ** a / fx

    def unload(self, xm, x, consistent):
        """Eq. 38: branch 1 from chi_M to xm, branch 2 from hbar (Eq. 37) to chi_M."""
        a, e, H, fx = self.a, self.eps, self.H, self.fx
        chiM = self.chi(xm)
        if chiM <= 0:
            return self.load(x)
        hbar = xm - e * H
        if x <= hbar:
            return D(0)
        if x >= chiM:
            br = x * (x ** a - chiM ** a) - self.c * (x ** (1 + a) - chiM ** (1 + a))
            return br / (e * fx * H) + ((x - xm) / (e * H) + 1) * chiM ** a / fx
        P = ((x - hbar) / e) ** (a + 1) / (fx * H)
        return P * self.K if consistent else P

    def work_load(self, x):
        """Eq. 33 integrated from 0, then Eq. 34 from the first yield eps_y H to x."""
        a, e, H, fx = self.a, self.eps, self.H, self.fx
        pre = 1 / (e * H * fx)
        xy = e * H
        xe = min(x, xy)
        W = pre * self.K * xe ** (2 + a) / (2 + a)
        if x <= xy:
            return W
        chi, e1 = self.chi(x), 1 - e
        I_x1a = (x ** (2 + a) - xy ** (2 + a)) / (2 + a)
        I_xchi = e1 * (e1 * chi ** (a + 2) / (a + 2) + e * H * chi ** (a + 1) / (a + 1))
        I_chi1a = e1 * chi ** (2 + a) / (2 + a)
        I_chia = e1 * chi ** (1 + a) / (1 + a)
        return W + pre * ((I_x1a - I_xchi) - self.c * (I_x1a - I_chi1a)) + I_chia / fx

    def work_unload(self, xm, consistent):
        """Eq. 38 integrated: branch 2 from hbar = xm - eps_y H (Eq. 37) to chi_M (Eq. 35-36),
        branch 1 from chi_M to xm."""
        a, e, H, fx = self.a, self.eps, self.H, self.fx
        chiM = self.chi(xm)
        if chiM <= 0:
            return self.work_load(xm)
        hbar = xm - e * H
        t = (chiM - hbar) / e
        W2 = e * t ** (a + 2) / ((a + 2) * fx * H)
        if consistent:
            W2 *= self.K
        x1, x2, pre = chiM, xm, 1 / (e * fx * H)
        I_x1a = (x2 ** (2 + a) - x1 ** (2 + a)) / (2 + a)
        I_x = (x2 * x2 - x1 * x1) / 2
        I_1 = x2 - x1
        ca, ca1 = chiM ** a, chiM ** (1 + a)
        W1 = pre * ((I_x1a - ca * I_x) - self.c * (I_x1a - ca1 * I_1)) + \
            ca / fx * ((I_x - x2 * I_1) / (e * H) + I_1)
        return W1 + W2

    def u_max(self, W):
        lo, hi = D(0), D(1)
        while hi - lo > D("1e-60") * hi:
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if self.work_load(mid) < W else (lo, mid)
        return (lo + hi) / 2


# (fx, fz, E/sigma_y, H, V*): V*^2 = W / (l0 E h0), so W = V*^2 E in units of sigma_y l0 h0.
# E/sigma_y from 500 to 1e20, u_max from near the first yield to 0.3 h0; fx, fz across their
# range, H from near 1 to 100.
CASES = [
    (1.5, 1.3, 500.0, 10.0, 1e-3),
    (1.5, 1.3, 500.0, 10.0, 1e-2),
    (1.5, 1.3, 1e6, 10.0, 1e-4),
    (1.5, 1.3, 1e8, 10.0, 1e-5),
    (1.5, 1.3, 1e10, 10.0, 1e-6),
    (1.5, 1.3, 1e12, 10.0, 1e-7),
    (1.5, 1.3, 1e14, 10.0, 1e-8),
    (1.5, 1.3, 1e16, 10.0, 1e-9),
    (1.5, 1.3, 1e16, 10.0, 1e-11),
    (1.5, 1.3, 1e18, 10.0, 1e-10),
    (1.5, 1.3, 1e20, 10.0, 1e-11),
    (1.5, 1.3, 1e20, 10.0, 1e-13),
    (1.2, 1.1, 1e16, 2.0, 1e-9),
    (1.8, 1.9, 1e16, 100.0, 3e-10),
    (3.0, 1.05, 1e12, 1.5, 1e-7),
    (1.01, 1.6, 1e18, 10.0, 1e-10),
    (1.5, 1.3, 1e4, 10.0, 2e-3),
    (1.2, 1.9, 1e3, 5.0, 3e-3),
]


class Series:
    """The paper's series as cantact sums it (docs/model.md section 5): stage i of area
    s_i = (1 - 1/fx) fx^-i and top h_i = fz^-i, elastic at E s_i (u - h_i) / H* (Eq. 14) once
    touched, at sigma_y s_i once h_i <= chi h0 (Eq. 29), i.e. from u_y = eps_y H* + (1 - eps_y)
    h_i; unloading (Eqs. 22-24) elastic stages along their loading lines, plastic ones at
    E s_i ((u - u_max)/H* + eps_y) from u_max - eps_y (H* - h_i). Works stage by stage in closed
    form, `stages` of them and the rest (area fx^-stages) at depth 0."""

    def __init__(self, fx, fz, E, H, stages=400):
        self.fx, self.fz, self.H, self.E = D(fx), D(fz), D(H), D(E)
        self.eps = 1 / self.E
        self.s = [(1 - 1 / self.fx) * self.fx ** -i for i in range(stages)] + \
            [self.fx ** -stages]
        self.h = [self.fz ** -i for i in range(stages)] + [D(0)]

    def work_load(self, u):
        E, H, eps = self.E, self.H, self.eps
        w = D(0)
        for s, h in zip(self.s, self.h):
            uy = eps * H + (1 - eps) * h
            if u <= h:
                continue
            w += E * s * (min(u, uy) - h) ** 2 / (2 * H) + (s * (u - uy) if u > uy else 0)
        return w

    def work_unload(self, um):
        E, H, eps = self.E, self.H, self.eps
        chi = (um - eps * H) / (1 - eps)
        w = D(0)
        for s, h in zip(self.s, self.h):
            if h >= um:
                continue
            w += E * s * eps * eps * (H - h) * (H + h) / (2 * H) if h <= chi else \
                E * s * (um - h) ** 2 / (2 * H)
        return w

    def u_max(self, W):
        lo, hi = D(0), self.H
        while hi - lo > D("1e-60") * hi:
            mid = (lo + hi) / 2
            lo, hi = (mid, hi) if self.work_load(mid) < W else (lo, mid)
        return (lo + hi) / 2


# (fx, fz, E/sigma_y, H, V*) for the series, E/sigma_y from 500 to 1e20
SERIES_CASES = [
    (1.5, 1.3, 500.0, 10.0, 4.4721359549995794e-3),
    (1.5, 1.3, 1e4, 10.0, 1e-3),
    (1.5, 1.3, 1e8, 10.0, 1e-5),
    (1.5, 1.3, 1e12, 10.0, 1e-7),
    (1.5, 1.3, 1e16, 10.0, 1e-9),
    (1.5, 1.3, 1e18, 10.0, 1e-10),
    (1.5, 1.3, 1e20, 10.0, 1e-12),
    (1.2, 1.9, 1e14, 5.0, 3e-9),
    (1.8, 1.1, 1e16, 20.0, 2e-9),
    (1.01, 1.9, 1e12, 10.0, 1e-7),  # half the area below the stages carried one by one
]


def main():
    print("/* generated by tests/laws_reference.py (120-digit decimal): fx, fz, E/sigma_y, H, V*;")
    print(" * u_max/h0, e as printed and consistent; P/P_Y loading at u_max, and unloading from")
    print(" * u_max at x1 (branch 1, midway to chi_M) and x2 (branch 2, midway to chi_M from")
    print(" * hbar), both readings */")
    for fx, fz, E, H, V in CASES:
        law = Law(fx, fz, E, H)
        W = D(V) * D(V) * D(E)
        um = law.u_max(W)
        Wl = law.work_load(um)
        e = [(law.work_unload(um, cons) / Wl).sqrt() for cons in (0, 1)]
        xm = D(float(um))  # the forces at the double nearest u_max, and at doubles x1, x2
        chiM, hbar = law.chi(xm), xm - law.eps * law.H
        x1, x2 = D(float((chiM + xm) / 2)), D(float((hbar + chiM) / 2))
        P = [law.load(xm), law.unload(xm, x1, 0), law.unload(xm, x2, 0), law.unload(xm, x2, 1)]
        print("    {%r, %r, %r, %r, %r, %.20e, %.20e, %.20e," % (fx, fz, E, H, V, float(um),
                                                               float(e[0]), float(e[1])))
        print("     %r, %r, %.20e, %.20e, %.20e, %.20e}," % (
            float(x1), float(x2), *[float(v) for v in P]))

    print("\n/* generated by tests/laws_reference.py (120-digit decimal): the series' fx, fz,")
    print(" * E/sigma_y, H, V*, its u_max/h0 and e */")
    for fx, fz, E, H, V in SERIES_CASES:
        law = Series(fx, fz, E, H)
        W = D(V) * D(V) * D(E)
        um = law.u_max(W)
        e = (law.work_unload(um) / law.work_load(um)).sqrt()
        print("    {%r, %r, %r, %r, %r, %.20e, %.20e}," % (fx, fz, E, H, V, float(um), float(e)))
    # an impact whose u_max lies eps_y H* / 2 above stage 5's top at E/sigma_y = 1e16: that
    # stage is elastic and its energy back hangs on u_max's last digits (refused)
    law = Series(1.5, 1.3, 1e16, 10.0)
    print("\n/* the energy (in sigma_y l0 h0) that reaches stage 5's top plus eps_y H* / 2 at")
    print(" * E/sigma_y = 1e16 */")
    print("#define SERIES_ELASTIC_NEAR_UMAX %.20e" %
          float(law.work_load(law.h[5] + law.eps * law.H / 2)))


if __name__ == "__main__":
    main()
