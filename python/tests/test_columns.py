"""The per-row results are the library's output columns (ct_sweep_columns): the same names as
the table, and the same bits as the cantact program's e table and time columns."""
import csv
import math

import numpy as np

import cantact

lib, ffi = cantact.lib, cantact.ffi


def table():
    """The library's column table, read here through the C API."""
    p = ffi.new("const ct_column **")
    n = lib.ct_sweep_columns(p)
    return [{"name": ffi.string(p[0][k].name).decode(),
             "group": ffi.string(p[0][k].group).decode(),
             "type": p[0][k].type.decode(), "digits": p[0][k].digits} for k in range(n)]


def number(text):
    return math.nan if text == "" else float(text)


def same(a, b):
    return (math.isnan(a) and math.isnan(b)) or a == b


def test_attributes_are_the_tables_columns():
    cols = table()
    names = [c["name"] for c in cols if c["type"] in "dw" and c["name"] != "V_star"]
    assert "dem_time_step_over_tau" in names
    assert [f[0] for f in cantact.ROW_FIELDS] == names
    assert [c["name"] for c in cantact.COLUMNS] == [c["name"] for c in cols]
    r = cantact.restitution(cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500), V_star=[1e-3, 3e-3],
                            impacts=2, time=True)
    floats = sorted(k for k, v in vars(r).items()
                    if not k.startswith("_") and isinstance(v, np.ndarray)
                    and v.dtype == np.float64 and v.shape == r.e.shape)
    # every float per-row attribute is a column, but for the impact energy (library units)
    assert floats == sorted(names + ["kinetic_energy"])


def test_default_scene_every_column_as_the_cli(run_cli, source):
    with open(run_cli("run", f"{source}/scripts/scenes/default.ini", "--set",
                      "output.what=e,time")) as f:
        rows = list(csv.DictReader(f))
    header = list(rows[0].keys())
    cols = {c["name"]: c for c in table()}
    written = [h for h in header if h in cols and cols[h]["type"] == "d" and h != "V_star"]
    # the e table's and the time group's float columns, all of them
    assert written == [c["name"] for c in table() if c["group"] in ("e", "time")
                       and c["type"] == "d" and c["name"] != "V_star"]
    assert "dem_time_step_over_tau" in written
    V = np.array([number(row["V_star"]) for row in rows])
    s = cantact.Cantor(fx=1.5, fz=1.3, H=10, E=500)
    r = cantact.restitution(s, V_star=V, time=True)
    assert len(rows) == 31 and r.e.shape == (31, 1)
    for k, row in enumerate(rows):
        assert int(row["impact"]) == 1 and number(row["V_star"]) == r.V_star[k]
        assert int(row["elastic"]) == int(r.elastic[k, 0])
        for name in written:
            x = float(getattr(r, name)[k, 0])
            if cols[name]["digits"] == 3:  # written to 3 digits: quadrature_error
                x = float("%.3g" % x)
            assert same(number(row[name]), x), (name, k, row[name], x)


def test_column_values_are_ct_column_value_bitwise():
    """ct_column_values (one call per column, what Restitution reads) gives every column of
    every row the bits of ct_column_value of that row: rows that succeeded, a failed one and
    one not run (whose bytes hold a message), in a layer whose h0, l0, sigma_y are not 1."""
    s = cantact.Rods([0.0, 0.3e-3, 0.1e-3], [2e-6, 1e-6, 3e-6], E=2e11, sigma_y=4e8, H=5,
                     unit="m")
    V = np.array([1e-4, 3e-3, 2.0, 0.02])
    solver = cantact._keys.RunKeys("test").solver()  # opts lives in it
    opts = solver.opts
    b, _ = s._build(V, 2, opts)
    n = V.size * 2
    rows = ffi.new("ct_sweep_row[]", n)
    spec = ffi.new("ct_sweep_spec *")
    speeds = ffi.from_buffer("double[]", V)
    spec.V_star, spec.nvel, spec.impacts, spec.opts = speeds, V.size, 2, opts
    spec.dynamics = 1
    assert lib.ct_sweep(b, spec, rows) == 0
    status = [rows[q].status for q in range(n)]
    assert status.count(0) == n - 2 and lib.CT_ESKIPPED in status  # V* = 2 crushes the layer
    layer = lib.ct_bundle_layer(b)
    assert layer.h0 != 1.0 and layer.l0 != 1.0 and layer.sigma_y != 1.0
    p = ffi.new("const ct_column **")
    for k in range(lib.ct_sweep_columns(p)):
        c = p[0] + k
        one = np.array([lib.ct_column_value(c, rows + q, layer) for q in range(n)])
        many = np.full(n, 7.0)
        lib.ct_column_values(c, rows, n, layer, ffi.from_buffer("double[]", many))
        assert one.tobytes() == many.tobytes(), ffi.string(c.name)
        part = np.full(n, 7.0)  # n counts: the rows from the pointer given, no more
        lib.ct_column_values(c, rows + 1, n - 2, layer, ffi.from_buffer("double[]", part))
        assert part[:n - 2].tobytes() == one[1:n - 1].tobytes() and (part[n - 2:] == 7.0).all()
