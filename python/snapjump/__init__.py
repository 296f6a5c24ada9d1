"""snapjump from Python: the theory, the contact solver, the analysis and the simulator of
this repository (README.md, "Python"), with the same case keys, units and error messages as the
command line.

    import snapjump
    p = snapjump.predict(R="30 mm", h="2 mm", net_weight="0.48 N")   # a dict, SI units
    c = snapjump.contact(nu=0.45)
    a = snapjump.analyze("record.csv", R="30 mm")                   # or columns / a DataFrame
    d = snapjump.run(model="axisymmetric", resolution="coarse", progress=print)
    r = snapjump.read_run(d)                                        # numpy arrays (+ pandas)

Errors raise snapjump.SnapjumpError (bad input: snapjump.InputError) with the command line's
message. Ctrl-C stops a run as --pause-at does: it can be resumed with run(resume=folder).
"""
from ._core import (InputError, SnapjumpError, __version__, analyze, compare, contact, predict,
                    read_run, read_sweep, run)

__all__ = ["predict", "contact", "analyze", "compare", "run", "read_run", "read_sweep",
           "SnapjumpError", "InputError"]

for _name in __all__:
    globals()[_name].__module__ = __name__  # snapjump.predict, as help() and tracebacks say
del _name, _core, _snapjump  # the private modules stay in sys.modules, out of the namespace
