"""The snakeboard's rest-to-rest plan in opty 1.5 with Ipopt (cyipopt).

The maneuver of `PROBLEM`: from rest at the origin to rest at a pose
ahead, to the side and turned, in a fixed time, minimizing the integral of
`u_torso^2 + u_wheels^2`, within bounds on the inputs and the steering
angle. `plan_peer.py` gives Chaplygin the same problem through
`chaplygin plan snakeboard`.

The dynamics are SymPy mechanics' (`sympy_peer.snakeboard`, MATH.md 3.1,
Chaplygin's default parameters): `KanesMethod` with the independent speeds
`(dot(x), dot(psi), dot(phi))`, whose full form `M(q) x' = F(q, u, tau)`
in the ten states `x = (q, u)` (`u` the independent speeds, then the
dependent `dot(y), dot(theta)`) holds the kinematics `q' = u`, the three
dynamic equations and the two velocity constraints differentiated once.
opty collocates `M x' - F = 0` by backward Euler
`M(x_{i+1}) (x_{i+1} - x_i)/h = F(x_{i+1}, tau_{i+1})` or the midpoint
rule (state and inputs averaged over the interval). Its objective and
gradient are written by hand, as opty asks: backward Euler
`h sum_i |tau_i|^2` over all nodes (the first node's inputs, which the
dynamics do not read, go to zero), the midpoint rule the trapezoidal
`h sum_i w_i |tau_i|^2`, `w = (1/2, 1, ..., 1, 1/2)`. Both tend to the
integral as `h -> 0`.

Usage: python opty_snakeboard.py NODES [midpoint|backward-euler] [cython|numpy]
prints `OPTY {...}`, the result of `solve` as JSON.
"""

import json
import sys
import time

import numpy as np
import sympy as sp
from opty import Problem
from sympy.physics.mechanics import KanesMethod, dynamicsymbols

from sympy_peer import snakeboard

# The maneuver, in Chaplygin's names: from rest with the wheels turned to
# rest at a pose ahead, to the left and turned, the torso and wheels free.
# Every coordinate and velocity is given at the start; at the goal the pose
# and the independent velocities (with them at rest the constraints stop
# the board).
PROBLEM = dict(
    duration=4.0,
    start={'x': 0.0, 'y': 0.0, 'theta': 0.0, 'psi': 0.0, 'phi': 0.3,
           'dot(x)': 0.0, 'dot(y)': 0.0, 'dot(theta)': 0.0, 'dot(psi)': 0.0,
           'dot(phi)': 0.0},
    goal={'x': 0.5, 'y': 0.08, 'theta': 0.3, 'dot(x)': 0.0, 'dot(psi)': 0.0, 'dot(phi)': 0.0},
    bounds={'phi': (-1.0, 1.0), 'u_torso': (-10.0, 10.0), 'u_wheels': (-10.0, 10.0)},
)

COORDINATES = ['x', 'y', 'theta', 'psi', 'phi']
INPUTS = ['u_torso', 'u_wheels']
# opty's names for the schemes.
SCHEMES = {'midpoint': 'midpoint', 'backward-euler': 'backward euler'}


def equations():
    """`M x' - F` of the snakeboard, its states `(q, u)`, and a map from
    Chaplygin's names to its states and inputs."""
    model = snakeboard()
    kane = KanesMethod(model['frame'], q_ind=model['q'], u_ind=model['independent'],
                       u_dependent=model['dependent'], kd_eqs=model['kinematics'],
                       velocity_constraints=model['constraints'])
    kane.kanes_equations(model['bodies'], model['loads'])
    inputs = [dynamicsymbols(name) for name in INPUTS]
    to_trajectories = dict(zip(model['inputs'], inputs))
    states = list(kane.q) + list(kane.u)
    t = dynamicsymbols._t
    rates = sp.Matrix([state.diff(t) for state in states])
    eom = (kane.mass_matrix_full * rates - kane.forcing_full).xreplace(to_trajectories)
    names = dict(zip(COORDINATES, model['q']))
    names.update({f'dot({c})': u for c, u in zip(COORDINATES, model['u'])})
    names.update(dict(zip(INPUTS, inputs)))
    return eom, states, names


def input_slices(problem, nodes):
    """Where each input's values sit in opty's free vector."""
    collocator = problem.collocator
    first = collocator.num_states * nodes
    return [slice(first + k * nodes, first + (k + 1) * nodes)
            for k, _ in enumerate(collocator.unknown_input_trajectories)]


def quadrature_weights(nodes, step, scheme):
    """The objective's weight of each node's inputs squared."""
    weights = np.full(nodes, step)
    if scheme == 'midpoint':
        weights[[0, -1]] = step / 2
    return weights


def build(nodes, scheme, problem=PROBLEM, backend='cython'):
    """opty's `Problem` for `problem` on `nodes` nodes, and its first guess:
    the start and goal interpolated, else the one given, else 0 (as
    `chaplygin plan` guesses)."""
    eom, states, names = equations()
    t = dynamicsymbols._t
    duration = problem['duration']
    step = duration / (nodes - 1)
    instance = [names[n].subs(t, 0.0) - v for n, v in problem['start'].items()]
    instance += [names[n].subs(t, duration) - v for n, v in problem['goal'].items()]
    bounds = {names[n]: bound for n, bound in problem['bounds'].items()}
    weights = quadrature_weights(nodes, step, scheme)
    slices = []

    def objective(free):
        return sum(weights @ free[s] ** 2 for s in slices)

    def gradient(free):
        grad = np.zeros_like(free)
        for s in slices:
            grad[s] = 2.0 * weights * free[s]
        return grad

    opty_problem = Problem(objective, gradient, eom, states, nodes, step,
                           instance_constraints=instance, bounds=bounds,
                           integration_method=SCHEMES[scheme], time_symbol=t,
                           backend=backend)
    slices.extend(input_slices(opty_problem, nodes))
    return opty_problem, first_guess(states, names, nodes, problem)


def first_guess(states, names, nodes, problem):
    """States interpolated from start to goal, inputs zero."""
    fraction = np.linspace(0.0, 1.0, nodes)
    guess = np.zeros(len(states) * nodes + len(INPUTS) * nodes)
    by_state = {names[n]: n for n in names}
    for k, state in enumerate(states):
        name = by_state[state]
        start, goal = problem['start'].get(name), problem['goal'].get(name)
        ends = [v for v in (start, goal) if v is not None]
        if len(ends) == 2:
            guess[k * nodes:(k + 1) * nodes] = start + fraction * (goal - start)
        elif ends:
            guess[k * nodes:(k + 1) * nodes] = ends[0]
    return guess


def solve(nodes, scheme, tol=1e-8, problem=PROBLEM, backend='cython'):
    """opty's optimum: objective, Ipopt's iterations and status, and the
    seconds of the whole solve (the equations, opty's code generation, and
    with the `cython` backend its compilation, and Ipopt)."""
    started = time.perf_counter()
    opty_problem, guess = build(nodes, scheme, problem, backend)
    built = time.perf_counter()
    opty_problem.add_option('tol', tol)
    opty_problem.add_option('max_iter', 3000)
    opty_problem.add_option('print_level', 0)
    _, info = opty_problem.solve(guess)
    finished = time.perf_counter()
    status = info['status_msg']
    return dict(objective=float(info['obj_val']),
                iterations=len(opty_problem.obj_value) - 1,
                status=status.decode() if isinstance(status, bytes) else str(status),
                succeeded=info['status'] in (0, 1),
                seconds=finished - started, build_seconds=built - started,
                solve_seconds=finished - built)


def main():
    nodes = int(sys.argv[1]) if len(sys.argv) > 1 else 21
    scheme = sys.argv[2] if len(sys.argv) > 2 else 'midpoint'
    backend = sys.argv[3] if len(sys.argv) > 3 else 'cython'
    result = dict(nodes=nodes, scheme=scheme, backend=backend,
                  **solve(nodes, scheme, backend=backend))
    print('OPTY ' + json.dumps(result), flush=True)


if __name__ == '__main__':
    main()
