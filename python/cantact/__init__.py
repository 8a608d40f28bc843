"""cantact: the coefficient of restitution of a rough surface of elastic-perfectly-plastic
rods (Cantor-fractal, random Cantor, a measured profile or your own rods), through libcantact.

    import cantact
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)          # E/sigma_y = 500, H*/h0 = 10
    r = cantact.restitution(s, V_star=np.geomspace(1e-5, 1e-2, 31))
    r.e[:, 0], r.u_max_over_h0[:, 0], r.V_star_crit[:, 0]     # arrays [speed, impact - 1]
    t = cantact.table(s, V_star=(1e-5, 1e-2), tolerance=1e-6)  # e(V*) with a checked error
    t(0.003)                                                   # its interpolation
    cantact.zeta_of_e(t(0.003), law="clipped")                 # the damping ratio (DEM)
    m = cantact.Profile("map.x3p", H=10, E=2e11, sigma_y=4e8, periodic=True)  # a map that
    r = cantact.restitution(m, mass=5.14e-4, speed=[0.01, 0.1],  # repeats, struck by a ball
                            body=cantact.Sphere(2.5e-3))             # of R = 2.5 mm

Results are dimensionless as the cantact program's (V*, u/h0, P/P_Y); errors raise
cantact.Error subclasses carrying the library's status and message. See README.md.
"""
from ._errors import guard as _guard
from ._errors import (Error, InvalidInput, IOFailure, NoConvergence, NotRun, OutOfMemory,
                      OutsideModel, strerror)
from ._ffi import LIBRARY_PATH, ffi, lib
from ._keys import BODIES, BODY_ROWS, KINDS, RUN_ROWS
from ._bodies import Body, Cylinder, Flat, Sphere
from ._results import COLUMNS, ROW_FIELDS, Restitution
from ._surfaces import Cantor, Profile, RandomCantor, Rods, Surface
from ._api import (DAMPING_LAWS, Ensemble, LoadCurve, Table, asym_load, asym_unload, e_of_zeta,
                   ensemble, landings, law_restitution, load_curve, read_table, restitution, series_load,
                   series_unload, table, zeta_of_e)

__all__ = [
    "Surface", "Cantor", "RandomCantor", "Rods", "Profile", "KINDS", "RUN_ROWS",
    "Body", "Flat", "Cylinder", "Sphere", "BODIES", "BODY_ROWS",
    "restitution", "Restitution", "ensemble", "Ensemble", "landings",
    "load_curve", "LoadCurve", "series_load", "series_unload", "asym_load", "asym_unload",
    "law_restitution", "table", "Table", "read_table", "Error", "InvalidInput", "OutOfMemory",
    "OutsideModel", "NoConvergence", "IOFailure", "NotRun", "strerror", "ROW_FIELDS", "COLUMNS",
    "LIBRARY_PATH", "zeta_of_e", "e_of_zeta", "DAMPING_LAWS",
]

# The boundary: every public function and method raises the module's exceptions only
# (cantact.Error's classes), never a bare Python one (_errors.py states the rule).
for _name in __all__:
    globals()[_name] = _guard(globals()[_name])
del _name
