# Loads libcantact_lammps.so into the LAMMPS that runs the input script and registers the pair
# style gran/hooke/history/cantact in it. In the input script (stock Debian lmp, PYTHON package):
#
#   python cantact_load input 2 SELF /path/to/libcantact_lammps.so format ps file /path/to/cantact_load.py
#   python cantact_load invoke
#   pair_style gran/hooke/history/cantact ...
#
# SELF passes the LAMMPS instance's address (a PyCapsule); cantact_lammps_register adds the style's creator to
# that instance's Force::pair_map. The library stays loaded (ctypes never unloads it), as the
# pair style's code must outlive the run.
import ctypes

_loaded = {}


def _address(lmpptr):
    """The LAMMPS pointer that the python command's SELF passes: a PyCapsule (as LAMMPS's own
    lammps(ptr=...) reads it), or an int."""
    if isinstance(lmpptr, int):
        return lmpptr
    get = ctypes.pythonapi.PyCapsule_GetPointer
    get.restype = ctypes.c_void_p
    get.argtypes = [ctypes.py_object, ctypes.c_char_p]
    return get(lmpptr, None)


def cantact_load(lmpptr, path):
    lib = _loaded.get(path)
    if lib is None:
        lib = ctypes.CDLL(path)
        lib.cantact_lammps_register.restype = ctypes.c_int
        lib.cantact_lammps_register.argtypes = [ctypes.c_void_p]
        _loaded[path] = lib
    if lib.cantact_lammps_register(ctypes.c_void_p(_address(lmpptr))) != 0:
        raise RuntimeError("cantact_lammps_register failed: gran/hooke/history/cantact is "
                           "taken by another style")
