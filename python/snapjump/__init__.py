"""snapjump from Python: the theory, the contact solver, the analysis and the simulator of
this repository (README.md, "Python"), with the case keys and units of the case files.

    import snapjump, numpy as np
    p = snapjump.predict(R="30 mm", h="2 mm", net_weight="0.48 N")     # a dict, SI units
    g = snapjump.predict(h=np.linspace(1e-3, 3e-3, 50)[:, None],       # a grid of designs:
                         net_weight=np.linspace(0.1, 1.0, 40))          # arrays (50, 40)
    c = snapjump.contact(nu=0.45)
    a = snapjump.analyze("record.csv", R="30 mm")                     # or columns / a DataFrame
    d = snapjump.run(model="axisymmetric", resolution="coarse", progress=print)
    r = snapjump.read_run(d)                                          # numpy arrays (+ pandas)
    k = snapjump.compare("record.csv", d)                             # record beside the run
    s = snapjump.design(jump_height="50 mm", net_weight="1 N")        # shells for a target

Numbers are SI; text takes a unit ("30 mm"). A missing file raises FileNotFoundError, a bad
value snapjump.InputError (a ValueError) naming it, any other failure snapjump.SnapjumpError.
Ctrl-C stops a run as the command line's --pause-at does: run(resume=folder) continues it.
"""
from ._core import (InputError, SnapjumpError, __version__, analyze, compare, contact, design,
                    predict, read_run, read_sweep, run)

__all__ = ["predict", "contact", "analyze", "compare", "design", "run", "read_run", "read_sweep",
           "SnapjumpError", "InputError"]

for _name in __all__:
    globals()[_name].__module__ = __name__  # snapjump.predict, as help() and tracebacks say
del _name, _core, _snapjump  # the private modules stay in sys.modules, out of the namespace
