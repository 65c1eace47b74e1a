"""Type stubs of the native module `chaplygin._chaplygin` (the Python
layer, `chaplygin/__init__.py`, wraps it)."""

from typing import Any, Dict, List, Optional, Tuple

import numpy
from numpy.typing import ArrayLike

def builtins() -> List[str]: ...
def builtin(name: str, engine: str = "jit") -> Model: ...
def load(path_or_text: str, engine: str = "jit") -> Model: ...

class Model:
    name: str
    coordinates: List[str]
    velocities: List[str]
    inputs: List[str]
    constraints: List[str]
    holonomic: List[str]
    momenta: List[str]
    parameters: Dict[str, float]
    engine: str
    report: str
    builtin_name: Optional[str]
    text: str
    def simulate(
        self,
        t_end: float,
        dt: float,
        initial: Optional[Dict[str, Any]],
        params: Optional[Dict[str, float]],
        inputs: Optional[Dict[str, Any]],
        formulation: str,
        integrator: Optional[str],
        stop_when: Optional[str],
        controller: str,
        rtol: float,
        atol: float,
        fixed_step: bool,
        prescribe: Optional[Dict[str, Any]],
    ) -> Dict[str, Any]: ...
    def animation(
        self,
        columns: List[str],
        rows: List[List[float]],
        params: Optional[Dict[str, float]],
        fps: float,
    ) -> str: ...
    def linearize(
        self,
        at: Optional[Dict[str, Any]],
        params: Optional[Dict[str, float]],
        sweep: Optional[Tuple[str, ArrayLike]],
    ) -> Dict[str, Any]: ...
    def steady(
        self,
        at: Optional[Dict[str, Any]],
        inputs: Optional[Dict[str, Any]],
        solve: List[str],
        guess: Optional[Dict[str, float]],
        params: Optional[Dict[str, float]],
        trace: Optional[Tuple[str, ArrayLike]],
    ) -> Dict[str, Any]: ...
    def gait(
        self,
        cycle: Dict[str, Any],
        period: float,
        cycles: int,
        steps: int,
        params: Optional[Dict[str, float]],
        initial: Optional[Dict[str, float]],
    ) -> Dict[str, Any]: ...
    def optimal_gait(
        self,
        direction: str,
        harmonics: int,
        cost: str,
        period: float,
        starts: int,
        margin: float,
        limit: float,
        steps: int,
        params: Optional[Dict[str, float]],
    ) -> Dict[str, Any]: ...
    def rhs(
        self,
        formulation: str,
        params: Optional[Dict[str, float]],
        inputs: Optional[Dict[str, Any]],
    ) -> Rhs: ...
    def acceleration(
        self, q: ArrayLike, qdot: ArrayLike, u: Optional[ArrayLike] = None
    ) -> Tuple[numpy.ndarray, numpy.ndarray]: ...
    def design_points(
        self,
        at: Optional[Dict[str, Any]],
        params: Optional[Dict[str, float]],
        speed: Tuple[str, ArrayLike],
        names: List[str],
        points: ArrayLike,
        jobs: Optional[int],
    ) -> List[Dict[str, Any]]: ...
    def plan(
        self,
        duration: float,
        nodes: int,
        scheme: str,
        start: Optional[Dict[str, Any]],
        goal: Optional[Dict[str, Any]],
        minimize: Optional[str],
        bounds: Optional[Dict[str, str]],
        params: Optional[Dict[str, float]],
        tol: float,
        final_cost: Optional[str],
        free_duration: bool,
        guess: Optional[str],
    ) -> Dict[str, Any]: ...
    def identify(
        self,
        data: str,
        table: Optional[Tuple[List[str], List[List[float]]]],
        estimate: List[Tuple[str, Optional[float]]],
        nodes: Optional[int],
        scheme: str,
        params: Optional[Dict[str, float]],
        tol: float,
    ) -> Dict[str, Any]: ...
    def document(self, format: str = "text") -> str: ...

class Rhs:
    """The right-hand side `f(t, x, u=None)` of one formulation of a model."""

    state: List[str]
    def __call__(self, t: float, x: ArrayLike, u: Optional[ArrayLike] = None) -> numpy.ndarray: ...
    def jacobian(self, t: float, x: ArrayLike, u: Optional[ArrayLike] = None) -> numpy.ndarray: ...
    def energy(self, x: ArrayLike) -> float: ...
    def initial_state(self, initial: Optional[Dict[str, Any]] = None) -> numpy.ndarray: ...
