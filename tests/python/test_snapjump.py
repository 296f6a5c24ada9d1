"""The Python package against the command line and against closed forms: the same numbers, the
same error messages, arrays out of a run. Run by `make test` (ctest PythonPackage)."""
import math
import os

import numpy as np
import pytest

import snapjump

SOURCE = os.environ.get("SNAPJUMP_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))


def test_predict_is_the_command_lines_json():
    p = snapjump.predict(R="30 mm", h="2 mm", net_weight="0.48 N")
    assert p["case"]["R"] == pytest.approx(0.03)
    # Zoelly's pressure of the complete sphere, 2 E (h/R)^2 / sqrt(3 (1 - nu^2)), nu = 0.45.
    E, h, R, nu = 1.2e6, 2e-3, 30e-3, 0.45
    p_c = 2 * E * (h / R) ** 2 / math.sqrt(3 * (1 - nu * nu))
    assert p["quantities"]["p_c"]["lower"] == pytest.approx(p_c, rel=1e-12)
    # F_c = E h^3 / R
    assert p["quantities"]["F_c"]["lower"] == pytest.approx(E * h ** 3 / R, rel=1e-12)
    # Bare numbers are SI; the same popper gives the same numbers.
    q = snapjump.predict(R=0.03, h=0.002, net_weight=0.48)
    assert q["quantities"] == p["quantities"]
    # A case as a dict of tables, with the TOML files' keys and unit strings.
    d = snapjump.predict({"title": "mine", "shell": {"R": "30 mm", "h": "2 mm"},
                          "material": {"E": "1.2 MPa"}, "popper": {"net_weight": "0.48 N"}})
    assert d["quantities"] == p["quantities"] and d["case"]["title"] == "mine"
    with pytest.raises(snapjump.InputError, match="unknown key 'Rr'"):
        snapjump.predict({"shell": {"Rr": "30 mm"}})
    # A case file and a value on top of it, as on the command line.
    r = snapjump.predict(os.path.join(SOURCE, "examples", "R30_h1.5.toml"), mu=0.6)
    assert r["case"]["h"] == pytest.approx(1.5e-3) and r["case"]["mu"] == pytest.approx(0.6)


def test_errors_carry_the_command_lines_message():
    with pytest.raises(snapjump.InputError, match=r"a length"):
        snapjump.predict(R="30 N")
    with pytest.raises(snapjump.InputError, match=r"unknown case value .zzz.; the case values are R, h"):
        snapjump.predict(zzz=1)
    with pytest.raises(snapjump.InputError):
        snapjump.contact(nu=0.7)


def test_contact_bounds():
    c = snapjump.contact(nu=0.5)
    assert c["N_plus"]["N"] == pytest.approx(76.94, rel=2e-3)  # the paper's N+
    lo, hi = c["bounds"]["alpha_F"]["lower"], c["bounds"]["alpha_F"]["upper"]
    assert 0 < lo < hi


def _jump_columns():
    # The analysis tests' reference jump (tests/measure/test_analysis.cpp): onset at 20.05 ms,
    # F* = 2 N at 22 ms, launch at 25.92 ms.
    t = np.arange(0, 1501) * 1e-4
    c = (5e-3 - 0.9e-3) / 20.05e-3
    w = np.maximum(5e-3 - c * t, 0.0)
    F = np.where(t < 21e-3, 0.5,
                 np.where(t < 22e-3, 0.5 + 1.5 * (t - 21e-3) / 1e-3,
                          np.where(t < 26e-3, 2.0 * (1 - (t - 22e-3) / 4e-3), 0.0)))
    return {"t": t, "F": F, "w": w}


def test_analyze_columns_a_dataframe_and_a_file(tmp_path):
    cols = _jump_columns()
    a = snapjump.analyze(cols, R="30 mm", complete=True)
    assert a["outcome"] == "Jump"
    q = a["quantities"]
    assert q["t_onset"]["value"] == pytest.approx(20.05e-3, abs=1e-9)
    assert q["F_star"]["value"] == pytest.approx(2.0, rel=1e-9)
    assert q["t_launch"]["value"] == pytest.approx(25.92e-3, abs=1e-8)
    path = tmp_path / "r.csv"
    with open(path, "w") as f:
        f.write("Time (s);Fz (N);w (mm)\n")
        for i in range(len(cols["t"])):
            f.write(f"{cols['t'][i]:.6f};{cols['F'][i]:.6f};{1e3 * cols['w'][i]:.6f}\n")
    b = snapjump.analyze(path, R=0.03)
    assert b["outcome"] == "Jump"
    assert b["quantities"]["F_star"]["value"] == pytest.approx(2.0, rel=1e-6)
    try:
        import pandas as pd
    except ImportError:
        return
    d = snapjump.analyze(pd.DataFrame(cols), R="30 mm")
    assert d["quantities"]["F_star"]["value"] == pytest.approx(2.0, rel=1e-9)


def test_analyze_refuses_columns_without_force():
    with pytest.raises(snapjump.InputError, match="t and F"):
        snapjump.analyze({"t": [0, 1]})


def test_a_short_run_in_process_with_progress_and_arrays(tmp_path):
    lines = []
    folder = snapjump.run(model="axisymmetric", resolution="coarse", end_time="5 ms",
                          output=tmp_path / "run", progress=lines.append)
    assert os.path.samefile(folder, tmp_path / "run")
    r = snapjump.read_run(folder)
    t = r["series"]["t"]
    assert isinstance(t, np.ndarray) and t[0] == 0.0 and t[-1] == pytest.approx(5e-3, abs=2e-4)
    assert np.all(np.diff(t) > 0)
    assert r["summary"]["status"].startswith("capped at 0.005 s")
    assert any(line.strip().startswith("prepared") for line in lines)
    assert r["units"]["t"] == "s" and r["values"]["R"] == pytest.approx(0.03)
    assert r["units"]["F_star_lower"] == "N" and r["values"]["F_star_lower"] > 0
    with pytest.raises(FileNotFoundError, match="not a snapjump run folder"):
        snapjump.read_run(tmp_path)


def test_a_failing_progress_callback_stops_the_run(tmp_path):
    def boom(line):
        raise RuntimeError("stop here")
    with pytest.raises(RuntimeError, match="stop here"):
        snapjump.run(model="axisymmetric", resolution="coarse", end_time="50 ms",
                     output=tmp_path / "run", progress=boom)


def test_read_sweep(tmp_path):
    path = tmp_path / "sweep.csv"
    path.write_text("run,status,outcome,alpha_F [1]\nrun-0000,completed,Jump,5.5\n"
                    "run-0001,failed,,\n")
    s = snapjump.read_sweep(tmp_path)
    assert s["table"]["outcome"] == ["Jump", ""]
    assert s["table"]["alpha_F"][0] == 5.5 and math.isnan(s["table"]["alpha_F"][1])
    assert s["units"]["alpha_F"] == "1"


def test_ctrl_c_stops_a_run_that_can_be_resumed(tmp_path):
    import signal

    def interrupt_once_prepared(line):
        if line.strip().startswith("prepared"):
            os.kill(os.getpid(), signal.SIGINT)  # as Ctrl-C would

    folder = tmp_path / "run"
    with pytest.raises(KeyboardInterrupt):
        snapjump.run(model="axisymmetric", resolution="coarse", end_time="40 ms", output=folder,
                     progress=interrupt_once_prepared)
    summary = snapjump.read_run(folder)["summary"]
    assert summary["status"].startswith("interrupted")
    snapjump.run(resume=folder)
    r = snapjump.read_run(folder)
    assert r["summary"]["status"].startswith("capped at 0.04 s")
    assert r["series"]["t"][-1] == pytest.approx(40e-3, abs=2e-4)
    snapjump.run(resume=folder, end_time="50 ms")  # a later cap continues it
    r = snapjump.read_run(folder)
    assert r["summary"]["status"].startswith("capped at 0.05 s")
    assert r["series"]["t"][-1] == pytest.approx(50e-3, abs=2e-4)


def test_predict_over_a_grid_of_designs():
    h = np.linspace(1e-3, 3e-3, 5)[:, None]
    mg = np.array([0.1, 0.48, 2.0, 20.0])
    g = snapjump.predict(h=h, net_weight=mg, R="30 mm")
    q = g["quantities"]
    assert q["p_c"]["lower"].shape == (5, 4) and g["outcome"].shape == (5, 4)
    E, R, nu = 1.2e6, 30e-3, 0.45
    hh, mm = np.broadcast_arrays(h, mg)
    np.testing.assert_allclose(q["p_c"]["lower"], 2 * E * (hh / R) ** 2 / np.sqrt(3 * (1 - nu * nu)),
                               rtol=1e-12)
    np.testing.assert_allclose(q["F_c"]["upper"], E * hh ** 3 / R, rtol=1e-12)
    np.testing.assert_allclose(g["case"]["net_weight"], mm, rtol=0)
    np.testing.assert_allclose(q["jump_margin"]["lower"], q["F_star"]["lower"] / mm, rtol=1e-12)
    # Each design is the scalar prediction of the same popper.
    for i, j in [(0, 0), (2, 1), (4, 3)]:
        p = snapjump.predict(h=float(hh[i, j]), net_weight=float(mm[i, j]), R="30 mm")
        assert g["outcome"][i, j] == p["outcome_text"]
        for key in ("F_star", "H", "t_star", "delta_p_j"):
            assert q[key]["lower"][i, j] == pytest.approx(p["quantities"][key]["lower"], rel=1e-12)
            assert q[key]["upper"][i, j] == pytest.approx(p["quantities"][key]["upper"], rel=1e-12)
    # A heavy popper does not jump: F* / mg below 1 at both bounds.
    assert "Jump" not in g["outcome"][0, 3]
    # Lists broadcast too, on a case given as a dict; a grid of 10^4 designs in one call.
    big = snapjump.predict({"shell": {"R": "30 mm", "h": "2 mm"}, "material": {"E": "1.2 MPa"},
                            "popper": {"net_weight": "0.48 N"}},
                           h=np.linspace(1e-3, 3e-3, 100)[:, None], mu=[0.1, 0.3],
                           net_weight=np.linspace(0.1, 1.0, 100)[:, None, None])
    assert big["quantities"]["F_star"]["lower"].shape == (100, 100, 2)
    assert np.all(np.isfinite(big["quantities"]["F_star"]["lower"]))
    np.testing.assert_array_equal(big["case"]["mu"][3, 7], [0.1, 0.3])


def test_a_grid_names_the_design_it_refuses():
    with pytest.raises(snapjump.InputError, match=r"design \[1\]: h\[1\].*smaller than shell.R"):
        snapjump.predict(h=[1e-3, 0.05])
    with pytest.raises(ValueError, match="takes numbers in SI"):
        snapjump.predict(h=["1 mm", "2 mm"])
    with pytest.raises(snapjump.InputError, match="plausibly"):
        snapjump.predict(R=[0.03, 3.0])
    p = snapjump.predict(R=[0.03, 3.0], h=[0.002, 0.2], allow_implausible=True)
    assert p["quantities"]["r_c"]["lower"][1] == pytest.approx(math.sqrt(3.0 * 0.2))


def test_version_is_the_projects():
    import re
    with open(os.path.join(SOURCE, "CMakeLists.txt")) as f:
        version = re.search(r"project\(snapjump VERSION ([0-9.]+)", f.read()).group(1)
    assert snapjump.__version__ == version


def test_the_namespace_is_the_api():
    dunders = {n for n in dir(snapjump) if n.startswith("__") and n.endswith("__")}
    assert set(dir(snapjump)) - dunders == set(snapjump.__all__)
    for name in ("csv", "json", "os", "re", "tempfile", "np"):
        assert not hasattr(snapjump, name)
    assert snapjump.predict.__module__ == "snapjump"


def test_missing_files_and_bad_values_in_pythons_words(tmp_path):
    missing = tmp_path / "nowhere.toml"
    for call in (lambda: snapjump.predict(missing), lambda: snapjump.run(missing),
                 lambda: snapjump.analyze(tmp_path / "nowhere.csv"),
                 lambda: snapjump.read_run(tmp_path / "nowhere"),
                 lambda: snapjump.read_sweep(tmp_path / "nowhere"),
                 lambda: snapjump.run(resume=tmp_path / "nowhere")):
        with pytest.raises(FileNotFoundError, match="nowhere"):
            call()
    with pytest.raises(FileNotFoundError, match="series.csv"):
        snapjump.read_run(tmp_path)
    for call, words in ((lambda: snapjump.predict(net_weight="0.5 m"), "net_weight"),
                        (lambda: snapjump.predict(R="30 N"), "R: shell.R"),
                        (lambda: snapjump.predict(R="3 m"), "allow_implausible=True"),
                        (lambda: snapjump.predict(popper_mass="1 g"), "popper.mass"),
                        (lambda: snapjump.contact(nu=0.7), "nu")):
        with pytest.raises(ValueError, match=words) as e:
            call()
        assert isinstance(e.value, snapjump.InputError) and "--" not in str(e.value)


def _write_run_and_sweep(tmp_path):
    # One run's folder and a sweep's table that holds the same run, as snapjump writes them:
    # series.csv without units, summary.json nested, sweep.csv with units in its headers.
    run = tmp_path / "run"
    run.mkdir()
    (run / "series.csv").write_text("t,z,F,contact\n0,0,0.48,ring\n0.0001,1e-6,0.5,disk\n")
    summary = {"status": "completed (apex of the flight)", "wall_time": 12.5,
               "case": {"R": 0.03, "h": 0.002, "net_weight": 0.48, "mesh": None},
               "measured": {"outcome": "Jump",
                            "quantities": {"F_star": {"value": 1.75, "unit": "N"},
                                           "t_star": {"value": 0.031, "unit": "s"}}},
               "theory": {"outcome_text": "Jump",
                          "quantities": {"F_star": {"lower": 1.6, "upper": 2.6, "unit": "N"}}}}
    import json
    (run / "summary.json").write_text(json.dumps(summary))
    sweep = tmp_path / "sweep"
    sweep.mkdir()
    (sweep / "sweep.csv").write_text(
        "run,status,outcome,predicted_outcome,R [m],h [m],net_weight [N],F_star [N],t_star [s],"
        "F_star_lo [N],F_star_hi [N],wall_time [s]\n"
        "run-0000,completed,Jump,Jump,0.03,0.002,0.48,1.75,0.031,1.6,2.6,"
        "12.5\n")
    return run, sweep


def test_read_run_and_read_sweep_share_keys_and_units(tmp_path):
    run, sweep = _write_run_and_sweep(tmp_path)
    r, s = snapjump.read_run(run), snapjump.read_sweep(sweep)
    assert r["series"]["F"][1] == 0.5 and r["series"]["contact"] == ["ring", "disk"]
    assert r["units"]["t"] == "s" and r["units"]["F"] == "N"
    shared = ["outcome", "predicted_outcome", "R", "h", "net_weight", "F_star",
              "t_star", "F_star_lower", "F_star_upper", "wall_time"]
    for key in shared:
        row = s["table"][key][0]
        assert r["values"][key] == row, key
        assert r["units"][key] == s["units"][key], key
    assert s["units"]["F_star_lower"] == "N" and s["units"]["R"] == "m"
    assert "F_star [N]" not in s["table"] and "F_star_lo" not in s["table"]


def _write_series(path, cols):
    with open(path, "w") as f:
        f.write(",".join(cols) + "\n")
        for row in zip(*cols.values()):
            f.write(",".join(repr(float(v)) for v in row) + "\n")


def _record_and_run(tmp_path):
    # The reference jump as a record and as a run's series, with the default popper's case.
    cols = _jump_columns()
    _write_series(tmp_path / "record.csv", cols)
    run = tmp_path / "run"
    run.mkdir()
    _write_series(run / "series.csv", cols)
    (run / "case.toml").write_text('[shell]\nR = "30 mm"\nh = "2 mm"\n[material]\n'
                                   'E = "1.2 MPa"\n[popper]\nnet_weight = "0.48 N"\n')
    return tmp_path / "record.csv", run


@pytest.mark.parametrize("with_pandas", [False, True])
def test_compare_a_record_beside_a_run(tmp_path, monkeypatch, with_pandas):
    import sys
    import types
    if with_pandas:  # a stand-in for pandas, whichever is installed: what compare hands it
        fake = types.ModuleType("pandas")

        class DataFrame:
            @classmethod
            def from_dict(cls, d, orient):
                frame = cls()
                frame.rows, frame.orient = d, orient
                return frame
        fake.DataFrame = DataFrame
        monkeypatch.setitem(sys.modules, "pandas", fake)
    else:
        monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas raises ImportError
    record, run = _record_and_run(tmp_path)
    c = snapjump.compare(record, run)
    assert c["outcomes"]["records"] == ["Jump"] and c["outcomes"]["run"] == "Jump"
    q = c["quantities"]
    assert q["F_star"]["record"] == pytest.approx(2.0, rel=1e-9)
    assert q["F_star_over_mg"]["record"] == pytest.approx(2.0 / 0.48, rel=1e-9)
    assert q["t_star"]["record"] == pytest.approx(25.92e-3 - 20.05e-3, abs=1e-8)
    assert q["t_star"]["difference"] == pytest.approx(0.0, abs=1e-12)  # the same series
    assert q["F_star"]["unit"] == "N"
    if with_pandas:
        assert c["frame"].orient == "index" and c["frame"].rows is q
    else:
        assert c["frame"] is None
    assert not (tmp_path / "run" / "figures").exists()  # figure=None draws none
    c2 = snapjump.compare([record, record], run, force_resolution="5 mN")
    assert q["F_star"]["uncertainty"] == pytest.approx(0.012)
    assert c2["quantities"]["F_star"]["n"] == 2
    assert c2["quantities"]["F_star"]["uncertainty"] == pytest.approx(0.005)
    with pytest.raises(FileNotFoundError, match="nowhere"):
        snapjump.compare(tmp_path / "nowhere.csv", run)
    with pytest.raises(snapjump.InputError, match="force_offset"):
        snapjump.compare(record, run, force_offset="1 m")


def test_every_public_function_explains_itself():
    import pydoc
    for name in snapjump.__all__:
        doc = getattr(snapjump, name).__doc__
        assert doc and len(doc.split()) > 10, name
    for name in ("predict", "contact", "analyze", "compare", "design", "run", "read_run",
                 "read_sweep"):
        assert "Returns" in getattr(snapjump, name).__doc__, name
    text = pydoc.render_doc(snapjump.run, renderer=pydoc.plaintext)
    for words in ("end_time", "seconds", "resolution", "progress", "Returns the run's folder",
                  "FileNotFoundError"):
        assert words in text, words


def _design_grid(tmp_path, out, hide_matplotlib):
    import subprocess
    import sys
    script = os.path.join(SOURCE, "examples", "python", "design_grid.py")
    code = ("import runpy, sys\n"
            + ("sys.modules['matplotlib'] = None\n" if hide_matplotlib else "")
            + f"sys.argv = [{script!r}, '--n', '6', '--out', {str(out)!r}]\n"
            + f"runpy.run_path({script!r}, run_name='__main__')\n")
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(snapjump.__file__)))
    return subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                          text=True, check=True, env=env).stdout


def test_the_design_grid_example(tmp_path):
    out = tmp_path / "grid.csv"
    said = _design_grid(tmp_path, out, hide_matplotlib=True)
    assert "no matplotlib" in said and str(out) in said
    import csv
    with open(out) as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == 36
    h = np.array([float(r["h [m]"]) for r in rows])
    mg = np.array([float(r["net_weight [N]"]) for r in rows])
    assert sorted(set(h)) == pytest.approx(np.linspace(1e-3, 3e-3, 6))
    assert sorted(set(mg)) == pytest.approx(np.linspace(0.1, 2.0, 6))
    # F* = alpha_F E h^3 / R: the same alpha_F bound for every design (one nu).
    alpha = np.array([float(r["F_star_lower [N]"]) for r in rows]) / (1.2e6 * h ** 3 / 0.03)
    np.testing.assert_allclose(alpha, snapjump.contact(nu=0.45)["bounds"]["alpha_F"]["lower"],
                               rtol=1e-9)
    # A design whose F* upper bound stays below its net weight cannot jump.
    for r in rows:
        if float(r["F_star_upper [N]"]) < float(r["net_weight [N]"]):
            assert "Jump" not in r["outcome"]
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return
    said = _design_grid(tmp_path, tmp_path / "grid.png", hide_matplotlib=False)
    assert (tmp_path / "grid.png").stat().st_size > 0


@pytest.mark.parametrize("with_pandas", [False, True])
def test_the_readers_frames_with_and_without_pandas(tmp_path, monkeypatch, with_pandas):
    import sys
    import types
    if with_pandas:  # a stand-in for pandas: the columns the readers hand it
        fake = types.ModuleType("pandas")
        fake.DataFrame = lambda columns: ("frame", columns)
        monkeypatch.setitem(sys.modules, "pandas", fake)
    else:
        monkeypatch.setitem(sys.modules, "pandas", None)
    run, sweep = _write_run_and_sweep(tmp_path)
    r, s = snapjump.read_run(run), snapjump.read_sweep(sweep)
    if with_pandas:
        assert r["frame"] == ("frame", r["series"]) and s["frame"] == ("frame", s["table"])
    else:
        assert r["frame"] is None and s["frame"] is None


def test_design_meets_its_target_through_predict():
    d = snapjump.design(jump_height="50 mm", net_weight="1 N", E="1.2 MPa", count=2,
                        branch=False)
    assert d["designs"]
    for x in d["designs"]:
        p = snapjump.predict(R=x["R"], h=x["h"], net_weight="1 N", E="1.2 MPa")
        assert p["quantities"]["H"]["lower"] >= 0.050
    with pytest.raises(snapjump.InputError, match="misses by"):
        snapjump.design(jump_height="100 m", branch=False)
