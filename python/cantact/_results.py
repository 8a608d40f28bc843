"""The rows of a sweep as the library's output columns (ct_sweep_columns, src/columns.c).

Every column of type 'd' but V_star is an attribute of Restitution with the column's name, and
every value is the library's own: ct_column_values of the rows in the layer they were
computed in (one call per column, bitwise ct_column_value of each row: the value over its
unit's factor, then over the column's divisor), so the module's numbers are the bits of
`cantact run`'s e table and time columns, and the module holds no column list, unit or factor
of its own. The sweep's times are t / tau already (its mass is E l0 / h0); the "time"
group is NaN unless restitution(..., time=True)."""
import numpy as np

from . import _check as chk
from ._errors import memory, size_text
from ._ffi import ffi, lib

# The names of the library's units (ct_unit), as COLUMNS shows them.
_UNIT_NAMES = {lib.CT_UNIT_ONE: "one", lib.CT_UNIT_LENGTH: "length",
               lib.CT_UNIT_FORCE: "force", lib.CT_UNIT_ENERGY: "energy",
               lib.CT_UNIT_TIME: "time", lib.CT_UNIT_COUNT: "count",
               lib.CT_UNIT_SPEED: "speed"}
# ROW_FIELDS' unit codes, as before the table: "1" dimensionless as computed (times too),
# "u" a length (/ h0), "P" a force (/ P_Y = sigma_y l0), "W" an energy (/ P_Y h0)
_UNIT_CODES = {"one": "1", "time": "1", "length": "u", "force": "P", "energy": "W",
               "count": "1", "speed": "1"}


def _field_of(offset):
    """The ct_sweep_row field ("r.e", "dyn.t_contact", "V_star") at a byte offset."""
    for name, f in ffi.typeof("ct_sweep_row").fields:
        if f.type.kind == "struct":
            for sub, g in f.type.fields:
                if f.offset + g.offset == offset:
                    return f"{name}.{sub}"
        elif f.offset == offset:
            return name
    return None


def _read_columns():
    """The library's column table: (the table itself, a tuple of dicts: name, group, unit,
    type, digits, physical, divisor, offset, field, doc, index)."""
    p = ffi.new("const ct_column **")
    n = lib.ct_sweep_columns(p)
    out = []
    for k in range(n):
        c = p[0][k]

        def text(ptr):
            return ffi.string(ptr).decode() if ptr != ffi.NULL else None

        out.append({"name": text(c.name), "group": text(c.group),
                    "unit": _UNIT_NAMES.get(int(c.unit), str(int(c.unit))),
                    "type": c.type.decode(), "digits": int(c.digits),
                    "physical": text(c.physical), "divisor": float(c.divisor),
                    "offset": int(c.offset), "field": _field_of(int(c.offset)),
                    "doc": text(c.doc), "index": k})
    return p[0], tuple(out)


_TABLE, COLUMNS = _read_columns()  # every column: the e table, the time columns, the row's
# The columns that are Restitution's per-row float attributes.
_ROW_COLUMNS = tuple(c for c in COLUMNS if c["type"] in "dw" and c["name"] != "V_star")
# (attribute, field of ct_sweep_row, unit code) of each, derived from the table: kept for
# compatibility; COLUMNS has the rest (e.g. dem_time_step_over_tau's divisor, 50).
ROW_FIELDS = tuple((c["name"], c["field"], _UNIT_CODES[c["unit"]]) for c in _ROW_COLUMNS)
# The columns whose NaN is the library's "not computed" in a row that succeeded (the
# closed-form check did not cover the row: the program writes them empty). Any other number
# of a row that succeeded must be finite: Restitution refuses it otherwise (OutsideModel).
_MAY_BE_NAN = frozenset({"e_closed_form", "quadrature_error"})


def finite_info(info):
    """info (what a surface's build found: its depth's truncation bound, ...), its numbers
    checked finite."""
    for k, v in info.items():
        if isinstance(v, float):
            chk.finite_result(f"info {k}", v)
    return info


def _row_view(rows, n, offset, dtype):
    """The field at byte offset of n ct_sweep_rows, as a strided NumPy view."""
    buf = ffi.buffer(rows)
    return np.ndarray(shape=(n,), dtype=dtype, buffer=buf, offset=offset,
                      strides=(ffi.sizeof("ct_sweep_row"),))


def column_values(column, rows, n, layer):
    """The column (a dict of COLUMNS) of n rows, dimensionless by layer: ct_column_values, one
    call for the column (bitwise ct_column_value of each row)."""
    c = _TABLE + column["index"]
    with memory(f"{column['name']}: {n} values ({size_text(n, 8)})"):
        out = np.empty(n, dtype=np.float64)
    lib.ct_column_values(c, rows, n, layer, ffi.from_buffer("double[]", out))
    return out


class Restitution:
    """The rows of a restitution sweep. Every per-row array has shape (len(V_star), impacts):
    [speed, impact - 1]. Attributes: V_star; the library's output columns (cantact.COLUMNS)
    of type double, with their names: e, u_max_over_h0, e_closed_form, quadrature_error (NaN
    with check=False), V_star_crit, u_release_over_h0, u_contact_over_h0, W_load_over_PY_h0,
    W_unload_over_PY_h0, e_rounding, and the time columns t_contact_over_tau,
    t_load_over_tau, t_unload_over_tau, P_peak_over_PY, e_kinematic, unload_period_over_tau,
    dem_time_step_over_tau (NaN without time=True), the speed columns
    v_impact_over_h0_per_tau (sqrt(2) V*) and v_rebound_over_h0_per_tau (e sqrt(2) V*) (floats;
    NaN where a row failed);
    kinetic_energy (the impact's energy in the library's units of the surface's rods: for a
    Cantor surface the dimensionless l0 E h0 V*^2); elastic (bool); status (int: 0, or the
    library's status of a failed or not-run row); message (str); info (depth, bound, rods,
    omitted of the surface built)."""

    def __init__(self, V_star, impacts, rows, layer, info, surface=None, time=True):
        self.V_star = V_star
        self.impacts = impacts
        self.info = finite_info(info)
        self._surface = surface
        shape = (V_star.size, impacts)
        n = V_star.size * impacts

        def field(name, dtype):
            return np.array(_row_view(rows, n, ffi.offsetof("ct_sweep_row", *name.split(".")),
                                      dtype)).reshape(shape)

        self.status = field("status", np.intc).astype(int)
        failed = self.status != 0

        def finite(name, x, may_be_nan=False):
            """x, or OutsideModel naming a non-finite number of a row that succeeded."""
            return chk.finite_result(
                name, x, ~failed, may_be_nan,
                lambda k: f"V* = {V_star[k[0]]!r}, impact {k[1] + 1}: {name}")

        for c in _ROW_COLUMNS:
            if c["group"] == "time" and not time:
                setattr(self, c["name"], np.full(shape, np.nan))
                continue
            x = column_values(c, rows, n, layer).reshape(shape)
            finite(c["name"], x, c["name"] in _MAY_BE_NAN)
            x[failed] = np.nan
            setattr(self, c["name"], x)
        self.kinetic_energy = finite("kinetic_energy", field("r.kinetic_energy", np.float64))
        self.kinetic_energy[failed] = np.nan
        self._u_max = field("r.u_max", np.float64)  # library units: a profile's refit
        self._u_max[failed] = np.nan
        self.elastic = (field("r.elastic", np.intc) != 0) & ~failed
        # a message is a C string sharing its bytes with the row's results (cantact.h): it ends
        # at its first NUL ("" where the row succeeded: the results follow message[0])
        size = dict(ffi.typeof("ct_sweep_row").fields)["message"].type.length
        msg = _row_view(rows, n, ffi.offsetof("ct_sweep_row", "message"), f"S{size}")
        self.message = np.array([m.partition(b"\0")[0].decode(errors="replace") for m in msg],
                                dtype=object).reshape(shape)

    def __repr__(self):
        return (f"<Restitution: {self.V_star.size} speeds x {self.impacts} impacts, "
                f"{int((self.status != 0).sum())} failed>")
