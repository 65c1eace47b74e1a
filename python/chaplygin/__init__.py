"""Chaplygin: nonholonomic mechanical models derived exactly and simulated
at compiled speed.

A model is read from its text (``load``: a ``.model`` file or the text
itself; ``builtin``: one of ``builtins()``), derived symbolically (the
constraint analysis, the Lagrange-d'Alembert equations, the reduced
port-Hamiltonian form, the momentum equation with a symmetry) and its
functions compiled to native code at run time. ``Model.simulate`` returns a
``Trajectory`` of NumPy columns, ``Model.linearize`` a ``Linearization``
with eigenvalues and intervals of stability, ``Model.gait`` what a shape
loop does and ``Model.optimal_gait`` the loop that does most, ``Model.plan`` the
optimal inputs between two states (a ``Plan``), ``Model.identify`` the
parameters that fit measured data (an ``Estimate``), ``Model.rhs`` a right-hand side
for ``scipy.integrate.solve_ivp``, and ``Model.sympy`` the derived matrices
as SymPy expressions; ``design_map`` the self-stable speeds over a grid of
parameters, on every core or on any ``concurrent.futures.Executor`` (a
Dask cluster's), and ``plans`` and ``estimates`` many plans or estimates, here or
on such an executor.

    >>> import chaplygin
    >>> board = chaplygin.builtin("snakeboard")
    >>> run = board.simulate(t_end=1.0, dt=0.01)
    >>> abs(run.summary["energy_drift"]) < 1e-12
    True
"""

from __future__ import annotations

import functools
import html
import json
import math
import os
import warnings
from concurrent.futures import Executor
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy
from numpy.typing import ArrayLike

from . import _chaplygin
from ._errors import ChaplyginError, ModelError, SimulationError
from ._sympy import derived_expressions

__all__ = [
    "ChaplyginError",
    "DesignMap",
    "Estimate",
    "Gait",
    "Linearization",
    "Model",
    "ModelError",
    "OptimalGait",
    "Plan",
    "Rhs",
    "SimulationError",
    "Steady",
    "SteadyFamily",
    "Trajectory",
    "builtin",
    "builtins",
    "design_map",
    "estimates",
    "load",
    "plans",
]

Rhs = _chaplygin.Rhs
Value = Union[float, str]


def builtins() -> List[str]:
    """The names of the built-in models."""
    return list(_chaplygin.builtins())


def builtin(name: str, engine: str = "jit") -> "Model":
    """The built-in model ``name``, its functions run by ``engine``
    (``"jit"``, native code compiled at run time, or ``"interpret"``)."""
    return Model(_chaplygin.builtin(name, engine))


def load(path_or_text: str, engine: str = "jit") -> "Model":
    """The model of the ``.model`` file at ``path_or_text``, or of the
    model text itself. Raises ``ModelError`` (with ``line`` and ``column``)
    for a model the compiler rejects."""
    return Model(_chaplygin.load(str(path_or_text), engine))


class Trajectory:
    """A simulation's recorded rows as NumPy columns.

    ``run.t`` is the time column, ``run["phi"]`` any other column by name
    (the state's entries: coordinates, then momenta or velocities),
    ``run.columns`` their names, ``run.data`` the ``(rows, columns)``
    array, ``run.summary`` the run's summary (a dict), ``run.tracks`` the
    declared points' positions (a ``Trajectory``, or ``None``).
    ``run.animate()`` draws the run as one offline HTML page, which Jupyter
    shows inline (``_repr_html_``).
    """

    def __init__(
        self,
        columns: Sequence[str],
        data: numpy.ndarray,
        summary: Optional[Dict[str, Any]],
        tracks: "Optional[Trajectory]" = None,
        draw: Optional[Callable[[List[str], numpy.ndarray, float], str]] = None,
    ) -> None:
        self.columns = list(columns)
        self.data = data
        self.summary = summary
        self.tracks = tracks
        self._draw = draw

    @property
    def t(self) -> numpy.ndarray:
        """The time of each row."""
        return self["t"]

    def __getitem__(self, name: str) -> numpy.ndarray:
        try:
            return self.data[:, self.columns.index(name)]
        except ValueError:
            raise KeyError(f"no column {name!r} (columns: {', '.join(self.columns)})") from None

    def __len__(self) -> int:
        return self.data.shape[0]

    def __repr__(self) -> str:
        return f"Trajectory({len(self)} rows, columns {self.columns})"

    def animate(self, path: Optional[Union[str, "os.PathLike[str]"]] = None, fps: float = 60.0) -> str:
        """The run as one HTML page that works offline (docs/INTERFACE.md
        section 10): a mechanism's bodies (wheels as discs rolling on their
        contact points' traces) and the items of the model's ``drawing:``
        section drawn in 3D at every ``1 / fps`` seconds of simulated time
        or so, z up. Writes it to ``path`` when given, and returns it.

        Raises ``ValueError`` for a model with nothing to draw (neither
        bodies nor a drawing section), a trajectory not returned by
        ``Model.simulate``, or ``fps`` not positive.
        """
        if self._draw is None:
            raise ValueError("this trajectory has no model to draw: animate a run Model.simulate returned")
        page = self._draw(self.columns, self.data, float(fps))
        if path is not None:
            with open(path, "w", encoding="utf-8") as file:
                file.write(page)
        return page

    def _repr_html_(self) -> Optional[str]:
        """The animation in an ``<iframe>`` for Jupyter; ``None`` (the text
        representation) for a run that cannot be drawn."""
        try:
            page = self.animate()
        except ValueError:
            return None
        return '<iframe srcdoc="{}" style="width: 100%; height: 540px; border: 0"></iframe>'.format(
            html.escape(page, quote=True)
        )

    def to_pandas(self) -> Any:
        """The rows as a ``pandas.DataFrame`` (pandas must be installed)."""
        import pandas

        return pandas.DataFrame(self.data, columns=self.columns)


class Linearization:
    """A linearization about a steady motion, or over a sweep.

    Over a sweep of ``variable``: ``values`` (``(len,)``), ``eigenvalues``
    (``(len, modes)`` complex, each row by descending real part),
    ``stable`` and ``neutral`` the intervals ``[(start, end), ...]`` of the
    variable where the motion is asymptotically stable and where it is
    neutrally stable (every eigenvalue but the zeros of conserved quantities
    on the imaginary axis), their ends refined by bisection between grid
    points; ``conserved`` the number of zeros discounted.

    At one point: ``eigenvalues`` (``(modes,)``), ``a`` and ``b`` the linear
    system ``x' = a x + b u`` in the variables ``state``, and ``stable``
    and ``neutral`` booleans; ``values`` is empty.
    """

    def __init__(self, fields: Mapping[str, Any]) -> None:
        self.variable: Optional[str] = fields.get("variable")
        self.state: Optional[List[str]] = fields.get("state")
        self.values: numpy.ndarray = fields.get("values", numpy.empty(0))
        self.eigenvalues: numpy.ndarray = fields["eigenvalues"]
        self.conserved: int = fields["conserved"]
        self.stable = fields["stable"]
        self.neutral = fields["neutral"]
        self.a: Optional[numpy.ndarray] = fields.get("a")
        self.b: Optional[numpy.ndarray] = fields.get("b")

    def __repr__(self) -> str:
        if self.variable is None:
            return f"Linearization(eigenvalues={self.eigenvalues}, stable={self.stable})"
        return (
            f"Linearization({self.variable} over {len(self.values)} values, "
            f"stable={self.stable}, neutral={self.neutral})"
        )


class Steady:
    """A steady motion found by ``Model.steady``.

    ``values`` maps the unknowns, every coordinate and ``dot(q)``, the inputs
    and, for a model with a planar symmetry, ``radius`` (of the circle the
    body frame's origin follows; ``inf`` when straight) to their values.
    ``eigenvalues`` are the linearization's, by descending real part, in the
    variables ``state``; ``stable`` whether the motion is asymptotically
    stable modulo the zeros of conserved quantities. ``family`` gives one
    direction per such zero, ``{entry: coefficient}``, along which the steady
    motions form a family. ``steps`` and ``residual``: the Gauss-Newton steps
    taken and the largest rate of the reduced flow left.
    """

    def __init__(self, fields: Mapping[str, Any]) -> None:
        self.values: Dict[str, float] = dict(fields["values"])
        self.eigenvalues: numpy.ndarray = fields["eigenvalues"]
        self.stable: bool = fields["stable"]
        self.state: List[str] = fields["state"]
        self.family: List[Dict[str, float]] = fields["family"]
        self.steps: int = fields["steps"]
        self.residual: float = fields["residual"]

    def __repr__(self) -> str:
        return f"Steady(values={self.values}, stable={self.stable})"


class SteadyFamily:
    """A family of steady motions followed by ``Model.steady(trace=...)``.

    ``columns`` are those of ``chaplygin steady --trace``'s ``steady.csv``
    (the traced variable first), ``data`` a row per value crossed in the
    family's order (past a fold, the values come back); ``family["v"]`` is a
    column. ``report`` names the folds, the changes of stability and why the
    trace ended.
    """

    def __init__(self, fields: Mapping[str, Any]) -> None:
        self.columns: List[str] = list(fields["columns"])
        self.data: numpy.ndarray = fields["data"]
        self.report: str = fields["report"]

    def __getitem__(self, name: str) -> numpy.ndarray:
        return self.data[:, self.columns.index(name)]

    def __repr__(self) -> str:
        return f"SteadyFamily({len(self.data)} rows of {self.columns[0]})"


class Gait:
    """What a prescribed shape loop does: ``displacements`` (``(cycles,
    3)``, each cycle's net ``(x, y, theta)`` in the body frame at its
    start) and ``trajectory`` (``t``, the coordinates, the momenta
    ``p1..pK``)."""

    def __init__(self, displacements: numpy.ndarray, trajectory: Trajectory) -> None:
        self.displacements = displacements
        self.trajectory = trajectory

    def __repr__(self) -> str:
        return f"Gait({len(self.displacements)} cycles, first {self.displacements[0]})"


class OptimalGait:
    """The shape loop that moves a model furthest from rest
    (``Model.optimal_gait``): ``laws`` (``{name: expression of t}``, as
    ``Model.gait`` takes them), ``coefficients`` (one row per shape
    coordinate: the constant, then the cosine and sine coefficient of each
    harmonic), ``efficiency`` (the displacement per unit of the loop's
    length, or per cycle), ``length``, ``displacement`` (``(x, y, theta)``
    over one cycle), ``starts`` (each refined start's efficiency) and
    ``gait``, the loop's run."""

    def __init__(self, found: Dict[str, Any], gait: Gait) -> None:
        self.laws: Dict[str, str] = dict(found["laws"])
        self.coefficients: numpy.ndarray = found["coefficients"]
        self.efficiency: float = found["efficiency"]
        self.length: float = found["length"]
        self.displacement: numpy.ndarray = found["displacement"]
        self.starts: List[float] = list(found["starts"])
        self.gait = gait

    def __repr__(self) -> str:
        return f"OptimalGait(efficiency {self.efficiency}, displacement {self.displacement})"


class _Drawing:
    """Draws rows of a model's run at the parameters ``params``: what
    ``Trajectory.animate`` calls. It pickles as the model's text and the
    parameters, so a trajectory sent between processes still animates."""

    def __init__(self, model: "Model", params: Optional[Dict[str, float]]) -> None:
        self.model = model
        self.params = params

    def __call__(self, columns: List[str], data: numpy.ndarray, fps: float) -> str:
        return self.model._native.animation(columns, data.tolist(), self.params, fps)


class Plan:
    """An optimal plan, verified (docs/INTERFACE.md section 13).

    ``plan.objective`` is the cost at the optimum, ``plan.duration`` the
    duration, ``plan.report`` the dict of ``plan.json`` (the grid, scheme,
    solver, iterations, seconds, status, the KKT residuals ``kkt``
    computed from the exact derivatives, and ``restart``, the first solve
    where the default guess was solved again nudged); ``plan.t`` the
    nodes' times, ``plan["x"]`` any column of ``plan.csv`` by name,
    ``plan.columns`` their names, and ``plan.trajectory`` the rows as a
    ``Trajectory``, so that ``plan.trajectory.animate()`` draws it. Plans
    pickle.
    """

    def __init__(self, trajectory: Trajectory, report: Dict[str, Any]) -> None:
        self.trajectory = trajectory
        self.report = report

    objective = property(lambda self: self.report["objective"], doc="The cost at the optimum.")
    duration = property(lambda self: self.report["duration"], doc="The duration T.")
    columns = property(lambda self: self.trajectory.columns, doc="The columns of plan.csv.")

    @property
    def t(self) -> numpy.ndarray:
        """The nodes' times."""
        return self.trajectory.t

    def __getitem__(self, name: str) -> numpy.ndarray:
        return self.trajectory[name]

    def __len__(self) -> int:
        return len(self.trajectory)

    def __repr__(self) -> str:
        report = self.report
        return (
            f"Plan(objective {report['objective']:.9g} over {report['duration']:g} s, "
            f"{report['nodes']} nodes, {report['scheme']})"
        )


class Estimate:
    """Parameters fitted to data, verified (docs/INTERFACE.md section 13).

    ``est.parameters`` maps each estimated parameter to its value,
    ``est.standard_errors`` to its Gauss-Newton standard error;
    ``est.residual_rms`` is the RMS of the fit's residuals over the measured
    values, ``est.iterations`` the solver's, ``est.report`` the dict of
    ``estimate.json`` (with the KKT residuals ``kkt`` computed from the exact
    derivatives). ``est.fit`` is ``fit.csv`` as a ``Trajectory`` (no
    drawing): one row per node, ``t``, every fitted coordinate and velocity
    by name, and each measured column's data as ``data(NAME)``, so
    ``est.fit["x"]`` and ``est.fit["data(x)"]`` compare. Estimates pickle.
    """

    def __init__(self, fit: Trajectory, report: Dict[str, Any]) -> None:
        self.fit = fit
        self.report = report

    parameters = property(lambda self: dict(self.report["parameters"]), doc="The estimates by name.")
    standard_errors = property(lambda self: dict(self.report["standard_errors"]), doc="Their standard errors.")
    residual_rms = property(lambda self: self.report["residual_rms"], doc="The residuals' RMS.")
    iterations = property(lambda self: self.report["iterations"], doc="The solver's iterations.")

    def __repr__(self) -> str:
        values = ", ".join(
            f"{name} = {value:.9g} +- {self.standard_errors[name]:.3g}" for name, value in self.parameters.items()
        )
        return f"Estimate({values}; residual RMS {self.residual_rms:.3g})"


class Model:
    """A model read from its text, derived exactly, its functions compiled.

    ``name``, ``coordinates``, ``velocities`` (``dot(q)``), ``inputs``,
    ``constraints``, ``holonomic``, ``momenta`` name its parts;
    ``parameters`` maps each parameter to its default value.
    """

    def __init__(self, native: Any) -> None:
        if isinstance(native, (str, bytes, os.PathLike)):
            raise TypeError(
                f"Model({native!r}): a Model is made by chaplygin.load(path_or_text) "
                "or chaplygin.builtin(name)"
            )
        self._native = native

    name = property(lambda self: self._native.name, doc="The built-in's name, or the file's path.")
    coordinates = property(lambda self: list(self._native.coordinates), doc="The coordinates q.")
    velocities = property(lambda self: list(self._native.velocities), doc="The velocities dot(q).")
    inputs = property(lambda self: list(self._native.inputs), doc="The inputs u.")
    constraints = property(lambda self: list(self._native.constraints), doc="The velocity constraints.")
    holonomic = property(lambda self: list(self._native.holonomic), doc="The configuration constraints f(q) = 0.")
    momenta = property(lambda self: list(self._native.momenta), doc="The reduced momenta alpha.")
    parameters = property(lambda self: dict(self._native.parameters), doc="The parameters' default values.")
    engine = property(lambda self: self._native.engine, doc='What runs the functions: "jit" or "interpret".')
    report = property(lambda self: self._native.report, doc="The derivation report.")

    def __repr__(self) -> str:
        return f"Model({self.name!r}, coordinates={self.coordinates}, engine={self.engine!r})"

    def __reduce__(self) -> Tuple[Any, Tuple[Optional[str], str, str]]:
        """Pickles as the model's text (or built-in name) and engine: a
        worker process rebuilds it (derived and compiled once per process)."""
        return (_rebuilt, self._state())

    def _state(self) -> Tuple[Optional[str], str, str]:
        return (self._native.builtin_name, self._native.text, self.engine)

    def simulate(
        self,
        t_end: float = 30.0,
        dt: float = 0.01,
        initial: Optional[Mapping[str, Value]] = None,
        params: Optional[Mapping[str, float]] = None,
        inputs: Optional[Mapping[str, Value]] = None,
        formulation: str = "reduced",
        integrator: Optional[str] = None,
        stop_when: Optional[str] = None,
        controller: str = "none",
        rtol: float = 1e-8,
        atol: float = 1e-8,
        fixed_step: bool = False,
        prescribe: Optional[Mapping[str, Value]] = None,
    ) -> Trajectory:
        """Simulates the model from ``t = 0`` to ``t_end``, recording every
        ``dt``.

        ``initial`` gives coordinates and velocities ``dot(q)`` (numbers, or
        expressions of the parameters such as ``"-5/rR"``; velocities not
        given are solved from the constraints; without any, the model's
        default motion). ``params`` overrides parameters. ``inputs`` gives
        each input a law: a number or an expression of ``t``, the
        parameters, the coordinates and velocities (``"-10*phi-2*dot(phi)"``).
        ``formulation`` is ``"reduced"``, ``"lagrange"`` or ``"momentum"``;
        ``integrator`` ``"rk4"``, ``"dopri5"``, ``"midpoint"`` or
        ``"discrete-gradient"`` (default: the discrete gradient for the
        reduced form, the midpoint rule otherwise); ``stop_when`` one
        comparison (``"abs(phi) > 1"``) that ends the run where it first
        holds; ``controller="energy"`` closes a model with a steering angle
        ``phi`` and two inputs, the torso's and the wheels' (the snakeboard,
        from any of its declarations), with Duindam and Stramigioli's energy
        controller. ``prescribe`` makes coordinates follow laws of ``t``
        and the parameters exactly (``{"phi": "0.2*sin(t)"}``): each starts
        on its law, and the force that keeps it there is the column
        ``force(NAME)``.

        Every integrator's step follows the tolerances ``rtol`` and ``atol``
        of its local error, no step longer than ``dt``; ``fixed_step=True``
        takes steps of exactly ``dt`` (not with dopri5). A run whose energy
        drift (without inputs) or constraint residual exceeds what the
        tolerance allows issues a ``RuntimeWarning`` naming it (the
        summary's ``warnings``); ``warnings.simplefilter("error",
        RuntimeWarning)`` makes it an exception.

        Raises ``SimulationError`` (with ``t``, ``state`` and the rows
        before it as ``trajectory``) for a run that stops early, and
        ``ValueError`` for input that does not read.
        """
        run = self._native.simulate(
            float(t_end),
            float(dt),
            _dict(initial),
            _dict(params),
            _dict(inputs),
            formulation,
            integrator,
            stop_when,
            controller,
            float(rtol),
            float(atol),
            bool(fixed_step),
            _dict(prescribe),
        )
        tracks = run["tracks"]
        trajectory = Trajectory(
            run["columns"],
            run["data"],
            run["summary"],
            Trajectory(tracks[0], tracks[1], None) if tracks is not None else None,
            _Drawing(self, _dict(params)),
        )
        failure = run["failure"]
        if failure is not None:
            raise SimulationError(failure["message"], failure["t"], failure["state"], trajectory)
        for warning in run["summary"]["warnings"]:
            warnings.warn(warning.removeprefix("warning: "), RuntimeWarning, stacklevel=2)
        return trajectory

    def plan(
        self,
        duration: float,
        nodes: int,
        start: Optional[Mapping[str, Value]] = None,
        goal: Optional[Mapping[str, Value]] = None,
        minimize: Optional[str] = None,
        bounds: Optional[Mapping[str, Tuple[Optional[Value], Optional[Value]]]] = None,
        scheme: str = "midpoint",
        params: Optional[Mapping[str, float]] = None,
        tol: float = 1e-8,
        final_cost: Optional[str] = None,
        free_duration: bool = False,
        guess: Optional[Union[str, "os.PathLike[str]"]] = None,
        formulation: str = "lagrange",
    ) -> Plan:
        """The inputs and trajectory over ``[0, duration]`` that minimize
        ``minimize`` (an expression of ``t``, the coordinates, velocities
        ``dot(q)``, inputs and parameters integrated over time; by default
        the sum of the inputs squared), by direct collocation on ``nodes``
        nodes with ``scheme`` (``"backward-euler"``, ``"midpoint"`` or
        ``"hermite-simpson"``), as ``chaplygin plan`` finds them.

        ``start`` and ``goal`` fix coordinates and velocities at ``t = 0``
        and ``t = duration`` (numbers or expressions of the parameters);
        what they do not name is free. ``bounds`` maps an input, coordinate
        or velocity to ``(lo, hi)`` at every node (``None`` for no bound on
        that side). ``params`` overrides parameters. ``tol`` is the solver's
        tolerance; the KKT residuals are verified to 100 times it.
        ``final_cost`` adds a cost at the end (an expression of ``t``, the
        final coordinates and velocities, and the parameters).
        ``free_duration=True`` makes the duration an unknown, ``duration``
        its first guess. ``guess`` is a CSV file with ``t`` and any of
        ``plan.csv``'s columns to start from; without it, a solve from the
        default guess that ends unverified is solved again once with the
        inputs nudged, and ``report["restart"]`` records the first solve.
        ``formulation`` is
        ``"lagrange"`` (the nodes hold ``q`` and ``dot(q)``), ``"reduced"``
        (they hold ``q`` and the reduced momenta, in chart 0) or
        ``"momentum"`` (``q``, the shape velocities and the momenta ``p``),
        as ``--formulation`` says.

        Raises ``ValueError`` for bad input (an unknown name, a bound with
        lo > hi, a start off the constraints) and for an answer that is not
        a verified optimum (the message says why, with the residuals);
        ``KeyboardInterrupt`` where Ctrl-C stops the solve.
        """
        given = _dict(params)
        planned = self._native.plan(
            float(duration),
            int(nodes),
            scheme,
            _dict(start),
            _dict(goal),
            minimize,
            None if bounds is None else {name: _bound(name, ends) for name, ends in bounds.items()},
            given,
            float(tol),
            final_cost,
            bool(free_duration),
            None if guess is None else os.fspath(guess),
            formulation,
        )
        trajectory = Trajectory(planned["columns"], planned["data"], None, None, _Drawing(self, given))
        return Plan(trajectory, json.loads(planned["report"]))

    def identify(
        self,
        data: Any,
        estimate: Union[Mapping[str, Optional[float]], Sequence[str]],
        nodes: Optional[int] = None,
        scheme: str = "midpoint",
        params: Optional[Mapping[str, float]] = None,
        tol: float = 1e-8,
    ) -> Estimate:
        """The parameters ``estimate`` names that fit the model's motion to
        ``data``, as ``chaplygin identify`` finds them: least squares over
        the measured values, the model's equations as collocation
        constraints by ``scheme`` at the data rows' own times, evenly
        spaced or not, or with ``nodes`` on that many nodes evenly spread
        over the data's time span, the data interpolated.

        ``data`` is a table with ``t``, any coordinates and velocities
        ``dot(q)`` by name (measured) and the inputs applied, by name: a
        dict of equally long arrays, a pandas ``DataFrame``, a
        ``Trajectory`` (``simulate``'s; its ``energy`` and residual columns
        are ignored) or the path of a CSV file. ``estimate`` maps each
        parameter to estimate to its first guess (``None``: its value), or
        lists their names. ``params`` sets other parameters. ``tol`` is the
        solver's tolerance; the KKT residuals are verified to 100 times it.

        Raises ``ValueError`` for bad input (an unknown parameter, a column
        that is not the model's, too few rows) and for an answer that is
        not a verified optimum; ``KeyboardInterrupt`` where Ctrl-C stops
        the solve.
        """
        guesses = dict(estimate) if isinstance(estimate, Mapping) else dict.fromkeys(estimate)
        named = [(str(name), None if guess is None else float(guess)) for name, guess in guesses.items()]
        source, table = _measured(data)
        found = self._native.identify(
            source, table, named, None if nodes is None else int(nodes), scheme, _dict(params), float(tol)
        )
        return Estimate(Trajectory(found["columns"], found["data"], None), json.loads(found["report"]))

    def linearize(
        self,
        at: Optional[Mapping[str, Value]] = None,
        sweep: Optional[Tuple[str, ArrayLike]] = None,
        params: Optional[Mapping[str, float]] = None,
    ) -> Linearization:
        """Linearizes about the steady motion ``at`` (coordinates and
        velocities, numbers or expressions of the parameters and of the
        sweep variable), with the symmetry reduced and the constraints
        eliminated; over ``sweep=(variable, values)``, at each value."""
        if sweep is not None:
            variable, values = sweep
            sweep = (str(variable), values)
        return Linearization(self._native.linearize(_dict(at), _dict(params), sweep))

    def steady(
        self,
        at: Optional[Mapping[str, Value]] = None,
        inputs: Optional[Mapping[str, Value]] = None,
        solve: Sequence[str] = (),
        guess: Optional[Mapping[str, float]] = None,
        params: Optional[Mapping[str, float]] = None,
        trace: Optional[Tuple[str, ArrayLike]] = None,
    ) -> Union[Steady, SteadyFamily]:
        """Finds a steady motion, as ``chaplygin steady``: ``at`` (coordinates
        and velocities) and ``inputs`` are numbers or expressions of the
        parameters and the unknowns; ``solve`` names the unknowns (such
        variables, or coordinates ``at`` leaves free), found by Gauss-Newton
        on the exact Jacobian from ``guess`` (0 where not given). Raises
        ``ValueError`` in one line where there is none near the guess. With
        ``trace=(variable, values)`` it follows the family over the values
        (evenly spaced, increasing) from the first solution, by
        pseudo-arclength continuation, and returns a ``SteadyFamily``."""
        if trace is not None:
            variable, values = trace
            trace = (str(variable), values)
        found = self._native.steady(
            _dict(at), _dict(inputs), [str(name) for name in solve], _dict(guess), _dict(params), trace
        )
        return Steady(found) if trace is None else SteadyFamily(found)

    def gait(
        self,
        cycle: Mapping[str, Value],
        period: float,
        cycles: int = 1,
        steps: int = 2000,
        params: Optional[Mapping[str, float]] = None,
        initial: Optional[Mapping[str, float]] = None,
    ) -> "Gait":
        """Runs a prescribed periodic shape trajectory: ``cycle`` gives each
        shape coordinate (every coordinate the symmetry does not move) a law,
        an expression of ``t`` and the parameters with period ``period``;
        the group follows from the momentum equation and the reconstruction,
        from zero momentum unless ``initial`` gives ``{"p1": ...}``. Returns
        a ``Gait``: ``displacements`` (one row ``(x, y, theta)`` per cycle, in
        the body frame at the cycle's start) and the ``trajectory``."""
        run = self._native.gait(
            dict(cycle), float(period), int(cycles), int(steps), _dict(params), _dict(initial)
        )
        return Gait(run["displacements"], Trajectory(run["columns"], run["data"], None))

    def optimal_gait(
        self,
        direction: str = "forward",
        harmonics: int = 1,
        cost: str = "length",
        period: float = 2.0 * math.pi,
        starts: int = 8,
        margin: float = 0.25,
        limit: float = math.pi,
        steps: int = 400,
        params: Optional[Mapping[str, float]] = None,
    ) -> OptimalGait:
        """The loop of ``harmonics`` Fourier harmonics per shape coordinate
        that moves the model furthest ``direction`` from rest
        (``"forward"``, ``"lateral"`` or ``"rotate"``) per unit of its length
        in the shape coordinates (``cost="length"``) or per cycle
        (``cost="none"``), as ``chaplygin gait --optimize``: exact gradients,
        L-BFGS from the best ``starts`` of a survey of random loops, loops
        keeping the connection's divisor above ``margin`` of its largest
        magnitude and every shape coordinate within ``[-limit, limit]``."""
        found = self._native.optimal_gait(
            str(direction),
            int(harmonics),
            str(cost),
            float(period),
            int(starts),
            float(margin),
            float(limit),
            int(steps),
            _dict(params),
        )
        run = Gait(found["displacements"], Trajectory(found["columns"], found["data"], None))
        return OptimalGait(found, run)

    def rhs(
        self,
        formulation: str = "reduced",
        params: Optional[Mapping[str, float]] = None,
        inputs: Optional[Mapping[str, Value]] = None,
    ) -> Rhs:
        """The right-hand side ``f(t, x, u=None)`` of a formulation, with
        ``f.jacobian(t, x, u=None)``, ``f.state`` and
        ``f.initial_state(initial)``; the inputs follow the ``inputs`` laws
        unless ``u`` is given."""
        return self._native.rhs(formulation, _dict(params), _dict(inputs))

    def acceleration(
        self,
        q: ArrayLike,
        qdot: ArrayLike,
        u: Optional[ArrayLike] = None,
    ) -> Tuple[numpy.ndarray, numpy.ndarray]:
        """The Lagrange-d'Alembert accelerations and constraint multipliers
        ``(qddot, lambda)`` at ``(q, qdot)`` under the inputs ``u`` (zero if
        ``None``)."""
        return self._native.acceleration(q, qdot, u)

    def document(self, format: str = "text") -> str:
        """The derivation document: ``"text"``, ``"latex"`` or ``"json"``."""
        return self._native.document(format)

    def sympy(self) -> Dict[str, Any]:
        """The derived matrices as SymPy objects: ``mass_matrix``,
        ``constraint_matrix``, ``kinetic_energy``, ``potential_energy``, and
        the reduced form's ``structure_matrix`` and ``hamiltonian`` where it
        is derived exactly (not for a model as large as the bicycle, whose
        reduced form is structured in the generated code).
        Coordinates and parameters are symbols of their own names, a
        velocity ``dot(q)`` is ``Symbol("dot_q")``."""
        return derived_expressions(self.document("json"))


def _dict(values: Optional[Mapping[str, Any]]) -> Optional[Dict[str, Any]]:
    return None if values is None else dict(values)


def _measured(data: Any) -> Tuple[str, Optional[Tuple[List[str], List[List[float]]]]]:
    """``Model.identify``'s ``data`` as the native call takes it: the name
    messages give it (a CSV's path), and its ``(columns, rows)`` unless it
    is a file."""
    if isinstance(data, (str, os.PathLike)):
        return os.fspath(data), None
    if isinstance(data, Trajectory):
        return "<Trajectory>", (list(data.columns), numpy.asarray(data.data, dtype=float).tolist())
    if isinstance(data, Mapping):
        columns = [str(name) for name in data]
        values = [numpy.asarray(column, dtype=float).ravel() for column in data.values()]
        lengths = {len(column) for column in values}
        if len(lengths) > 1:
            raise ValueError(f"data: its columns differ in length ({', '.join(map(str, sorted(lengths)))} rows)")
        rows = numpy.column_stack(values).tolist() if values else []
        return "<dict>", (columns, rows)
    if hasattr(data, "columns") and hasattr(data, "to_numpy"):
        rows = numpy.asarray(data.to_numpy(dtype=float)).tolist()
        return "<DataFrame>", ([str(name) for name in data.columns], rows)
    raise ValueError(
        f"data: give a dict of arrays, a pandas DataFrame, a Trajectory or a CSV file's path, not {type(data).__name__}"
    )


def _bound(name: str, ends: Tuple[Optional[Value], Optional[Value]]) -> str:
    """``(lo, hi)`` as ``chaplygin plan --bound``'s ``LO:HI``, a ``None``
    end left empty, a number written so that it reads back exactly."""
    try:
        lo, hi = ends
    except (TypeError, ValueError):
        raise ValueError(f"bounds[{name!r}]: give (lo, hi), None for an open end; got {ends!r}") from None

    def end(value: Optional[Value]) -> str:
        if value is None:
            return ""
        return value if isinstance(value, str) else repr(float(value))

    return f"{end(lo)}:{end(hi)}"


@functools.lru_cache(maxsize=8)
def _rebuilt(builtin_name: Optional[str], text: str, engine: str) -> Model:
    """The model of a pickled state, derived and compiled once per process."""
    if builtin_name is not None:
        return builtin(builtin_name, engine)
    return load(text, engine)


class DesignMap:
    """The self-stable speeds of a steady motion over a grid of parameters.

    ``params`` maps each parameter varied to its grid values (in the order
    given); ``shape`` is their lengths. Per design point (arrays of that
    shape): ``stable_from`` and ``stable_to`` the first stable interval's
    ends (NaN where there is none); ``intervals`` (nested lists) every
    stable interval ``(from, to)``; ``changes`` each ``(speed, before,
    after)`` where the number of unstable modes changes; ``failures``
    ``None`` or why the point could not be linearized. Interval ends and
    changes are refined by bisection between the speed grid's points.
    """

    def __init__(self, params: Dict[str, numpy.ndarray], points: List[Dict[str, Any]]) -> None:
        self.params = params
        self.shape = tuple(len(values) for values in params.values())
        self.intervals = _nested([list(map(tuple, p["intervals"])) for p in points], self.shape)
        self.changes = _nested([list(map(tuple, p["changes"])) for p in points], self.shape)
        self.failures = _nested([p["failure"] for p in points], self.shape)
        ends = [p["intervals"][0] if p["intervals"] else (math.nan, math.nan) for p in points]
        self.stable_from = numpy.array([e[0] for e in ends]).reshape(self.shape)
        self.stable_to = numpy.array([e[1] for e in ends]).reshape(self.shape)

    def __repr__(self) -> str:
        stable = int(numpy.count_nonzero(~numpy.isnan(self.stable_from)))
        return f"DesignMap({self.shape} design points over {list(self.params)}, {stable} self-stable)"


def _nested(flat: List[Any], shape: Tuple[int, ...]) -> List[Any]:
    """The row-major list ``flat`` as nested lists of ``shape``."""
    if len(shape) <= 1:
        return list(flat)
    step = len(flat) // shape[0]
    return [_nested(flat[i * step : (i + 1) * step], shape[1:]) for i in range(shape[0])]


def design_map(
    model: Model,
    speed: Tuple[str, ArrayLike],
    params: Mapping[str, Any],
    at: Optional[Mapping[str, Value]] = None,
    executor: Optional[Executor] = None,
    jobs: Optional[int] = None,
    chunks: int = 64,
) -> DesignMap:
    """At every design point of the grid of ``params`` (``{name: values}``
    for each parameter varied, ``{name: value}`` for one held at a value;
    the last varied parameter fastest), the speeds ``speed = (variable,
    values)`` at which the steady motion ``at`` (as for
    ``Model.linearize``) is asymptotically stable, as ``chaplygin map``
    finds them.

    With ``executor=None`` every design point runs here, on ``jobs``
    threads (every core by default) with the GIL released. With any
    ``concurrent.futures.Executor`` (``dask.distributed.Client(...)
    .get_executor()``, a ``ProcessPoolExecutor``) the points go out in
    about ``chunks`` tasks, each rebuilding the model from its pickled text
    once per worker process and running on one thread; the result is the
    same, bit for bit."""
    variable, values = speed
    speed = (str(variable), numpy.asarray(values, dtype=float))
    fixed = {name: float(v) for name, v in params.items() if numpy.ndim(v) == 0}
    varied = {name: numpy.asarray(v, dtype=float) for name, v in params.items() if numpy.ndim(v) != 0}
    names = list(varied)
    if not names:
        raise ValueError("params: vary at least one parameter ({name: values})")
    grid = numpy.array(numpy.meshgrid(*varied.values(), indexing="ij")).reshape(len(names), -1).T
    request = (_dict(at), fixed, speed, names)
    if executor is None:
        points = model._native.design_points(*request, grid, jobs)
    else:
        size = max(1, -(-len(grid) // max(1, chunks)))
        parts = [grid[i : i + size] for i in range(0, len(grid), size)]
        tasks = [executor.submit(_design_points, model._state(), request, part) for part in parts]
        points = [point for task in tasks for point in task.result()]
    return DesignMap(varied, list(points))


def plans(
    model: Model,
    requests: Sequence[Mapping[str, Any]],
    executor: Optional[Executor] = None,
) -> List[Plan]:
    """The plans ``requests`` ask of ``model``, each a dict of
    ``Model.plan``'s keyword arguments (a grid of durations, parameters or
    goals), in their order.

    With ``executor=None`` they are solved here, one after the other. With
    any ``concurrent.futures.Executor`` (``dask.distributed.Client(...)
    .get_executor()``, a ``ProcessPoolExecutor``) each is one task, the
    model rebuilt from its pickled text once per worker process, as
    ``design_map`` runs; the plans come back pickled, and are the same.
    A request that fails raises its error here."""
    return _solved_all(model, "plan", requests, executor)


def estimates(
    model: Model,
    requests: Sequence[Mapping[str, Any]],
    executor: Optional[Executor] = None,
) -> List[Estimate]:
    """The estimates ``requests`` ask of ``model``, each a dict of
    ``Model.identify``'s keyword arguments (data sets, first guesses or
    grids), in their order, here or on ``executor`` as ``plans`` solves
    plans. The data go to the workers pickled (a path is read there)."""
    return _solved_all(model, "identify", requests, executor)


def _solved_all(model: Model, method: str, requests: Sequence[Mapping[str, Any]], executor: Optional[Executor]) -> List[Any]:
    """``model.method(**request)`` for each request, in their order: here,
    or each a task on ``executor``."""
    requests = [dict(request) for request in requests]
    if executor is None:
        return [getattr(model, method)(**request) for request in requests]
    tasks = [executor.submit(_solved, model._state(), method, request) for request in requests]
    return [task.result() for task in tasks]


def _solved(state: Tuple[Optional[str], str, str], method: str, request: Dict[str, Any]) -> Any:
    """One executor task: a plan or estimate of the model rebuilt from
    ``state`` (once per process)."""
    return getattr(_rebuilt(*state), method)(**request)


def _design_points(state: Tuple[Optional[str], str, str], request: Any, points: numpy.ndarray) -> List[Dict[str, Any]]:
    """One executor task: ``points`` of a design map on one thread, the
    model rebuilt from ``state`` (once per process)."""
    return list(_rebuilt(*state)._native.design_points(*request, points, 1))
