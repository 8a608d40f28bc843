"""cantact e(V*) tables in Yade: every new contact of Yade's linear spring-dashpot
(ViscElMat / ViscElPhys, Law2_ScGeom_ViscElPhys_Basic) gets the normal damping cn that rebounds
with the table's e at its normal impact speed.

    import cantact_yade
    damping = cantact_yade.Damping("e_table.csv")   # a table `cantact table` wrote
    # or one table per pair of materials (ids, labels or Material objects; either order):
    # damping = cantact_yade.Damping(pairs={("steel2", "steel2"): "e_1_1.csv",
    #                                       ("steel2", "steel3"): "e_1_2.csv",
    #                                       ("steel3", "steel3"): "e_2_2.csv"})
    O.engines = [ForceResetter(), InsertionSortCollider([Bo1_Sphere_Aabb()]),
                 InteractionLoop([Ig2_Sphere_Sphere_ScGeom()],
                                 [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                                 [Law2_ScGeom_ViscElPhys_Basic()]),
                 damping.engine(),                  # right after the InteractionLoop
                 NewtonIntegrator(damping=0)]
    damping.check_engines()                         # refuses an order or a setting that breaks it

What it does, in a PyRunner run every step between the InteractionLoop and the
NewtonIntegrator, for each contact made real in this step (Interaction.iterMadeReal ==
O.iter):
  v_n  = the normal approach speed the law saw (the bodies' velocities, as Yade's law takes them)
  table = the table of the two bodies' pair of materials (pairs=), else the one table given
  e    = table.e_of_speed(v_n)                    (cantact.read_table: the same bits as
                                                   include/cantact_table.h's ct_tab_e_of_speed)
  zeta = cantact.zeta_of_e(e, law="clipped")      (Yade clips the normal force at 0: the
                                                   separation is where k delta + c delta'
                                                   reaches 0, not at zero overlap)
  cn   = 2 zeta' sqrt(m k_n)                      (m = m1 m2 / (m1 + m2); a body that is not
                                                   dynamic counts as infinitely heavy)
where zeta' corrects Yade's time integration (dt_compensation, on by default): the
NewtonIntegrator evaluates the dashpot with the velocity of half a step earlier, which acts as
a damping ratio zeta' / sqrt(1 - zeta' omega dt) (omega = sqrt(k_n / m)): a first-order error
in e of about zeta omega dt / 2. zeta' solves zeta' / sqrt(1 - zeta' omega dt) = zeta.

The first step (first_step, on by default): Yade has computed the new contact's force with the
material's cn (0 here) before any Python runs, over a step in which the contact began part of
the way through. The runner adds the difference between that force and the impulse the
contact should have had since it began (the overlap d0 was reached at speed v_n, d0 / v_n
ago: tau = d0 / v_n + dt / 2, impulse k_n v_n tau^2 / 2 + cn v_n tau) to both bodies, in the
same step (O.forces.addF before the NewtonIntegrator). Without it e is off by about
2 zeta omega dt (phase - 1/2); with both corrections the error is second order in dt
(measured in head_on.py).

Limits: normal damping only (cs, friction, rolling untouched); no periodic cell (the shift of
a contact across the cell is not in v_n); one Python call per step (a large simulation pays
for the loop over its interactions in Python); e is the first impact's on the virgin surface,
as the table says, whatever happened at that spot before.
"""
import math
import os
import sys

import cantact

__all__ = ["Damping"]


def _material_key(k, pair):
    """a material named in a pairs= key: its id (int >= 0), its label (str), or the Material
    (its id read when a contact needs it: it may be appended to O.materials later)"""
    if isinstance(k, bool) or not (isinstance(k, (int, str)) or hasattr(k, "id")):
        raise ValueError(f"cantact_yade: pairs key {pair!r}: a material is its id (int), its "
                         f"label (str) or the Material, not {k!r}")
    if isinstance(k, int) and k < 0:
        raise ValueError(f"cantact_yade: pairs key {pair!r}: material id {k} < 0")
    if isinstance(k, str) and not k:
        raise ValueError(f"cantact_yade: pairs key {pair!r}: an empty label")
    return k


def _ident(k):
    return k if isinstance(k, (int, str)) else ("Material", id(k))


def _matches(k, mat):
    if isinstance(k, int):
        return mat.id == k
    if isinstance(k, str):
        return mat.label == k
    return k is mat or (k.id >= 0 and k.id == mat.id)


class Damping:
    """Per-contact normal damping from cantact tables. table: a path or a cantact.Table with
    v_per_V_star (the table's speeds in Yade's units: write the scene's [impact] mass in the
    same units as Yade's), for every contact. pairs: {(material A, material B): table, ...},
    one table per pair of materials (either order; a material is its id in O.materials, its
    label, or the Material itself), e.g. the tables dem/pair_tables.py writes for each pair's
    reduced radius and mass; a contact of a pair not listed takes table, or stops the run with
    an error naming its materials when there is none. law: "clipped" (Yade's
    Law2_ScGeom_ViscElPhys_Basic; "tension" only for a law that lets the dashpot pull).
    first_step, dt_compensation: the corrections above. Counts: contacts (set up), outside
    (impact speeds outside their table: its end's e)."""

    def __init__(self, table=None, law="clipped", first_step=True, dt_compensation=True,
                 label="cantactDamping", pairs=None):
        read = {}  # a path read once, whatever the pairs naming it

        def load(t, what):
            if isinstance(t, cantact.Table):
                tab = t
            elif isinstance(t, (str, bytes, os.PathLike)):
                key = os.path.abspath(os.fsdecode(t))
                if key not in read:
                    read[key] = cantact.read_table(t)
                tab = read[key]
            else:
                raise ValueError(f"cantact_yade: {what}: a table is a path or a cantact.Table, "
                                 f"not {type(t).__name__}")
            if tab.v_per_V_star is None:
                raise ValueError(f"cantact_yade: {what} has no v_per_V_star (give [impact] mass "
                                 "in the scene that wrote it)")
            return tab

        if table is None and not pairs:
            raise ValueError("cantact_yade: give a table, or pairs={(material A, material B): "
                             "table, ...}")
        self.table = None if table is None else load(table, "the table")
        self.pairs = []  # (key A, key B, table)
        if pairs is not None:
            if not hasattr(pairs, "items"):
                raise ValueError("cantact_yade: pairs must be a dict {(material A, material B): "
                                 f"table}}, not {type(pairs).__name__}")
            seen = {}
            for pair, t in pairs.items():
                if not (isinstance(pair, tuple) and len(pair) == 2):
                    raise ValueError(f"cantact_yade: pairs key {pair!r}: give two materials, "
                                     "(A, B)")
                ka, kb = (_material_key(k, pair) for k in pair)
                same = frozenset((_ident(ka), _ident(kb)))  # (A, B) and (B, A) alike
                if same in seen:
                    raise ValueError(f"cantact_yade: pairs {seen[same]!r} and {pair!r} are the "
                                     "same pair of materials")
                seen[same] = pair
                self.pairs.append((ka, kb, load(t, f"the table of pair {pair!r}")))
        self._of = {}  # (material id, material id) -> table, as contacts meet them
        if law not in cantact.DAMPING_LAWS:
            raise ValueError(f"cantact_yade: law = {law!r}: must be 'clipped' or 'tension'")
        self.law = law
        self.first_step = first_step
        self.dt_compensation = dt_compensation
        self.label = label
        self.contacts = 0
        self.outside = 0
        self.log = []  # (id1, id2, iter, v_n, e, zeta, cn) of every contact set up

    # ---- which table ------------------------------------------------------------------------

    def table_of(self, a, b):
        """The table of a contact between a and b (bodies or materials): the one of their pair
        of materials in pairs, else table; ValueError when none applies, or when two entries of
        pairs name the same pair (say by label and by id) with different tables."""
        ma, mb = (getattr(x, "material", x) for x in (a, b))
        key = (ma.id, mb.id) if ma.id <= mb.id else (mb.id, ma.id)
        if ma.id >= 0 and key in self._of:
            return self._of[key]
        found = [t for ka, kb, t in self.pairs
                 if (_matches(ka, ma) and _matches(kb, mb))
                 or (_matches(ka, mb) and _matches(kb, ma))]
        if len({id(t) for t in found}) > 1:
            raise ValueError(f"cantact_yade: materials {_name(ma)} and {_name(mb)}: pairs gives "
                             f"{len(found)} different tables for them")
        tab = found[0] if found else self.table
        if tab is None:
            raise ValueError(f"cantact_yade: no table for a contact of materials {_name(ma)} and "
                             f"{_name(mb)}: give it in pairs, or a table for every other pair")
        if ma.id >= 0 and mb.id >= 0:
            self._of[key] = tab
        return tab

    # ---- the engine -------------------------------------------------------------------------

    def engine(self):
        """The PyRunner to put right after the InteractionLoop (iterPeriod 1)."""
        from yade.wrapper import PyRunner
        main = sys.modules["__main__"]
        name = "_cantact_yade_" + self.label
        setattr(main, name, self)  # PyRunner's command runs in __main__
        return PyRunner(command=f"{name}.step()", iterPeriod=1, label=self.label)

    def check_engines(self):
        """Raises ValueError unless O.engines runs this runner every step right after the
        InteractionLoop and before a NewtonIntegrator with damping = 0 (Yade's numerical
        damping would change every rebound)."""
        from yade import O
        from yade.wrapper import InteractionLoop, NewtonIntegrator, PyRunner
        engines = list(O.engines)
        k = next((i for i, e in enumerate(engines) if isinstance(e, PyRunner)
                  and e.label == self.label), None)
        if k is None:
            raise ValueError("cantact_yade: the runner is not in O.engines")
        if engines[k].iterPeriod != 1 or engines[k].virtPeriod or engines[k].realPeriod:
            raise ValueError("cantact_yade: the runner must run every step (iterPeriod = 1)")
        if k == 0 or not isinstance(engines[k - 1], InteractionLoop):
            raise ValueError("cantact_yade: the runner must come right after the InteractionLoop")
        newton = [e for e in engines[k + 1:] if isinstance(e, NewtonIntegrator)]
        if not newton:
            raise ValueError("cantact_yade: no NewtonIntegrator after the runner")
        if newton[0].damping != 0:
            raise ValueError(f"cantact_yade: NewtonIntegrator damping = {newton[0].damping}: "
                             "must be 0 (it damps every rebound)")

    # ---- per step ---------------------------------------------------------------------------

    def step(self):
        from yade import O
        it = O.iter
        for i in O.interactions:
            if i.iterMadeReal == it and i.isReal:
                self._set_up(O, i)

    def _set_up(self, O, i):
        g, p = i.geom, i.phys
        b1, b2 = O.bodies[i.id1], O.bodies[i.id2]
        s1, s2 = b1.state, b2.state
        n, c = g.normal, g.contactPoint
        c1, c2 = c - s1.pos, c - s2.pos
        rel = (s1.vel + s1.angVel.cross(c1)) - (s2.vel + s2.angVel.cross(c2))
        v_n = n.dot(rel)  # > 0 approaching, as the law's normalVelocity
        m1 = s1.mass if b1.dynamic else math.inf
        m2 = s2.mass if b2.dynamic else math.inf
        m = 1.0 / (1.0 / m1 + 1.0 / m2)
        k = p.kn
        if not (v_n > 0.0 and k > 0.0 and 0.0 < m < math.inf):
            return  # not an impact (a resting contact, or no mass): left as Yade made it
        table = self.table_of(b1, b2)
        V = v_n / table.v_per_V_star
        if not bool(table.covers(V)[0]):
            self.outside += 1
        e = float(table.e_of_speed(v_n)[0])
        zeta = cantact.zeta_of_e(e, law=self.law)
        omega, dt = math.sqrt(k / m), O.dt
        z = zeta
        if self.dt_compensation and zeta > 0.0:
            a = zeta * zeta * omega * dt  # z / sqrt(1 - z omega dt) = zeta
            z = 2.0 * zeta * zeta / (a + math.sqrt(a * a + 4.0 * zeta * zeta))
        cn_old, cn = p.cn, 2.0 * z * math.sqrt(m * k)
        p.cn = cn
        if self.first_step:
            d0 = g.penetrationDepth
            applied = max(0.0, k * d0 + cn_old * v_n)
            tau = d0 / v_n + 0.5 * dt
            wanted = (0.5 * k * v_n * tau * tau + cn * v_n * tau) / dt
            df = n * (wanted - applied)  # as the law's force: -df on id1, +df on id2
            O.forces.addF(i.id1, -df)
            O.forces.addF(i.id2, df)
            O.forces.addT(i.id1, -c1.cross(df))
            O.forces.addT(i.id2, c2.cross(df))
        self.contacts += 1
        self.log.append((i.id1, i.id2, O.iter, v_n, e, zeta, cn))


def _name(mat):
    return f"{mat.label!r} (id {mat.id})" if mat.label else f"id {mat.id}"


def main_guard(fn):
    """Runs fn() as a Yade batch script's body and exits with its return value; an exception
    exits 1 (yade -x itself exits 0 after an uncaught exception)."""
    try:
        status = fn()
    except SystemExit:
        raise
    except BaseException:
        import traceback
        traceback.print_exc()
        status = 1
    sys.stdout.flush()
    sys.stderr.flush()
    sys.exit(int(status or 0))
