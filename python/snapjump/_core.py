"""The implementation of the package snapjump (its API and documentation: __init__.py)."""
import csv
import json
import os
import re
import tempfile

from . import _snapjump

__version__ = _snapjump.__version__


class SnapjumpError(RuntimeError):
    """snapjump failed (a run that could not go on, a folder it could not write); the message
    says what and where. The base of every error the package raises itself."""


class InputError(SnapjumpError, ValueError):
    """Bad input (a case value, a unit, a file's content): a ValueError whose message names the
    value and where it was given, in the functions' words (net_weight, not --net-weight)."""


def _flag(key):
    # net_weight -> --net-weight; a dotted case key (shell.R) -> its flag's name (R).
    return "--" + key.split(".")[-1].replace("_", "-")


def _value(v):
    if isinstance(v, bool) or v is None:
        raise InputError(f"{v!r} is not a quantity; give a number (SI) or text with a unit")
    return v if isinstance(v, str) else repr(float(v))


# The command line's options that the functions take under another name.
_KEYWORDS = {"column": "columns", "unit": "units", "no-figure": "figure=None",
             "allow-implausible": "allow_implausible=True", "complete": "complete=True"}


def _python_words(message):
    """A command line's message in the functions' words: --net-weight -> net_weight."""
    import re
    return re.sub(r"(?<![\w-])--([A-Za-z][A-Za-z0-9-]*)",
                  lambda m: _KEYWORDS.get(m.group(1), m.group(1).replace("-", "_")), message)


def _call(args, progress=None):
    code, out, err = _snapjump.cli([str(a) for a in args], progress)
    if code == 0:
        return out
    message = "\n".join(line[len("error: "):] if line.startswith("error: ") else line
                        for line in err.strip().splitlines()
                        if line and not line.startswith("Run with --help")) or out.strip()
    raise (InputError if code == 2 else SnapjumpError)(_python_words(message))


def _existing(path, what):
    """path as text; FileNotFoundError naming `what` when nothing is there."""
    path = os.fspath(path)
    if not os.path.exists(path):
        raise FileNotFoundError(2, f"no such {what}", path)
    return path


def _toml_text(case):
    # A case given as a dict of tables, {"shell": {"R": "30 mm"}, "title": "..."}, as TOML text.
    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, (int, float)):
            return repr(v)
        return json.dumps(str(v))  # a TOML basic string: JSON's escapes are TOML's
    lines = [f"{k} = {value(v)}" for k, v in case.items() if not isinstance(v, dict)]
    for table, keys in case.items():
        if isinstance(keys, dict):
            lines.append(f"[{table}]")
            for k, v in keys.items():
                if table == "shell" and k == "mesh":  # relative to here, not to the temporary file
                    v = os.path.abspath(os.fspath(v))
                lines.append(f"{k} = {value(v)}")
    return "\n".join(lines) + "\n"


class _CaseFile:
    """The case as a file for the command line: a path as given, a dict written to a temporary
    file (removed afterwards)."""

    def __init__(self, case):
        self.case, self.tmp = case, None

    def __enter__(self):
        if self.case is None:
            return []
        if isinstance(self.case, dict):
            fd, self.tmp = tempfile.mkstemp(suffix=".toml", prefix="snapjump-case-")
            with os.fdopen(fd, "w") as f:
                f.write(_toml_text(self.case))
            return [self.tmp]
        return [os.fspath(self.case)]

    def __exit__(self, *exc):
        if self.tmp:
            os.remove(self.tmp)


def _check_case(case, values):
    """Every keyword a case key (InputError otherwise), and a case file that exists."""
    for name in values:
        _case_key(name)
    if case is not None and not isinstance(case, dict):
        _existing(case, "case file")


def _case_args(case_files, values):
    args = list(case_files)
    for key, v in values.items():
        args += [_flag(key), _value(v)]
    return args


def _keyword_keys():
    # keyword (R, net_weight, popper_mass) and dotted key (shell.R) -> the case's dotted key.
    out = {}
    for k in _snapjump.case_keys:
        out[k["flag"].replace("-", "_")] = k["key"]
        out[k["key"]] = k["key"]
    return out


def _case_key(keyword):
    keys = _keyword_keys()
    if keyword not in keys:
        names = ", ".join(k["flag"].replace("-", "_") for k in _snapjump.case_keys)
        raise InputError(f"unknown case value '{keyword}'; the case values are {names}")
    return keys[keyword]


def _case_text(case):
    # The case as (TOML text, its name in messages) for the module; None: the built-in default.
    if case is None:
        return None, "built-in default case"
    if isinstance(case, dict):
        return _toml_text(case), "the case given as a dict"
    path = os.fspath(case)
    _existing(path, "case file")
    with open(path) as f:
        return f.read(), path


def _predict_many(case, values, allow_implausible):
    import numpy as np
    fixed, names, arrays = [], [], []
    for name, v in values.items():
        key = _case_key(name)
        if np.ndim(v) == 0 and not isinstance(v, np.ndarray):
            fixed.append((key, _value(v), name))
            continue
        try:
            arrays.append(np.asarray(v, dtype=float))
        except (TypeError, ValueError):
            raise InputError(f"{name}: an array of designs takes numbers in SI, "
                             f"e.g. {name}=[0.001, 0.002]") from None
        names.append((key, name))
    shape = np.broadcast_shapes(*(a.shape for a in arrays))
    flat = [np.ascontiguousarray(np.broadcast_to(a, shape)).ravel() for a in arrays]
    text, source = _case_text(case)
    try:
        r = _snapjump.predict_many(text, source, fixed, [k for k, _ in names],
                                   [n for _, n in names], flat, list(shape), allow_implausible)
    except ValueError as e:
        raise InputError(str(e)) from None
    for q in r["quantities"].values():
        q["lower"], q["upper"] = q["lower"].reshape(shape), q["upper"].reshape(shape)
    r["case"] = {k: a.reshape(shape) for k, a in r["case"].items()}
    r["outcome"] = np.array(r["outcome"], dtype=str).reshape(shape)
    r["outcome_text"] = r["outcome"]
    r["beyond_range"] = np.array(r["beyond_range"], dtype=str).reshape(shape)
    r["units"] = "SI"
    return r


def predict(case=None, allow_implausible=False, **values):
    """The closed-form theory for a popper, or for a grid of designs at once.

    case: a case file (path), a dict of its tables ({"shell": {"R": "30 mm", "h": "2 mm"}, ...},
        the same keys and unit strings as the TOML files), or None (the paper's default popper,
        (R, h) = (30, 2.0) mm, net weight 0.48 N).
    allow_implausible: take values outside what a popper can plausibly be (README.md,
        "Plausible values") as they are.
    **values: case values on top of the case, by name (R, h, phi, E, nu, rho, net_weight,
        popper_mass, wire_stiffness, mu, container_volume, p0, alpha_n, beta_n, delta_p_j,
        delta_p_j_over_pc, ...) or dotted key ("shell.R"): text with a unit ("30 mm") or a
        number in SI (0.03 for 30 mm; phi in radians).

    Returns, for scalar values, the command line's `snapjump predict --format json` as a dict (SI):
    "case" (the case's values), "quantities" ({name: {"lower", "upper", "unit"}}: p_c, F_c,
    F_star, H, ...), "outcome" (the outcomes the theory allows, a list), "outcome_text",
    "beyond_range", "reverse_snap".

    Any value given as an array (or a list) of numbers in SI makes it a grid of designs: the
    arrays broadcast as numpy's do, and each number of the result becomes an array of their
    shape: "quantities" ({name: {"lower": array, "upper": array, "unit"}}), "case" ({key:
    array}, the case's numbers), "outcome" and "outcome_text" (arrays of the outcome's text:
    "Jump", "Jump or Snap", "unknown: ..."), "beyond_range" (array of text, "" inside the
    theory's range). Each design is checked as a case file is; an invalid one raises
    InputError naming its position. The grid is evaluated in C++ in one loop: 10^4 designs
    take about 0.4 s (the first call in a process adds about 0.6 s for the contact solver's
    constants), measured with

        PYTHONPATH=build/python /usr/bin/python3 -m timeit -s "import snapjump, numpy as np; \\
            snapjump.predict(h=0.002)" \\
            "snapjump.predict(h=np.linspace(1e-3, 3e-3, 100)[:, None], \\
                              net_weight=np.linspace(0.1, 1, 100))"

    Raises FileNotFoundError for a missing case file, InputError (a ValueError) for a bad
    value, naming it.
    """
    if any(not isinstance(v, str) and hasattr(v, "__len__") for v in values.values()):
        return _predict_many(case, values, allow_implausible)
    for name in values:
        _case_key(name)
    text_args = ["--allow-implausible"] if allow_implausible else []
    if case is not None and not isinstance(case, dict):
        _case_text(case)  # a missing file raises FileNotFoundError
    with _CaseFile(case) as files:
        return json.loads(_call(["predict", *_case_args(files, values), *text_args,
                                 "--format", "json"]))


def contact(nu=0.5):
    """The shell-plane contact solver's constants and the theory's prefactor bounds, as
    `snapjump contact --format json` (docs/contact-solver.md).

    nu: Poisson's ratio (dimensionless), in (-1, 0.5].

    Returns a dict: "N_plus", "N_minus", "n2" (the disk and ring branches' constants, rescaled
    units), "bounds" ({"alpha_r", "alpha_e", "alpha_F", "alpha_t": {"lower", "upper"}}, the
    prefactors' bounds at nu), and the checks of the solver.
    Raises InputError for nu outside its range."""
    return json.loads(_call(["contact", "--nu", repr(float(nu)), "--format", "json"]))


def _write_columns(columns, path):
    names = list(columns.keys())
    if "t" not in names or "F" not in names:
        raise InputError(f"the columns need t and F (the plate force); given: {', '.join(names)}")
    data = [list(columns[n]) for n in names]
    rows = len(data[0])
    if any(len(d) != rows for d in data):
        raise InputError("the columns have different lengths")
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(names)
        for i in range(rows):
            w.writerow([d[i] if isinstance(d[i], str) else repr(float(d[i])) for d in data])


def analyze(data, case=None, R=None, complete=False, force_offset=None, columns=None, units=None):
    """The characteristic quantities and the outcome of a time series (docs/analysis.md), as
    `snapjump analyze --format json`.

    data: a CSV file (any format the command line reads: separators, decimal commas, units in
        the headers), a dict of columns in SI, or a pandas DataFrame: t [s] and F [N] (the plate
        force) and any of z, r, w, e [m], delta_p [Pa], contact.
    case: a case file whose popper the record is of (R, net weight, masses for the theory).
    R: the shell's radius, text with a unit ("30 mm") or metres; needed for the onset w / R.
    complete: the record covers the whole experiment (its end is the landing).
    force_offset: added to F, e.g. "0.48 N" for a plate tared with the popper on it.
    columns: which header names a column, {"t": "Time (s)"}; units: the unit of a column whose
        header has none, {"F": "mN"}.

    Returns a dict (SI): "outcome" ("Jump", "Snap", "No snap", "Thrown" or "undetermined"),
    "quantities" ({key: {"value", "unit", "label", "source", "definition"}}: t_onset, F_star,
    t_star, H, ...), "warnings", "undetermined" (why, when it is).
    Raises FileNotFoundError for a missing file, InputError for a bad value or record."""
    args = ["analyze"]
    tmp = None
    if isinstance(data, (str, os.PathLike)):
        args.append(_existing(data, "record file"))
    else:
        if hasattr(data, "to_dict") and hasattr(data, "columns"):  # a pandas DataFrame
            data = {str(c): data[c].tolist() for c in data.columns}
        fd, tmp = tempfile.mkstemp(suffix=".csv", prefix="snapjump-")
        os.close(fd)
        args.append(tmp)
    try:
        if tmp:
            _write_columns(dict(data), tmp)
        if case is not None:
            args += ["--case", _existing(case, "case file")]
        if R is not None:
            args += ["--R", _value(R)]
        if force_offset is not None:
            args += ["--force-offset", _value(force_offset)]
        if complete:
            args.append("--complete")
        for k, v in (columns or {}).items():
            args += ["--column", f"{k}={v}"]
        for k, v in (units or {}).items():
            args += ["--unit", f"{k}={v}"]
        return json.loads(_call(args + ["--format", "json"]))
    finally:
        if tmp:
            os.remove(tmp)


def run(case=None, output=None, resolution=None, model=None, end_time=None, resume=None,
        progress=None, **values):
    """Simulates the popper in this process, as `snapjump run`, and returns its folder.

    case: a case file, a dict of its tables, or None (the paper's default popper), as predict().
    output: the folder to write (default: one named after the case, as the command line's).
    resolution: "coarse", "default" or "fine" (the mesh and grid presets).
    model: "3d" (the paper's MPM) or "axisymmetric" (finite elements, seconds to minutes).
    end_time: a cap on the simulated time after the release, text ("50 ms") or seconds; the run
        ends at the apex of the flight, at the latest there. With resume, a later cap continues
        a run that went to its own.
    resume: a run's folder to continue from its checkpoint (case and output then come from it).
    progress: called with each line the run prints (progress and results), e.g. print.
    **values: case values on top of the case, as predict()'s (R="30 mm", net_weight=0.48).

    Returns the run's folder (text): series.csv, summary.json, case.toml, figures; read it with
    read_run(). Ctrl-C stops the run with a checkpoint past the release (KeyboardInterrupt;
    continue with run(resume=folder)).
    Raises FileNotFoundError for a missing case file or folder, InputError for a bad value,
    SnapjumpError when the run fails."""
    if resume is not None:
        _check_case(None, values)
        _existing(resume, "run folder")
    else:
        _check_case(case, values)
    with _CaseFile(None if resume is not None else case) as files:
        if resume is not None:
            args = ["run", "--resume", os.fspath(resume)]
            if end_time is not None:
                args += ["--end-time", _value(end_time)]
        else:
            args = ["run", *_case_args(files, values)]
            if output is not None:
                args += ["--output", os.fspath(output)]
            if resolution is not None:
                args += ["--resolution", resolution]
            if model is not None:
                args += ["--model", model]
            if end_time is not None:
                args += ["--end-time", _value(end_time)]
        out = _call(args, progress)
    if resume is not None:
        return os.fspath(resume)
    m = re.search(r"^\s*output\s+(.+?)(?: \(that is .*\))?$", out, re.MULTILINE)
    if not m:
        raise SnapjumpError("snapjump run did not say where it wrote:\n" + out)
    return m.group(1).strip()


# The units of a run's series.csv (docs/popper.md, "Measurements").
_SERIES_UNITS = {"t": "s", "z": "m", "r": "m", "w": "m", "e": "m", "e_apex": "m", "F": "N",
                 "delta_p": "Pa", "vz": "m/s", "kinetic": "J", "elastic": "J",
                 "gravitational": "J", "contact": ""}


def _key_and_unit(header):
    """A column's header as (key, unit): "F_star_lo [N]" -> ("F_star_lower", "N"); a theory
    bound's _lo / _hi as predict's lower / upper."""
    import re
    m = re.fullmatch(r"(.*?) \[(.*)\]", header)
    key, unit = (m.group(1), m.group(2)) if m else (header, _SERIES_UNITS.get(header, ""))
    key = re.sub(r"_lo$", "_lower", re.sub(r"_hi$", "_upper", key))
    return key, unit


def _frame(columns):
    try:
        import pandas as pd
    except ImportError:
        return None
    return pd.DataFrame(columns)


def _table(path):
    """A CSV table as ({key: numpy array} (text columns stay lists), {key: unit})."""
    import csv
    import numpy as np
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    if not rows:
        raise InputError(f"{path}: the table is empty")
    header, body = rows[0], rows[1:]
    out, units = {}, {}
    for k, name in enumerate(header):
        key, units[key] = _key_and_unit(name)
        cells = [r[k] if k < len(r) else "" for r in body]
        try:
            out[key] = np.array([float(c) if c != "" else np.nan for c in cells])
        except ValueError:
            out[key] = cells
    return out, units


def _run_values(summary):
    """A run's summary as one row of a sweep's table: ({key: value}, {key: unit})."""
    values, units = {}, {}
    measured = summary.get("measured") or {}
    theory = summary.get("theory") or {}
    values["status"], units["status"] = summary.get("status", ""), ""
    values["outcome"], units["outcome"] = measured.get("outcome", ""), ""
    values["predicted_outcome"], units["predicted_outcome"] = theory.get("outcome_text", ""), ""
    case_units = {k["flag"].replace("-", "_"): k["unit"] for k in _snapjump.case_keys}
    case_units.update(counterweight="kg", moving_mass="kg")
    for key, v in (summary.get("case") or {}).items():
        if isinstance(v, (int, float)) and not isinstance(v, bool):
            values[key], units[key] = float(v), case_units.get(key, "")
    for key, q in (theory.get("quantities") or {}).items():
        for end in ("lower", "upper"):
            v = q.get(end)
            values[f"{key}_{end}"] = float("nan") if v is None else float(v)
            units[f"{key}_{end}"] = q.get("unit", "")
    for key, q in (measured.get("quantities") or {}).items():
        v = q.get("value")
        values[key] = float("nan") if v is None else float(v)
        units[key] = q.get("unit", "")
    if "wall_time" in summary:
        values["wall_time"], units["wall_time"] = float(summary["wall_time"]), "s"
    return values, units


def read_run(folder):
    """A simulated run's folder (written by run()), as arrays and numbers in SI.

    folder: the run's folder (series.csv, summary.json, case.toml).

    Returns a dict:
      "series": {column: numpy array} of the time series (t [s], z, r, w, e, e_apex [m], F [N],
          delta_p [Pa], vz [m/s], kinetic, elastic, gravitational [J]; contact as a list of
          text: none / ring / disk);
      "values": the run as one row of a sweep's table (read_sweep), {key: number or text}:
          status, outcome (measured), predicted_outcome, the case's values (R, h, E,
          net_weight, ...), the measured quantities (F_star, t_star, H, alpha_F, ...), the
          theory's bounds as KEY_lower and KEY_upper (F_star_lower, ...), wall_time;
      "units": {key: SI unit} for the series' columns and the values ("1" or "" when none);
      "summary": summary.json as a dict; "case": case.toml's text (None without one);
      "frame": the series as a pandas DataFrame, or None when pandas is not installed.

    Raises FileNotFoundError for a folder that is not there or holds no series.csv.
    """
    import json
    folder = _existing(folder, "run folder")
    series_path = os.path.join(folder, "series.csv")
    if not os.path.isfile(series_path):
        raise FileNotFoundError(2, "not a snapjump run folder (no series.csv)", series_path)
    series, units = _table(series_path)
    summary_path = _existing(os.path.join(folder, "summary.json"), "run summary")
    with open(summary_path) as f:
        summary = json.load(f)
    values, value_units = _run_values(summary)
    case_path = os.path.join(folder, "case.toml")
    case_text = None
    if os.path.isfile(case_path):
        with open(case_path) as f:
            case_text = f.read()
    return {"series": series, "values": values, "units": {**units, **value_units},
            "summary": summary, "case": case_text, "frame": _frame(series)}


def read_sweep(folder):
    """A sweep's table (snapjump sweep's sweep.csv), one row a run, as arrays in SI.

    folder: the sweep's folder, or its sweep.csv.

    Returns a dict:
      "table": {key: numpy array} (text columns as lists), with the keys of read_run's
          "values": run, status, outcome, predicted_outcome, the swept keys as given
          (friction.mu), the case's values (R, h, ...), the measured quantities (F_star, ...),
          the theory's bounds as KEY_lower / KEY_upper, wall_time, undetermined, error; the
          unit that sweep.csv writes in a header ("F_star [N]") is not part of the key;
      "units": {key: SI unit};
      "frame": the table as a pandas DataFrame, or None when pandas is not installed.

    Raises FileNotFoundError for a folder that is not there or holds no sweep.csv.
    """
    folder = _existing(folder, "sweep folder")
    path = folder if folder.endswith(".csv") else os.path.join(folder, "sweep.csv")
    if not os.path.isfile(path):
        raise FileNotFoundError(2, "no sweep table (a sweep's folder holds sweep.csv)", path)
    table, units = _table(path)
    return {"table": table, "units": units, "frame": _frame(table)}


def compare(records, run_dir, columns=None, units=None, force_offset=None, settle_time=None,
            complete=False, force_resolution=None, ring_width=None, length_resolution=None,
            figure=None):
    """Measured records beside a simulated run and the theory's bounds, as `snapjump compare
    RECORD... RUN_DIR --format json` (docs/analysis.md, "A record beside a run").

    records: a record's CSV file (any format analyze() reads) or a list of them; several give
        their mean and spread.
    run_dir: the run's folder (written by run(): series.csv, case.toml).
    columns, units: which header names a record's column ({"t": "Time (s)"}) and the unit of a
        column whose header has none ({"F": "mN"}), as in analyze().
    force_offset: added to the records' F, e.g. "0.48 N" for a plate tared with the popper on it.
    settle_time: how long a record must go on after its force peak to call it Snap ("50 ms").
    complete: the records cover the whole experiment.
    force_resolution: the plate's resolution, the records' uncertainty of F (default 12 mN).
    ring_width: the contact ring's width the camera sees, the uncertainty of r* (r* is not
        judged without it).
    length_resolution: the lasers' resolution, the uncertainty of z, w and e.
    figure: where to draw the overlay figure (.png or .svg); None draws none.
    Values with a unit are text ("12 mN"); bare numbers are SI.

    Returns the command's JSON as a dict (SI): "quantities" ({key: {"record", "run", "lower",
    "upper", "difference", "uncertainty", "within", "in_bounds", "n", "values", "spread",
    "unit", ...}}), "outcomes" ({"records": [...], "run": ..., "theory": ...}), "records",
    "notes", "units"; and "frame": the quantities as a pandas DataFrame (one row a quantity),
    or None when pandas is not installed (the dict holds the same numbers).

    Raises FileNotFoundError for a missing record or run folder, InputError for a bad value.
    """
    import json
    if isinstance(records, (str, os.PathLike)):
        records = [records]
    args = ["compare", *(_existing(r, "record file") for r in records),
            _existing(run_dir, "run folder")]
    for name, v in (("--force-offset", force_offset), ("--settle-time", settle_time),
                    ("--force-resolution", force_resolution), ("--ring-width", ring_width),
                    ("--length-resolution", length_resolution)):
        if v is not None:
            args += [name, _value(v)]
    if complete:
        args.append("--complete")
    for k, v in (columns or {}).items():
        args += ["--column", f"{k}={v}"]
    for k, v in (units or {}).items():
        args += ["--unit", f"{k}={v}"]
    args += ["--figure", os.fspath(figure)] if figure is not None else ["--no-figure"]
    result = json.loads(_call(args + ["--format", "json"]))
    quantities = result.get("quantities", {})
    try:
        import pandas as pd
    except ImportError:
        result["frame"] = None
    else:
        result["frame"] = pd.DataFrame.from_dict(quantities, orient="index")
    return result


def design(jump_height=None, peak_force=None, margin=None, t_star_max=None, footprint=None,
           min_h=None, max_h_over_R=None, max_suction=None, net_weight_max=None,
           rank="smallest", count=5, grid=None, branch=True, verify=None, model=None,
           resolution=None, output=None, jobs=None, case=None, **values):
    """The spherical caps that meet targets for a jump by the theory's lower bounds, as
    `snapjump design ... --format json` (docs/design.md).

    Targets (text with a unit or SI numbers): jump_height H at least a value ("50 mm") or
    within a range ("40 mm..60 mm"); peak_force F* likewise ("2 N"); margin F* / mg at least
    this (default 1); t_star_max t* at most this ("40 ms").
    Constraints: footprint, the rim's diameter 2 R sin(phi) at most (default "100 mm"); min_h,
    the thinnest wall ("0.5 mm"); max_h_over_R, the thickest shell (0.1); max_suction, the
    pump's suction ("20 kPa"); net_weight_max: search the net weight from the case's up to this.
    rank: "smallest" (footprint), "lightest" (shell), "margin" (F* / mg) or "highest" (H);
    count designs (5); grid points per searched dimension (120); branch=False skips each
    design's reverse snap.
    verify: simulate the N best (a sweep in `output`, default "runs/design"), with model
    ("axisymmetric" or "3d"), resolution ("coarse", "default", "fine") and jobs.
    case: a case file or a dict of tables for the material, phi, the protocol and the apparatus;
    values: case keys as in predict() (E="1.2 MPa", net_weight="1 N").

    Returns a dict (SI): "designs" (each with "R", "h", "net_weight", "footprint", "shell_mass",
    "zoelly_pc", "H", "F_star", "t_star", "jump_margin" as {"lower", "upper"}, "outcome",
    "reverse_snap"), "pareto" (footprint against H's lower bound), "rank", "evaluated".
    With verify, the simulation's report is printed and its runs are in output (read_sweep()).

    Raises InputError when no design meets the targets (the message names what binds and by
    how much) or for a bad value.
    """
    import json
    _check_case(case, values)
    with _CaseFile(case) as files:
        args = ["design", *_case_args(files, values)]
        for name, v in (("--jump-height", jump_height), ("--peak-force", peak_force),
                        ("--t-star-max", t_star_max), ("--footprint", footprint),
                        ("--min-h", min_h), ("--max-suction", max_suction),
                        ("--net-weight-max", net_weight_max)):
            if v is not None:
                args += [name, _value(v)]
        for name, v in (("--margin", margin), ("--max-h-over-R", max_h_over_R),
                        ("--grid", grid), ("--jobs", jobs)):
            if v is not None:
                args += [name, str(v)]
        args += ["--rank", rank, "--count", str(int(count)), "--format", "json"]
        if not branch:
            args.append("--no-branch")
        if verify is not None:
            args += ["--verify", str(int(verify))]
            for name, v in (("--model", model), ("--resolution", resolution),
                            ("--output", output)):
                if v is not None:
                    args += [name, os.fspath(v)]
        out = _call(args)
    # The designs' JSON first; with verify, the simulation's report after it.
    result, end = json.JSONDecoder().raw_decode(out)
    if out[end:].strip():
        print(out[end:].strip())
    return result
