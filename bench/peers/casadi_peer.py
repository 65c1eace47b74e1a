"""CasADi on the Lagrange-d'Alembert right-hand side (MATH.md 2) of the
snakeboard and the N-link wheeled snake: the saddle-point system

    [[g, -A^T], [A, 0]] (qddot, lambda) = (B u - C, -Adot qdot)

built as an SX function (g the Hessian of T in qdot, C = d(g qdot)/dq qdot
- dT/dq, A the Jacobian of the constraints in qdot, Adot qdot = d(A qdot)/dq
qdot), solved symbolically with `casadi.solve`, emitted as C with
`Function.generate`, compiled with `gcc -O3` together with a timing harness
(timing.c) and timed per call (best of 7 batches of 100000 calls).

Parameters are Chaplygin's defaults. Usage: python casadi_peer.py [largest N]
"""

import os
import subprocess
import sys
import tempfile
import time

import casadi as ca

HERE = os.path.dirname(os.path.abspath(__file__))


def snakeboard():
    q, qd, u = ca.SX.sym('q', 5), ca.SX.sym('qd', 5), ca.SX.sym('u', 2)
    m, r, jt, jw = 1.0, 0.5, 0.3, 0.05
    j = jt + m * r**2
    kinetic = (m / 2 * (qd[0]**2 + qd[1]**2) + j / 2 * qd[2]**2 + jt * qd[2] * qd[3]
               + jt / 2 * qd[3]**2 + jw / 2 * qd[4]**2)
    th, phi = q[2], q[4]
    constraints = ca.vertcat(
        -ca.sin(th + phi) * qd[0] + ca.cos(th + phi) * qd[1] + r * ca.cos(phi) * qd[2],
        -ca.sin(th - phi) * qd[0] + ca.cos(th - phi) * qd[1] - r * ca.cos(phi) * qd[2])
    forces = ca.vertcat(0, 0, 0, u[0], u[1])
    return q, qd, u, kinetic, constraints, forces


def snake(links):
    n = links + 2
    q, qd = ca.SX.sym('q', n), ca.SX.sym('qd', n)
    u = ca.SX.sym('u', max(links - 1, 1))
    m, l, j = 1.0, 0.6, 0.03
    vx, vy = qd[0], qd[1]
    kinetic, rows, forces = 0, [], [0] * n
    for i in range(links):
        th = q[2 + i]
        if i > 0:
            previous = q[1 + i]
            vx = vx - l / 2 * (ca.sin(previous) * qd[1 + i] + ca.sin(th) * qd[2 + i])
            vy = vy + l / 2 * (ca.cos(previous) * qd[1 + i] + ca.cos(th) * qd[2 + i])
            forces[1 + i] = forces[1 + i] - u[i - 1]
            forces[2 + i] = forces[2 + i] + u[i - 1]
        kinetic = kinetic + m / 2 * (vx**2 + vy**2) + j / 2 * qd[2 + i]**2
        rows.append(-ca.sin(th) * vx + ca.cos(th) * vy)
    return q, qd, u, kinetic, ca.vertcat(*rows), ca.vertcat(*forces)


def lagrange_dalembert(q, qd, u, kinetic, constraints, forces, potential=None):
    g = ca.hessian(kinetic, qd)[0]
    coriolis = ca.jtimes(ca.mtimes(g, qd), q, qd) - ca.gradient(kinetic, q)
    a = ca.jacobian(constraints, qd)
    a_rate = ca.jtimes(ca.mtimes(a, qd), q, qd)
    c = a.shape[0]
    system = ca.blockcat([[g, -a.T], [a, ca.SX.zeros(c, c)]])
    force = forces - coriolis
    if potential is not None:
        force = force - ca.gradient(potential, q)
    solution = ca.solve(system, ca.vertcat(force, -a_rate))
    return ca.Function('acceleration', [q, qd, u], [solution])


def study(name, model, directory):
    """Builds, compiles and times one model's function; returns it."""
    start = time.perf_counter()
    function = lagrange_dalembert(*model)
    derivation = time.perf_counter() - start
    source = os.path.join(directory, f'{name}.c')
    function.generate(f'{name}.c', {'with_header': True})
    os.replace(f'{name}.c', source)
    os.replace(f'{name}.h', os.path.join(directory, f'{name}.h'))
    binary = os.path.join(directory, name)
    subprocess.run(['gcc', '-O3', '-o', binary, '-include', os.path.join(directory, f'{name}.h'),
                    os.path.join(HERE, 'timing.c'), source, '-lm'], check=True)
    sizes = [function.size1_in(i) for i in range(3)]
    output = subprocess.run([binary] + [str(s) for s in sizes], check=True,
                            capture_output=True, text=True).stdout.split()
    print(f'{name}: SX function built in {derivation:.3f} s, {function.n_instructions()} '
          f'instructions, {os.path.getsize(source)} bytes of C; compiled C '
          f'{float(output[0]):.1f} ns/call', flush=True)
    return function


def main():
    largest = int(sys.argv[1]) if len(sys.argv) > 1 else 12
    with tempfile.TemporaryDirectory() as directory:
        study('snakeboard', snakeboard(), directory)
        for links in range(2, largest + 1):
            study(f'snake{links}', snake(links), directory)


if __name__ == '__main__':
    main()
