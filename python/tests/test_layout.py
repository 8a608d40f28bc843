"""cffi in ABI mode trusts python/cantact/_ffi.py's struct declarations: every size and field
offset must be what the C compiler makes of include/cantact.h (python/tests/layout.c)."""
import re
import subprocess

from cantact._ffi import CDEF, ffi


def test_every_struct_matches_the_header(layout):
    out = subprocess.run([layout], check=True, capture_output=True, text=True).stdout
    c = dict(line.rsplit(" ", 1) for line in out.splitlines())
    structs = [n for n in re.findall(r"}\s*(ct_\w+);", CDEF) if ffi.typeof(n).kind == "struct"]
    assert structs, "no struct declared"
    for name in structs:
        assert name in c, f"{name}: missing from python/tests/layout.c"
        assert ffi.sizeof(name) == int(c[name]), f"{name}: size differs from cantact.h"
        for field, _ in ffi.typeof(name).fields:
            key = f"{name}.{field}"
            assert key in c, f"{key}: missing from python/tests/layout.c"
            assert ffi.offsetof(name, field) == int(c[key]), f"{key}: offset differs"
