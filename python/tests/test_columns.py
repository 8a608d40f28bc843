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
