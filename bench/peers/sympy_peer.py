"""SymPy mechanics (KanesMethod with velocity constraints) on the snakeboard
and the N-link wheeled snake, timed and counted like Chaplygin.

For each model: the derivation time (bodies, loads and constraints to
`kanes_equations`, then the explicit accelerations `M^-1 f` by `LUsolve`),
the operation count of `sympy.cse` of those accelerations (counted with
`sympy.count_ops`, see README.md), and the per-call time of the `lambdify`d
accelerations (best of several batches).

Parameters are Chaplygin's defaults: snakeboard m = 1, r = 0.5, Jt = 0.3,
Jw = 0.05; snake m = 1, l = 0.6, j = 0.03.

Usage: python sympy_peer.py [largest N]   (default 3)
"""

import sys
import time
import timeit

import sympy as sp
from sympy.physics.mechanics import (
    KanesMethod, Point, ReferenceFrame, RigidBody, dynamicsymbols, inertia,
)


def count(replacements, reduced):
    """Operations of a cse result: count_ops of every replacement and output."""
    return sum(sp.count_ops(e) for _, e in replacements) + sum(
        sp.count_ops(e) for e in reduced)


def body(name, point, frame, mass, moment):
    return RigidBody(name, point, frame, mass, (inertia(frame, 0, 0, moment), point))


def snakeboard():
    """Snakeboard of MATH.md 3.1: a point mass m at (x, y), the board's
    inertia m r^2 turning with theta, the torso Jt with theta + psi, the
    wheels Jw with phi; torques u1 on psi (reaction on the board), u2 on phi."""
    q = dynamicsymbols('x y theta psi phi')
    u = dynamicsymbols('ux uy utheta upsi uphi')
    x, y, th, psi, phi = q
    m, r, jt, jw = 1, sp.Rational(1, 2), sp.Rational(3, 10), sp.Rational(1, 20)
    u1, u2 = sp.symbols('u1 u2')
    n = ReferenceFrame('N')
    board = n.orientnew('B', 'Axis', [th, n.z])
    torso = board.orientnew('T', 'Axis', [psi, board.z])
    wheels = n.orientnew('W', 'Axis', [phi, n.z])
    board.set_ang_vel(n, u[2] * n.z)
    torso.set_ang_vel(n, (u[2] + u[3]) * n.z)
    wheels.set_ang_vel(n, u[4] * n.z)
    centre = Point('P')
    centre.set_vel(n, u[0] * n.x + u[1] * n.y)
    bodies = [
        body('board', centre, board, m, m * r**2),
        body('torso', centre, torso, 0, jt),
        body('wheels', centre, wheels, 0, jw),
    ]
    loads = [(torso, u1 * n.z), (board, -u1 * n.z), (wheels, u2 * n.z)]
    constraints = [
        -sp.sin(th + phi) * u[0] + sp.cos(th + phi) * u[1] + r * sp.cos(phi) * u[2],
        -sp.sin(th - phi) * u[0] + sp.cos(th - phi) * u[1] - r * sp.cos(phi) * u[2],
    ]
    kinematics = [sp.diff(qi, sp.Symbol('t')) - ui for qi, ui in zip(q, u)]
    return dict(q=q, u=u, independent=[u[0], u[3], u[4]], dependent=[u[1], u[2]],
                kinematics=kinematics, constraints=constraints, frame=n,
                bodies=bodies, loads=loads, inputs=[u1, u2])


def snake(links):
    """The N-link wheeled snake of models/src/snake.rs."""
    t = sp.Symbol('t')
    headings = dynamicsymbols(' '.join(f'theta{i}' for i in range(1, links + 1)))
    headings = headings if isinstance(headings, list) else [headings]
    q = list(dynamicsymbols('x y')) + headings
    u = list(dynamicsymbols('ux uy')) + list(
        dynamicsymbols(' '.join(f'w{i}' for i in range(1, links + 1)) + ' extra'))[:links]
    m, l, j = 1, sp.Rational(3, 5), sp.Rational(3, 100)
    n = ReferenceFrame('N')
    frames, bodies, constraints = [], [], []
    velocity = u[0] * n.x + u[1] * n.y
    for i in range(links):
        frame = n.orientnew(f'L{i + 1}', 'Axis', [headings[i], n.z])
        frame.set_ang_vel(n, u[2 + i] * n.z)
        if i > 0:
            velocity = velocity + l / 2 * (u[1 + i] * frames[-1].y + u[2 + i] * frame.y)
        centre = Point(f'C{i + 1}')
        centre.set_vel(n, velocity)
        frames.append(frame)
        bodies.append(body(f'link{i + 1}', centre, frame, m, j))
        constraints.append(velocity.dot(frame.y))
    torques = sp.symbols(' '.join(f'tau{i}' for i in range(1, links)) + ' unused')[:links - 1]
    loads = []
    for i, tau in enumerate(torques):
        loads += [(frames[i + 1], tau * n.z), (frames[i], -tau * n.z)]
    kinematics = [sp.diff(qi, t) - ui for qi, ui in zip(q, u)]
    dependent = [u[1]] + u[2:2 + links - 1]
    independent = [ui for ui in u if ui not in dependent]
    return dict(q=q, u=u, independent=independent, dependent=dependent,
                kinematics=kinematics, constraints=constraints, frame=n,
                bodies=bodies, loads=loads, inputs=list(torques))


def study(name, build):
    start = time.perf_counter()
    model = build()
    kane = KanesMethod(model['frame'], q_ind=model['q'], u_ind=model['independent'],
                       u_dependent=model['dependent'], kd_eqs=model['kinematics'],
                       velocity_constraints=model['constraints'])
    kane.kanes_equations(model['bodies'], model['loads'])
    equations = time.perf_counter() - start
    mass, forcing = kane.mass_matrix, kane.forcing
    accelerations = mass.LUsolve(forcing)
    derivation = time.perf_counter() - start
    print(f'{name}: kanes_equations {equations:.3f} s, with M^-1 f {derivation:.3f} s',
          flush=True)
    replacements, reduced = sp.cse(list(accelerations))
    operations = count(replacements, reduced)
    mf_replacements, mf_reduced = sp.cse(list(mass) + list(forcing))
    mf_operations = count(mf_replacements, mf_reduced)
    arguments = list(model['q']) + list(model['u']) + list(model['inputs'])
    function = sp.lambdify(arguments, list(accelerations), cse=True)
    values = [0.3 * (i + 1) ** 0.5 % 1.0 + 0.1 for i in range(len(arguments))]
    per_call = min(timeit.repeat(lambda: function(*values), number=2000, repeat=5)) / 2000
    print(f'{name}: cse ops of M^-1 f {operations}, of (M, f) {mf_operations}; '
          f'lambdify {per_call * 1e9:.0f} ns/call', flush=True)


def main():
    largest = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    study('snakeboard', snakeboard)
    for links in range(2, largest + 1):
        study(f'snake{links}', lambda: snake(links))


if __name__ == '__main__':
    main()
