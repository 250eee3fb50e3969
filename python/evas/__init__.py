"""evas from Python: a scene's model, its residual and Jacobian, and runs of any
integrator (built in or plug-in), with NumPy arrays and SciPy sparse matrices.

    import evas
    m = evas.Model("scenes/demo.yaml")
    q0, v0 = m.initial_state()
    K, C = m.jacobian(0.0, q0, v0)          # scipy.sparse.csc_matrix, fixed pattern
    r = m.run("ida", {"rtol": 1e-8})        # dict: time, values, channels, stats, status

docs/extending.md describes every function.
"""
import os as _os
import sys as _sys


def _missing(module, debian_package):
    """An ImportError naming what this interpreter lacks and how to install it."""
    deb = "/usr/bin/python3"
    how = (
        "install it with: apt-get install -y %s" % debian_package
        if _os.path.realpath(_sys.executable) == _os.path.realpath(deb)
        else "install it with: %s -m pip install %s (or run evas with %s, whose "
        "Debian package %s provides it)" % (_sys.executable, module, deb, debian_package)
    )
    return ImportError(
        "evas needs %s, which this Python (%s) does not have: %s"
        % (module, _sys.executable, how)
    )


# NumPy carries every array evas returns: without it the first call would fail
# with a bare "No module named numpy", so the import says so at once.
try:
    import numpy as _numpy  # noqa: F401
except ImportError:
    raise _missing("numpy", "python3-numpy") from None

# Integrator plug-ins resolve evas's symbols against the module that loads them:
# load the compiled part with global symbol visibility.
_flags = _sys.getdlopenflags()
_sys.setdlopenflags(_flags | _os.RTLD_GLOBAL)
try:
    from . import _evas
finally:
    _sys.setdlopenflags(_flags)

InputError = _evas.InputError
RunError = _evas.RunError
integrators = _evas.integrators
load_plugin = _evas.load_plugin

problems = _evas.problems

__all__ = [
    "Model",
    "Problem",
    "problems",
    "read_results",
    "write_results",
    "integrators",
    "load_plugin",
    "InputError",
    "RunError",
]


def _csc(parts):
    try:  # imported when first needed: `import evas` needs no SciPy
        import scipy.sparse
    except ImportError:
        raise _missing("scipy", "python3-scipy") from None

    data, indices, indptr, shape = parts
    return scipy.sparse.csc_matrix((data, indices, indptr), shape=shape)


class Model(_evas.Model):
    """A scene's model: the problem qdd + f(t, q, v) = 0 of its bodies and elements.

    Model("scene.yaml"), Model(text=YAML) (a scene given as text; relative body
    files are found from base_dir, default the current folder), and either with
    params={"crank.lof.speed": 418.879} (or ["crank.lof.speed=418.879"]): the
    edits of evas run --param.

    size, name, t_start, t_end, channels, output_times, settings (the scene's
    integrator settings, each as float, int or str), warnings (the scene's
    plausibility warnings: likely unit slips); initial_state() -> (q, v);
    force(t, q, v) -> f;
    jacobian(t, q, v) -> (K, C); rhs(t, y) and rhs_jacobian(t, y) of the first-
    order form y' = [v; -f]; residual(t, y, yd) and iteration_matrix(t, y, yd, cj)
    = dF/dy + cj dF/dyd of F = [yd_q - v; yd_v + f] (what IDA solves);
    outputs(t, q, v) -> the scene's output channels; run(...).
    With joints (a DAE, M qdd + f + G^T lambda = 0, g = 0): constraint_count,
    constraint_names, constraint(t, q, v) -> (g, g', ga) with
    d(g')/dt = G qdd + ga, constraint_jacobian(t, q) -> G, consistent_state(t,
    q, v) -> (q, v, lambda) projected onto the constraints. residual, rhs and
    their Jacobians are those of the unconstrained part; the full DAE in a
    formulation (index-3, index-2, ggl = "default", index-1), y = [q; v;
    lambda (; mu); z]: dae_size(formulation), dae_residual(t, y, yd,
    formulation), dae_iteration_matrix(t, y, yd, cj, formulation),
    dae_consistent_start(t, q, v, formulation) -> (y, yd, max |F|).
    """

    def __init__(self, scene=None, params=None, text=None, base_dir=None):
        if (scene is None) == (text is None):
            raise TypeError("Model: give a scene file or text=YAML, not both")
        if isinstance(params, dict):
            params = ["%s=%s" % (k, _setting_text(v)) for k, v in params.items()]
        params = list(params or [])
        if text is not None:
            scene = _os.path.join(base_dir or _os.getcwd(), "(text).yaml")
        super().__init__(_os.fspath(scene), text, params)

    def jacobian(self, t, q, v):
        """K = df/dq and C = df/dv as scipy.sparse.csc_matrix (fixed pattern)."""
        K, C = self._jacobian(t, q, v)
        return _csc(K), _csc(C)

    def rhs_jacobian(self, t, y):
        """d(rhs)/dy = [[0, I], [-K, -C]] as scipy.sparse.csc_matrix."""
        return _csc(self._rhs_jacobian(t, y))

    def iteration_matrix(self, t, y, yd, cj):
        """dF/dy + cj dF/dyd = [[cj I, -I], [K, cj I + C]] as scipy.sparse.csc_matrix."""
        return _csc(self._iteration_matrix(t, y, yd, cj))

    def constraint_jacobian(self, t, q):
        """G = dg/dq (m x n) as scipy.sparse.csc_matrix (fixed pattern)."""
        return _csc(self._constraint_jacobian(t, q))

    def dae_iteration_matrix(self, t, y, yd, cj, formulation="default"):
        """dF/dy + cj dF/dyd of dae_residual (the jointed scene's full DAE in a
        formulation) as scipy.sparse.csc_matrix."""
        return _csc(self._dae_iteration_matrix(t, y, yd, cj, formulation))

    def run(self, integrator="", settings=None, t_end=None):
        """Runs the scene with an integrator (the scene's when "") and settings
        {key: value} (evas run --help-settings); t_end overrides the scene's end.
        Returns {time, values (rows x channels), channels, stats, status, integrator};
        a failed run has status "failed: ..." and the rows computed so far."""
        return self._run(integrator, dict(settings or {}), t_end)


class Problem(_evas.Problem):
    """A problem of `evas problem` (evas.problems() lists them; IVP Test Set
    problems with their published end points, docs/problems.md).

    Problem("andrews", formulation="ggl"): a constrained mechanical problem
    M(q) qdd + f(t, q, v) + G^T lambda = 0, g(t, q) = 0, with its parts
    force(t, q, v), jacobian(t, q, v) -> (K, C), mass(t, q) -> M,
    constraint(t, q, v) -> (g, g', ga), constraint_jacobian(t, q) -> G, and
    the residual of its DAE in a formulation (index-3, index-2, ggl, index-1;
    "default" = ggl), y = [q; v; lambda (; mu)]: residual(t, y, yd),
    iteration_matrix(t, y, yd, cj) = dF/dy + cj dF/dyd, consistent_start(t, q,
    v) -> (y, yd, max |F|). A first-order problem (first_order: chemakzo,
    transamp, wheelset), M y' = f(t, y): mass_matrix(), rhs(t, y),
    residual(t, y, yd) = M yd - f and iteration_matrix (dense).
    reference() -> the published end point; score(q, v, lambda_, rtol, atol)
    (first order: score(y, rtol=..., atol=...)) -> the test set's mescd, scd.
    Sparse matrices are scipy.sparse.csc_matrix.
    """

    def __init__(self, name, formulation="default"):
        super().__init__(name, formulation)

    def jacobian(self, t, q, v):
        """K = df/dq and C = df/dv as scipy.sparse.csc_matrix."""
        K, C = self._jacobian(t, q, v)
        return _csc(K), _csc(C)

    def mass(self, t, q):
        """M(q) as scipy.sparse.csc_matrix (the identity without a mass matrix)."""
        return _csc(self._mass(t, q))

    def constraint_jacobian(self, t, q):
        """G = dg/dq (m x n) as scipy.sparse.csc_matrix."""
        return _csc(self._constraint_jacobian(t, q))

    def iteration_matrix(self, t, y, yd, cj):
        """dF/dy + cj dF/dyd of the residual: scipy.sparse.csc_matrix (a NumPy
        array for a first-order problem)."""
        J = self._iteration_matrix(t, y, yd, cj)
        return J if self.first_order else _csc(J)


def _setting_text(v):
    """A Python value as evas reads it: repr keeps every digit of a float."""
    if isinstance(v, bool):
        return "true" if v else "false"
    return repr(v) if isinstance(v, float) else str(v)


def write_results(path, time, values, channels, units=None, source="python"):
    """Writes a results file evas reads (read_results, and `evas study
    --reference-file` as a reference computed in Python): time (rows),
    values (rows x channels), channel names and units; `source` is recorded
    as the file's integrator."""
    import numpy as np

    return _evas._write_results(
        _os.fspath(path),
        np.asarray(time, dtype=float),
        np.asarray(values, dtype=float),
        list(channels),
        list(units or []),
        source,
    )


def read_results(path):
    """A results file (results.h5 of evas run): {time, values, channels, units,
    status, integrator, scene}."""
    return _evas._read_results(path)
