"""Bodies: what strikes the rods (docs/model.md §14), a ct_body set up by the library's rows.

A body is one kind of the library's registry of bodies (ct_body_name: flat, cylinder, sphere)
with its keys, the rows of section body of ct_body_keys_table (radius, position), each given as
text to ct_key_parse, which stores it in the ct_body or refuses it in its own words, as the
program reads a scene's [body] section. The module holds no key, range, default or message of
a body: Flat, Cylinder and Sphere are Body("flat"), Body("cylinder", ...) and Body("sphere",
...). The table's one row of section surface, surface.periodic, belongs to the surface
(Surface(..., periodic=True), the program's [surface] periodic = true); a build joins the two
into the ct_body of its ct_build_request (request()). Whether a surface can carry the body (a
sphere needs an areal surface, a cylinder a line, a Cantor surface one rod per piece), where
the apex lands, and what the face reaches, the library's build says (ct_surface_build)."""
from . import _check as chk
from . import _keys
from ._errors import error, invalid
from ._ffi import ffi, lib

_ROWS = {f"{r.section}.{r.name}": r for r in _keys.BODY_ROWS}
# The rows a body takes (section body, but for shape, which names the body) and the rows that
# belong to the surface (section surface: periodic), each by its name and "section.name".
_BODY = {k: r for r in _keys.BODY_ROWS if r.section == "body" and r.name != "shape"
         for k in (r.name, f"{r.section}.{r.name}")}
_NAMES = tuple(r.name for r in _keys.BODY_ROWS if r.section == "body" and r.name != "shape")
SURFACE_ROWS = {k: r for r in _keys.BODY_ROWS if r.section == "surface"
                for k in (r.name, f"{r.section}.{r.name}")}


def parse(body, row, value, name, where):
    """value, given as the keyword argument name, parsed through the row into the ct_body
    body (Python's words of the row made its own: periodic=True is "true"); refused in the
    library's words, "where: section.name = value: reason"."""
    key = f"{row.section}.{row.name}"
    given = _keys.text(row, name, _keys.own_words(key, row, name, value))
    st = lib.ct_key_parse(row.c, given, body)
    if st != lib.CT_OK:
        raise error(st, f"{where}: {key} = {_keys.shown(given)}: {_keys.message()}")


def defaults():
    """A ct_body at the library's defaults (ct_body_defaults: the flat strip)."""
    b = ffi.new("ct_body *")
    lib.ct_body_defaults(b)
    return b


class Body:
    """What strikes the rods: Body(shape, **keys), shape one of cantact.BODIES (flat,
    cylinder, sphere: the library's registry of bodies), every keyword a row of the body
    (cantact.BODY_ROWS of section body: radius, position; "body.radius" names one too), set as
    the program sets [body] shape and its keys from a scene: the same values accepted, the
    same refused with the same words. radius: R of a cylinder or sphere, in the surface's
    length unit (metres for profiles and maps, the rods' unit, l0's unit for a Cantor
    surface); position: where the apex lands, x (a number) on a line, (x, y) on a plane, in
    the same unit (not given: the middle of the surface). Pass it as body= to restitution,
    table, load_curve or ensemble. Whether the surface repeats under it is the surface's
    periodic (surface.periodic)."""

    def __init__(self, shape, **keys):
        self._setup(shape, keys, "Body()")

    def _setup(self, shape, keys, where):
        b = defaults()
        parse(b, _ROWS["body.shape"], shape, "shape", where)
        for key, value in keys.items():
            if key not in _BODY:
                own = SURFACE_ROWS.get(key)
                if own is not None:
                    raise invalid(f"{where}: {key}: surface.{own.name} is the surface's key: "
                                  f"give {own.name}= to the surface")
                raise invalid(f"{where}: {chk._text(key)}: not a key of a body (its keys: "
                              f"{', '.join(_NAMES)})")
        for r in _keys.BODY_ROWS:  # in the table's order, as a scene's keys
            for key in (r.name, f"{r.section}.{r.name}"):
                if key in keys and _BODY.get(key) is r:
                    parse(b, r, keys[key], key, where)
        self._body = b
        self._keys = {k: v for k, v in keys.items()}

    @property
    def shape(self):
        """The body's name in the library's registry ("flat", "cylinder", "sphere")."""
        return _keys._text_of(lib.ct_body_name(self._body.shape))

    @property
    def radius(self):
        """R as parsed (0 for the flat strip, which has none)."""
        return float(self._body.radius)

    @property
    def position(self):
        """The apex as given: None (the middle of the surface), (x,) or (x, y)."""
        x, y = self._body.position[0], self._body.position[1]
        if x != x:
            return None
        return (x,) if y != y else (x, y)

    def __str__(self):
        """The library's words (ct_body_describe), "" for the flat strip."""
        buf = ffi.new("char[]", 256)
        lib.ct_body_describe(self._body, buf, 256)
        return ffi.string(buf).decode(errors="replace")

    def __repr__(self):
        keys = ", ".join(f"{k}={v!r}" for k, v in self._keys.items())
        return f"Body({self.shape!r}{', ' if keys else ''}{keys})"


class Flat(Body):
    """The paper's flat strip, Body("flat"): the rods as built, bit for bit."""

    def __init__(self):
        self._setup("flat", {}, "Flat()")

    def __repr__(self):
        return "Flat()"


class Cylinder(Body):
    """A rigid cylinder, its axis across a line surface (per unit depth, like the strip),
    Body("cylinder", radius=R, position=x): a line profile, a Cantor or random Cantor surface
    with representation = "segments" (one rod per piece), or Rods placed by x."""

    def __init__(self, radius, position=None):
        keys = {"radius": radius}
        if position is not None:
            keys["position"] = position
        self._setup("cylinder", keys, "Cylinder()")

    def __repr__(self):
        at = "" if self.position is None else f", position={self._keys['position']!r}"
        return f"Cylinder({self._keys['radius']!r}{at})"


class Sphere(Body):
    """A rigid sphere over an areal surface, Body("sphere", radius=R, position=(x, y)): an
    X3P map, or Rods placed by x and y."""

    def __init__(self, radius, position=None):
        keys = {"radius": radius}
        if position is not None:
            keys["position"] = position
        self._setup("sphere", keys, "Sphere()")

    def __repr__(self):
        at = "" if self.position is None else f", position={self._keys['position']!r}"
        return f"Sphere({self._keys['radius']!r}{at})"


def body_of(name, value):
    """value, checked to be a body (None: the surface's default, the flat strip)."""
    if value is not None and not isinstance(value, Body):
        raise invalid(f"{name}: must be a cantact body (Flat, Cylinder, Sphere or Body) or "
                      f"None, got {type(value).__name__}")
    return value


def request(body, surface_body):
    """The ct_body of a build: the body's shape, radius and position (None: the flat strip)
    with the surface's periodic (surface_body: the ct_body its periodic was parsed into)."""
    b = ffi.new("ct_body *", (body._body if body is not None else defaults())[0])
    b.periodic = surface_body.periodic
    return b


def is_default(body):
    """True for no body or a body of the library's default shape (ct_body_defaults: the flat
    strip), which leaves the rods as built (docs/model.md §14)."""
    return body is None or body._body.shape == defaults().shape
