"""pytest suite of the Python module (python/evas): the model's f, K, C and the
first-order residual and iteration matrix against finite differences, runs of
built-in and plug-in integrators, SciPy's implicit solvers on evas's right-hand
side and Jacobian against IDA, results files, errors."""
import os
import subprocess
import tempfile

import numpy as np
import pytest
import scipy.integrate

import evas

SRC = os.environ["EVAS_SOURCE_DIR"]
DEMO = os.path.join(SRC, "scenes", "demo.yaml")


@pytest.fixture(scope="module")
def model():
    return evas.Model(DEMO)


def state(m, seed=1):
    """The initial state, perturbed so that every element is loaded."""
    rng = np.random.default_rng(seed)
    q, v = m.initial_state()
    return q + 1e-6 * rng.standard_normal(m.size), v + 1e-3 * rng.standard_normal(m.size)


def test_model_basics(model):
    assert model.size == 28 and model.name == "demo"
    q, v = model.initial_state()
    assert q.shape == (28,) and v.shape == (28,)
    assert model.force(0.0, q, v).shape == (28,)
    assert len(model.channels) == 30 and model.t_end == pytest.approx(0.15)
    s = model.settings
    assert isinstance(s["rtol"], float) and s["rtol"] > 0
    assert isinstance(s["max_steps"], int) and isinstance(s["name"], str)
    assert model.warnings == []


def test_model_from_text_and_params():
    """YAML text (bodies found from base_dir) and --param edits give the same
    model as the file; an edit shows in the model, a unit slip in warnings."""
    text = open(DEMO).read()
    a = evas.Model(text=text, base_dir=os.path.dirname(DEMO))
    b = evas.Model(DEMO)
    q, v = b.initial_state()
    assert a.size == b.size and a.channels == b.channels
    assert np.array_equal(a.force(0.0, q, v), b.force(0.0, q, v))
    c = evas.Model(DEMO, params={"time.end": 0.05, "integrator.rtol": 1e-7})
    assert c.t_end == pytest.approx(0.05) and c.settings["rtol"] == pytest.approx(1e-7)
    d = evas.Model(DEMO, params=["time.end=0.05"])
    assert d.t_end == pytest.approx(0.05)
    # 3000 typed for rad/s (it was rpm): run, with the warning naming the slip
    slip = evas.Model(DEMO, params={"shaft.lof.speed": 3000})
    assert any("3000 rpm would be 314.159 rad/s" in w for w in slip.warnings), slip.warnings
    with pytest.raises(evas.InputError, match="nosuch"):
        evas.Model(DEMO, params={"nosuch.key": 1})
    with pytest.raises(TypeError):
        evas.Model(DEMO, text=text)


def test_missing_numpy_is_named():
    """An interpreter without NumPy gets an ImportError that names NumPy and the
    command that installs it, at import time (not a bare error at the first
    call). Simulated by hiding numpy from a child interpreter."""
    code = (
        "import sys\n"
        "class Hide:\n"
        "    def find_spec(self, name, path=None, target=None):\n"
        "        if name == 'numpy' or name.startswith('numpy.'):\n"
        "            raise ImportError('No module named numpy')\n"
        "sys.meta_path.insert(0, Hide())\n"
        "import evas\n"
    )
    r = subprocess.run([__import__("sys").executable, "-c", code], capture_output=True, text=True)
    assert r.returncode != 0
    assert "evas needs numpy" in r.stderr and "install it with" in r.stderr, r.stderr


def test_jacobian_against_differences(model):
    t = 0.01
    q, v = state(model)
    K, C = model.jacobian(t, q, v)
    assert K.format == "csc" and K.shape == (28, 28)
    f0 = model.force(t, q, v)
    Kd, Cd = np.zeros((28, 28)), np.zeros((28, 28))
    for j in range(28):
        hq, hv = 1e-9, 1e-6  # modal coordinates ~1e-6, velocities ~1e-3
        dq, dv = np.zeros(28), np.zeros(28)
        dq[j], dv[j] = hq, hv
        Kd[:, j] = (model.force(t, q + dq, v) - model.force(t, q - dq, v)) / (2 * hq)
        Cd[:, j] = (model.force(t, q, v + dv) - model.force(t, q, v - dv)) / (2 * hv)
    scale_k = np.abs(Kd).max()
    scale_c = np.abs(Cd).max()
    # measured 3.7e-9 and 5.7e-12 of the largest entry
    assert np.abs(K.toarray() - Kd).max() < 1e-6 * scale_k
    assert np.abs(C.toarray() - Cd).max() < 1e-6 * scale_c
    assert f0.shape == (28,)


def test_residual_and_iteration_matrix(model):
    t, cj = 0.01, 3.0e4
    q, v = state(model, 2)
    y = np.concatenate([q, v])
    yd = model.rhs(t, y)
    # the residual vanishes on the right-hand side: F(t, y, rhs(t, y)) = 0
    assert np.abs(model.residual(t, y, yd)).max() < 1e-9 * np.abs(yd).max()
    J = model.iteration_matrix(t, y, yd, cj).toarray()
    # dF/dy + cj dF/dyd by central differences of the residual
    Jd = np.zeros((56, 56))
    for j in range(56):
        h = 1e-9 if j < 28 else 1e-6
        e = np.zeros(56)
        e[j] = h
        Jd[:, j] = (model.residual(t, y + e, yd) - model.residual(t, y - e, yd)) / (2 * h)
        Jd[:, j] += cj * (model.residual(t, y, yd + e) - model.residual(t, y, yd - e)) / (2 * h)
    assert np.abs(J - Jd).max() < 1e-5 * np.abs(Jd).max()
    A = model.rhs_jacobian(t, y).toarray()
    assert np.allclose(A[:28, 28:], np.eye(28)) and np.abs(A[:28, :28]).max() == 0


def test_run_builtin_integrators_agree(model):
    ref = model.run("ida", {"rtol": 1e-10, "atol": 1e-13}, t_end=0.01)
    assert ref["status"] == "completed" and ref["values"].shape == (21, 30)
    peak = np.abs(ref["values"]).max(axis=0)
    peak[peak == 0] = 1.0
    for name, settings in [("cvode", {"rtol": 1e-8}), ("generalized-alpha", {"step": 2e-6})]:
        r = model.run(name, settings, t_end=0.01)
        assert r["status"] == "completed", r["status"]
        assert r["stats"]["steps"] > 0
        assert (np.abs(r["values"] - ref["values"]) / peak).max() < 1e-3, name


def test_plugin_integrator_from_python(model):
    assert evas.load_plugin(os.environ["EVAS_RADAU_PLUGIN"]) == ["radau-iia"]
    assert "radau-iia" in evas.integrators()
    ref = model.run("ida", {"rtol": 1e-10, "atol": 1e-13}, t_end=0.01)
    r = model.run("radau-iia", {"step": 1e-5}, t_end=0.01)
    peak = np.abs(ref["values"]).max(axis=0)
    peak[peak == 0] = 1.0
    # measured 3.9e-5 of the channel peaks (Radau IIA is order 3; tests/test_plugins.cpp)
    assert (np.abs(r["values"] - ref["values"]) / peak).max() < 1e-4


@pytest.mark.parametrize("method", ["Radau", "BDF"])
def test_scipy_on_evas_rhs_and_jacobian(model, method):
    """SciPy's implicit solvers (Hairer-Wanner's Radau5; a variable-order BDF) on
    y' = rhs(t, y) with evas's analytic Jacobian reach IDA's answer."""
    t_end = 0.005
    ref = model.run("ida", {"rtol": 1e-10, "atol": 1e-13}, t_end=t_end)
    q0, v0 = model.initial_state()
    times = ref["time"]
    sol = scipy.integrate.solve_ivp(model.rhs, (0.0, t_end), np.concatenate([q0, v0]),
                                    method=method, t_eval=times, rtol=1e-8, atol=1e-11,
                                    jac=lambda t, y: model.rhs_jacobian(t, y))
    assert sol.success, sol.message
    rows = np.array([model.outputs(t, y[:28], y[28:]) for t, y in zip(sol.t, sol.y.T)])
    peak = np.abs(ref["values"]).max(axis=0)
    peak[peak == 0] = 1.0
    err = (np.abs(rows - ref["values"]) / peak).max()
    assert err < 1e-4, err


def test_read_results_of_an_evas_run():
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        subprocess.run([os.environ["EVAS_PROGRAM"], "run", DEMO, "--t-end", "0.01", "--out", out,
                        "-q"], check=True)
        r = evas.read_results(os.path.join(out, "results.h5"))
    assert r["status"] == "completed" and r["values"].shape == (21, 30)
    assert r["time"][-1] == pytest.approx(0.01)
    assert len(r["units"]) == 30


def test_errors_name_the_input(model):
    with pytest.raises(evas.InputError, match="nowhere.yaml"):
        evas.Model("nowhere.yaml")
    q, v = model.initial_state()
    with pytest.raises(evas.InputError, match="length 28"):
        model.force(0.0, q[:3], v)
    with pytest.raises(evas.InputError, match="unknown"):
        model.run("no-such-integrator", {}, t_end=0.01)
    with pytest.raises(evas.InputError):
        model.run("ida", {"rtol": "abc"}, t_end=0.01)


def test_scipy_work_precision_example():
    """examples/python_scipy/work_precision.py runs and writes its table and figure."""
    script = os.path.join(SRC, "examples", "python_scipy", "work_precision.py")
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run(["python3" if not os.path.exists("/usr/bin/python3") else "/usr/bin/python3",
                        script, DEMO, "--t-end", "0.005", "--rtols", "1e-5", "--out", tmp],
                       check=True, capture_output=True)
        lines = open(os.path.join(tmp, "work_precision.csv")).read().splitlines()
        assert lines[0].startswith("solver,rtol,error")
        assert [x.split(",")[0] for x in lines[1:]] == ["ida", "scipy-Radau", "scipy-BDF"]
        for x in lines[1:]:
            assert float(x.split(",")[2]) < 1e-2  # every solver near the reference
        assert os.path.getsize(os.path.join(tmp, "work_precision.png")) > 1000


def test_joints_from_python():
    """A scene with a revolute joint (scenes/hinged_beam.yaml): G against central
    differences of g, the consistent start on the constraints, and runs: IDA
    solves the DAE with |g| at the level of its tolerances, generalized-alpha in
    its index-3 form at round-off, and refuses IDA's GGL form (docs/theory.md
    section 10)."""
    m = evas.Model(os.path.join(SRC, "scenes", "hinged_beam.yaml"))
    assert m.constraint_count == 5
    assert m.constraint_names[0] == "pin.p.x" and m.constraint_names[4] == "pin.r.y"
    q, v = state(m, 3)
    g, gv, ga = m.constraint(0.01, q, v)
    G = m.constraint_jacobian(0.01, q).toarray()
    assert G.shape == (5, m.size)
    np.testing.assert_allclose(gv, G @ v, atol=1e-14)  # a frame at rest: g_t = 0
    h = 1e-7
    Gfd = np.column_stack([(m.constraint(0.01, q + h * e, v)[0] - m.constraint(0.01, q - h * e, v)[0])
                           / (2 * h) for e in np.eye(m.size)])
    assert np.abs(G - Gfd).max() < 1e-8 * (1 + np.abs(G).max())
    qc, vc, lam = m.consistent_state(0.0, q, v)
    gc, gvc, _ = m.constraint(0.0, qc, vc)
    assert np.abs(gc).max() < 1e-12 and np.abs(gvc).max() < 1e-12 and lam.shape == (5,)
    r = m.run("ida", {"rtol": "1e-6"}, 0.05)
    assert r["status"] == "completed"
    assert r["stats"]["max_constraint"] < 1e-9
    ga_run = m.run("generalized-alpha", {"step": "1e-4"}, 0.01)  # index-3 (Arnold & Bruls)
    assert ga_run["status"] == "completed" and ga_run["stats"]["max_constraint"] < 1e-12
    ggl = m.run("generalized-alpha", {"step": "1e-4", "formulation": "ggl"}, 0.01)
    assert ggl["status"].startswith("failed") and "index-3" in ggl["status"]
    pen = m.run("generalized-alpha", {"step": "1e-4", "formulation": "penalty",
                                      "penalty_stiffness": "1e8"}, 0.01)
    assert pen["status"] == "completed" and pen["stats"]["max_constraint"] < 1e-5


@pytest.mark.parametrize("form", ["index-3", "index-2", "default", "index-1"])
def test_joints_full_dae_residual(form):
    """The jointed scene's full DAE (dae/formulation.h): consistent start with
    a zero residual, the iteration matrix against central differences."""
    m = evas.Model(os.path.join(SRC, "scenes", "hinged_beam.yaml"))
    q, v = state(m, 4)
    y, yd, r = m.dae_consistent_start(0.0, q, v, form)
    n, mc = m.size, m.constraint_count
    assert len(y) == m.dae_size(form) >= 2 * n + mc and r < 1e-9
    assert np.abs(m.dae_residual(0.0, y, yd, form)).max() < 1e-9
    rng = np.random.default_rng(5)
    y1, yd1, cj = y + 1e-6 * rng.standard_normal(len(y)), yd + 1e-3 * rng.standard_normal(len(y)), 1e3
    J = m.dae_iteration_matrix(0.0, y1, yd1, cj, form).toarray()
    h = 1e-7
    Jfd = np.column_stack([
        (m.dae_residual(0.0, y1 + h * e, yd1 + cj * h * e, form)
         - m.dae_residual(0.0, y1 - h * e, yd1 - cj * h * e, form)) / (2 * h)
        for e in np.eye(len(y))])
    assert np.abs(J - Jfd).max() < 1e-5 * (1 + np.abs(Jfd).max())


@pytest.mark.parametrize("case", ["states", "beam"])
def test_run_gives_the_rows_of_evas_run(case):
    """One run for every front end (run/run.h): Model.run gives the rows of
    `evas run` bit for bit, on the validation engine with element internal states
    (Maxwell mounts, a clutch disk; validation/engine/scenes.sh) and on a jointed
    beam under generalized-alpha, multiplier channels included."""
    with tempfile.TemporaryDirectory() as tmp:
        if case == "states":
            subprocess.run([os.path.join(SRC, "validation", "engine", "scenes.sh"), tmp, "0.005"],
                           check=True)
            scene, args, settings = os.path.join(tmp, "case5.yaml"), [], {}
            integrator = ""
        else:
            scene = os.path.join(SRC, "scenes", "hinged_beam.yaml")
            args = ["--integrator", "generalized-alpha", "--step", "1e-4", "--t-end", "0.02"]
            integrator, settings = "generalized-alpha", {"step": "1e-4"}
        out = os.path.join(tmp, "out")
        subprocess.run([os.environ["EVAS_PROGRAM"], "run", scene, "--out", out, "-q"] + args,
                       check=True)
        ref = evas.read_results(os.path.join(out, "results.h5"))
        m = evas.Model(scene)
        r = m.run(integrator, settings, 0.02 if case == "beam" else None)
    assert r["status"] == "completed" and ref["status"] == "completed"
    assert r["channels"] == ref["channels"]
    assert r["values"].shape == ref["values"].shape and r["values"].shape[0] > 2
    np.testing.assert_array_equal(r["time"], ref["time"])
    np.testing.assert_array_equal(r["values"], ref["values"])
    if case == "beam":
        assert sum(c.endswith(".lambda") for c in r["channels"]) == 5


def _fd_iteration_matrix(p, t, y, yd, cj, h=1e-7):
    """dF/dy + cj dF/dyd by central differences of p.residual."""
    n = len(y)
    J = np.zeros((n, n))
    for k in range(n):
        e = np.zeros(n)
        e[k] = h * max(1.0, abs(y[k]))
        J[:, k] = (p.residual(t, y + e, yd + cj * e) - p.residual(t, y - e, yd - cj * e)) / (
            2 * e[k]
        )
    return J


@pytest.mark.parametrize("form", ["index-3", "ggl", "index-1"])
def test_problem_residual_of_andrews(form):
    """Andrews' squeezing mechanism (IVP Test Set; Hairer & Wanner 1996, VII.7):
    the consistent start satisfies the DAE of every formulation, and the
    iteration matrix matches differences of the residual."""
    assert "andrews" in evas.problems()
    p = evas.Problem("andrews", formulation=form)
    assert p.size == 7 and p.constraint_count == 6 and p.formulation == form
    q, v = p.initial_state()
    y, yd, r = p.consistent_start(0.0, q, v)
    assert len(y) == p.dae_size and r < 1e-10
    assert np.max(np.abs(p.residual(0.0, y, yd))) < 1e-8
    g, gv, ga = p.constraint(0.0, q, v)
    assert np.max(np.abs(g)) < 1e-12
    G = p.constraint_jacobian(0.0, q)
    assert G.shape == (6, 7)
    M = p.mass(0.0, q)
    assert M.shape == (7, 7) and np.allclose(M.toarray(), M.toarray().T)
    rng = np.random.default_rng(3)
    y1 = y + 1e-3 * rng.standard_normal(len(y))
    yd1 = yd + 1e-3 * rng.standard_normal(len(y))
    J = p.iteration_matrix(0.0, y1, yd1, 50.0).toarray()
    Jfd = _fd_iteration_matrix(p, 0.0, y1, yd1, 50.0)
    assert np.max(np.abs(J - Jfd)) < 1e-5 * max(1.0, np.max(np.abs(Jfd)))


def test_problem_reference_and_score():
    p = evas.Problem("andrews")
    ref = p.reference()
    s = p.score(ref["q"], ref["v"], ref.get("lambda"), rtol=1.0, atol=1.0)
    assert s["mescd"] == float("inf")
    q = ref["q"].copy()
    q[2] += 1e-4 * (1.0 + abs(q[2]))
    s = p.score(q, ref["v"], rtol=1.0, atol=1.0)
    assert s["mescd"] == pytest.approx(4.0, abs=1e-9) and s["worst"] == 2


def test_problem_first_order():
    """The chemical Akzo Nobel problem, M y' = f with M singular: the residual
    M yd - f and its iteration matrix cj M - df/dy against differences."""
    p = evas.Problem("chemakzo")
    assert p.first_order and p.size == 6
    y, yp = p.initial_state()
    assert np.max(np.abs(p.residual(0.0, y, yp))) < 1e-8
    M = p.mass_matrix()
    assert M.shape == (6, 6) and M[5, 5] == 0.0
    J = p.iteration_matrix(0.0, y, yp, 10.0)
    Jfd = _fd_iteration_matrix(p, 0.0, y, yp, 10.0, h=1e-8)
    assert np.max(np.abs(J - Jfd)) < 1e-5 * max(1.0, np.max(np.abs(Jfd)))
    with pytest.raises(evas.InputError, match="no formulations"):
        evas.Problem("chemakzo", formulation="index-2")
    with pytest.raises(evas.InputError, match="no problem named 'andrew'"):
        evas.Problem("andrew")


def test_a_python_reference_for_a_study():
    """A reference computed in Python (here IDA at rtol 1e-11 through Model.run),
    written with write_results, read back, and used by `evas study
    --reference-file`: the study's case is measured against it."""
    beam = os.path.join(SRC, "scenes", "hinged_beam.yaml")
    m = evas.Model(beam)
    ref = m.run("ida", {"rtol": 1e-11, "atol": 1e-14})
    assert ref["status"] == "completed"
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "ref.h5")
        evas.write_results(path, ref["time"], ref["values"], ref["channels"], source="scipy")
        back = evas.read_results(path)
        assert back["integrator"] == "scipy" and back["values"].shape == ref["values"].shape
        np.testing.assert_array_equal(back["values"], ref["values"])
        out = os.path.join(tmp, "study")
        subprocess.run([os.environ["EVAS_PROGRAM"], "study", "work-precision", beam,
                        "--reference-file", path, "--case", "ida rtol=1e-6", "--channels",
                        "spring.f*", "--out", out, "-q", "--no-plot"], check=True,
                       stdout=subprocess.DEVNULL)
        md = open(os.path.join(out, "study.md")).read()
        assert "ref.h5 (scipy, completed)" in md
        with pytest.raises(evas.InputError, match="rows x channels"):
            evas.write_results(path, ref["time"], ref["values"][:, :2], ref["channels"])
