"""The library's key tables, read, and the one translation of a Python value into the text a
row parses.

Every kind of surface has its rows (ct_surface_kind_keys: sections surface, material and what
else the kind owns), and so have a run (ct_run_keys_table: sections impact, solver, table and
ensemble) and a body (ct_body_keys_table: body.shape, body.radius, body.position and
surface.periodic, stored in a ct_body). The library parses a value through its row
(ct_surface_set for a surface's key, ct_key_parse for a run's or a body's) and refuses it in
its own words, so the module accepts and refuses what a scene does, with the same message, and
holds no key, range, default or message of its own. Python judges a value's type only, by the
module's rules (_check.py): a number key takes a real number, made the double nearest to it
(its text is repr of that double: exact); an integer key an integer (its digits); a word or
depth word a str; a file a path; a point a number x or a sequence (x,) or (x, y) (their reprs,
", " between). Messages of a range say "section.name = value: reason", as the program's
(without its file:line)."""
from collections import namedtuple

import numpy as np

from . import _check as chk
from ._errors import error, invalid
from ._ffi import ffi, lib

# A row of a key table: section, name, type (ct_key_type), lo, hi, flags (CT_KEY_*), words (a
# tuple), range (what an out-of-range value is told), default (as the docs show it: "" none),
# doc, and c (the row itself, const ct_key *, for the library's calls).
Row = namedtuple("Row", "section name type lo hi flags words range default doc c")


def _text_of(ptr):
    return None if ptr == ffi.NULL else ffi.string(ptr).decode()


def _rows(table, n):
    out = []
    for k in range(n):
        r = table[k]
        words = _text_of(r.words)
        out.append(Row(_text_of(r.section), _text_of(r.name), int(r.type), float(r.lo),
                       float(r.hi), int(r.flags), tuple(words.split("|")) if words else (),
                       _text_of(r.range), _text_of(getattr(r, "def")), _text_of(r.doc),
                       table + k))
    return tuple(out)


def _kinds():
    n = ffi.new("size_t *")
    out = {}
    for k in range(lib.ct_surface_kind_count()):
        table = lib.ct_surface_kind_keys(k, n)
        out[_text_of(lib.ct_surface_kind_name(k))] = _rows(table, n[0])
    return out


def _run_rows():
    n = ffi.new("size_t *")
    return _rows(lib.ct_run_keys_table(n), n[0])


def _body_rows():
    n = ffi.new("size_t *")
    return _rows(lib.ct_body_keys_table(n), n[0])


# The kinds of surface in the registry's order, each with its rows.
KINDS = _kinds()
# The rows of a run (impact, solver, table, ensemble), in the table's order.
RUN_ROWS = _run_rows()
_RUN = {f"{r.section}.{r.name}": r for r in RUN_ROWS}
# The rows of a body (section body) and surface.periodic, in the table's order: offsets into
# a ct_body.
BODY_ROWS = _body_rows()
# The kinds of body in the registry's order (ct_body_name).
BODIES = tuple(_text_of(lib.ct_body_name(k)) for k in range(lib.ct_body_count()))


# Python's words for a row's words: check=True is solver.check = all (every impact also in
# closed form, the module's default; the program's is auto), False none; errors="raise" is
# solver.on_error = stop, "rows" skip; periodic=True is surface.periodic = true, False false.
# The rows' own words are taken as well.
WORDS = {"solver.check": {True: "all", False: "none"},
         "solver.on_error": {"raise": "stop", "rows": "skip"},
         "surface.periodic": {True: "true", False: "false"}}


def run_row(key):
    """The run's row "section.name"."""
    return _RUN[key]


def own_words(key, row, name, value):
    """value given as the keyword argument name, Python's word of the row key (WORDS) made the
    row's own word; a str is the library's to judge; anything else refused naming both."""
    words = WORDS.get(key)
    if words is None:
        return value
    for given, word in words.items():
        if (isinstance(value, (bool, np.bool_)) if isinstance(given, bool)
                else isinstance(value, str)) and value == given:
            return word
    if not isinstance(value, str):  # a str is the library's to judge
        raise invalid(f"{name} = {chk._text(value)}: must be "
                      f"{' or '.join(map(repr, words))} ({key}: {row.range})")
    return value


def message():
    """The library's message of the last failure."""
    return ffi.string(lib.ct_error_message()).decode(errors="replace")


def shown(text):
    """A value's text as the library's messages show it: at most 80 characters, a longer one
    cut to 72 and "..."."""
    t = text.decode(errors="replace") if isinstance(text, bytes) else text
    return t if len(t) <= 80 else t[:72] + "..."


def _word(name, value, row):
    """A word given as a str, as bytes; anything else refused with the row's own words."""
    if isinstance(value, str) and "\0" not in value:
        try:
            return value.encode()
        except UnicodeEncodeError:
            pass
    raise invalid(f"{name} = {chk._text(value)}: {row.range}")


def text(row, name, value):
    """The text (bytes) row parses for value, given as the keyword argument `name`: the type
    is judged here (the module's rules), the value by the library."""
    t = row.type
    if t == lib.CT_KEY_NUMBER:
        return repr(chk._double(name, value)).encode()
    if t in (lib.CT_KEY_INTEGER, lib.CT_KEY_COUNT):
        return str(chk.integer(name, value)).encode()
    if t == lib.CT_KEY_DEPTH:
        if isinstance(value, str):
            return _word(name, value, row)
        try:
            return str(chk.integer(name, value)).encode()
        except Exception:
            raise invalid(f"{name} = {chk._text(value)}: must be an integer or one of "
                          f"{', '.join(map(repr, row.words))}") from None
    if t == lib.CT_KEY_WORD:
        return _word(name, value, row)
    if t == lib.CT_KEY_TEXT:
        if row.flags & lib.CT_KEY_FILE:
            return chk.path(name, value)
        if isinstance(value, str) and "\0" not in value:
            return value.encode("utf-8", "surrogateescape")
        raise invalid(f"{name} = {chk._text(value)}: {row.range}")
    if t == lib.CT_KEY_RANGE:
        try:
            ends = list(value)
        except TypeError:
            ends = [value]
        return ":".join(repr(chk._double(f"{name}[{k}]", x)) for k, x in enumerate(ends)).encode()
    if t == lib.CT_KEY_POINT:  # x, or (x,) or (x, y): the row judges how many
        if isinstance(value, (str, bytes)):
            raise invalid(f"{name} = {chk._text(value)}: {row.range}")
        if isinstance(value, np.ndarray) and value.ndim == 0:
            value = value[()]
        try:
            xs = list(value)
        except TypeError:
            return repr(chk._double(name, value)).encode()
        return ", ".join(repr(chk._double(f"{name}[{k}]", x)) for k, x in enumerate(xs)).encode()
    raise invalid(f"{name}: {row.section}.{row.name} is not given as a keyword argument")


def parse(row, value, name=None, where=None):
    """value (given as the keyword argument name) parsed through a row outside any settings
    of its own (a kind's row asked of a method's argument): the number, integer, word index or
    (from, to) it stores; refused in the library's words ("where: section.name = value:
    reason")."""
    if row.type not in (lib.CT_KEY_NUMBER, lib.CT_KEY_INTEGER, lib.CT_KEY_DEPTH,
                        lib.CT_KEY_COUNT, lib.CT_KEY_WORD, lib.CT_KEY_RANGE):
        raise invalid(f"{name or row.name}: {row.section}.{row.name} is not parsed alone")
    given = text(row, name or row.name, value)
    buf = ffi.new("char[]", int(row.c.offset) + 16)  # the row stores at its offset
    st = lib.ct_key_parse(row.c, given, buf)
    if st != lib.CT_OK:
        raise error(st, f"{where + ': ' if where else ''}{row.section}.{row.name} = "
                        f"{shown(given)}: {message()}")
    at = buf + int(row.c.offset)
    if row.type == lib.CT_KEY_NUMBER:
        return ffi.cast("double *", at)[0]
    if row.type in (lib.CT_KEY_INTEGER, lib.CT_KEY_DEPTH):
        return int(ffi.cast("long *", at)[0])
    if row.type == lib.CT_KEY_COUNT:
        return int(ffi.cast("uint64_t *", at)[0])
    if row.type == lib.CT_KEY_WORD:
        return int(ffi.cast("int *", at)[0])
    v = ffi.cast("double *", at)
    return v[0], v[1]


class RunKeys:
    """The keys of a run (ct_run_keys) at the library's defaults (ct_run_keys_defaults), set
    from keyword arguments through their rows; solver() is what the solver keys mean
    (ct_run_keys_solver), as the program's [solver] section. where names the call in the
    library's messages ("restitution()"), as a scene's file:line."""

    def __init__(self, where):
        self._k = ffi.gc(ffi.new("ct_run_keys *"), lib.ct_run_keys_clear)
        lib.ct_run_keys_defaults(self._k)
        self._given = {}
        self._where = where

    @property
    def values(self):
        """The ct_run_keys as parsed."""
        return self._k

    def set(self, key, value, name=None):
        """Parses value through the row "section.name" (given as the keyword argument name;
        Python's words of some rows translated, see WORDS)."""
        row = run_row(key)
        name = name or row.name
        self.set_text(key, text(row, name, own_words(key, row, name, value)))

    def set_text(self, key, given):
        """Parses the text given (bytes) through the row key."""
        row = run_row(key)
        st = lib.ct_key_parse(row.c, given, self._k)
        if st != lib.CT_OK:
            raise error(st, f"{self._where}: {key} = {shown(given)}: {message()}")
        self._given[key] = given

    def solver(self):
        """The impact options, the sweep's path, threads, on_error, depth_tolerance
        (ct_run_solver); the library's refusal of a tolerance no double precision meets named
        as the program names it."""
        out = ffi.new("ct_run_solver *")
        st = lib.ct_run_keys_solver(self._k, out)
        if st != lib.CT_OK:
            given = shown(self._given.get("solver.tolerance", b""))
            raise error(st, f"{self._where}: solver.tolerance = {given}: {message()}")
        return out
