"""CasADi on the Lagrange-d'Alembert right-hand side of the benchmark bicycle
(Meijaard, Papadopoulos, Ruina & Schwab 2007), declared exactly as
`models/bicycle.model` declares it: the same eight coordinates, frames,
points, four bodies, two rolling contacts and the front contact's height as
a holonomic constraint, with the paper's table 1 as parameter values.

The equations are built and timed by `casadi_peer.py` (MATH.md section 2),
with the potential's gradient: the saddle-point system

    [[g, -A^T], [A, 0]] (qddot, lambda) = (B u - C - dV/dq, -Adot qdot)

as an SX function, `casadi.solve` symbolic, `Function.generate` to C,
compiled with `gcc -O3` together with `timing.c` and timed per call (best of
7 batches of 100000 calls at the harness's fixed state
q_k = 0.3 (k + 1) / 2, qdot_k = 0.3 (k + 1) / 3, u_k = 0.3 (k + 1) / 4).

Printed: the SX function's build time and instruction count, ns per call,
and (qddot, lambda) at the harness's state, which Chaplygin's bicycle
benchmark prints at the same state (`BICYCLE_STATE`), so that the two are
seen to compute the same equations.

Usage: python casadi_bicycle.py
"""

import tempfile

import casadi as ca

from casadi_peer import study

# Meijaard et al. (2007), table 1.
P = dict(w=1.02, c=0.08, lam=0.3141592653589793, g=9.81, rR=0.3, mR=2.0,
         IRxx=0.0603, IRyy=0.12, xB=0.3, zB=-0.9, mB=85.0, IBxx=9.2, IByy=11.0,
         IBzz=2.8, IBxz=2.4, xH=0.9, zH=-0.7, mH=4.0, IHxx=0.05892, IHyy=0.06,
         IHzz=0.00708, IHxz=-0.00756, rF=0.35, mF=3.0, IFxx=0.1405, IFyy=0.28)


def rotation(axis, angle):
    """The rotation about the parent's `axis` by `angle`, columns the new axes."""
    c, s = ca.cos(angle), ca.sin(angle)
    if axis == 'x':
        return ca.blockcat([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == 'y':
        return ca.blockcat([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return ca.blockcat([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def bicycle():
    q, qd, u = ca.SX.sym('q', 8), ca.SX.sym('qd', 8), ca.SX.sym('u', 2)
    x_p, y_p, psi, phi, theta_b, delta, theta_r, theta_f = [q[i] for i in range(8)]
    rate = dict(zip(['x_p', 'y_p', 'psi', 'phi', 'theta_b', 'delta', 'theta_r', 'theta_f'],
                    [qd[i] for i in range(8)]))
    p = P
    lam = p['lam']
    axis = dict(x=0, y=1, z=2)
    frames = {'ground': (ca.SX.eye(3), ca.SX.zeros(3))}

    def rotate(name, parent, ax, angle, angle_rate):
        r_parent, w_parent = frames[parent]
        frames[name] = (ca.mtimes(r_parent, rotation(ax, angle)),
                        w_parent + angle_rate * r_parent[:, axis[ax]])

    rotate('yaw', 'ground', 'z', psi, rate['psi'])
    rotate('roll', 'yaw', 'x', phi, rate['phi'])
    rotate('rear_frame', 'roll', 'y', theta_b, rate['theta_b'])
    rotate('rear_wheel', 'rear_frame', 'y', theta_r, rate['theta_r'])
    rotate('head', 'rear_frame', 'y', lam, 0)
    rotate('fork', 'head', 'z', delta, rate['delta'])
    rotate('front_frame', 'fork', 'y', -lam, 0)
    rotate('front_wheel', 'fork', 'y', theta_f, rate['theta_f'])

    def unit(frame, ax):
        return frames[frame][0][:, axis[ax]]

    cl, sl = ca.cos(lam), ca.sin(lam)
    w, c, rR, rF = p['w'], p['c'], p['rR'], p['rF']
    rear_contact = ca.vertcat(x_p, y_p, 0)
    rear_hub = rear_contact - rR * unit('roll', 'z')
    rear_center = rear_hub + p['xB'] * unit('rear_frame', 'x') + (p['zB'] + rR) * unit('rear_frame', 'z')
    steer_point = (rear_hub + (w * cl - (rR - rF) * sl - (rF * sl - c * cl)) * unit('head', 'x')
                   + (w * sl + (rR - rF) * cl) * unit('head', 'z'))
    front_hub = steer_point + (rF * sl - c * cl) * unit('fork', 'x')
    front_center = (front_hub + ((p['xH'] - w) * cl - (p['zH'] + rF) * sl) * unit('fork', 'x')
                    + ((p['xH'] - w) * sl + (p['zH'] + rF) * cl) * unit('fork', 'z'))
    down = ca.vertcat(0, 0, 1)
    fork_y = unit('fork', 'y')
    toward = ca.cross(fork_y, ca.cross(fork_y, down))
    front_contact = front_hub - rF * toward / ca.norm_2(toward)

    def velocity(point):
        return ca.jtimes(point, q, qd)

    def inertia(xx, yy, zz, xz):
        return ca.blockcat([[xx, 0, xz], [0, yy, 0], [xz, 0, zz]])

    bodies = [
        ('rear_wheel', rear_hub, p['mR'], inertia(p['IRxx'], p['IRyy'], p['IRxx'], 0)),
        ('rear_frame', rear_center, p['mB'], inertia(p['IBxx'], p['IByy'], p['IBzz'], p['IBxz'])),
        ('front_frame', front_center, p['mH'], inertia(p['IHxx'], p['IHyy'], p['IHzz'], p['IHxz'])),
        ('front_wheel', front_hub, p['mF'], inertia(p['IFxx'], p['IFyy'], p['IFxx'], 0)),
    ]
    kinetic, potential = 0, 0
    for frame, center, mass, tensor in bodies:
        r, omega = frames[frame]
        body_omega = ca.mtimes(r.T, omega)
        v = velocity(center)
        kinetic = kinetic + mass / 2 * ca.dot(v, v) + ca.mtimes([body_omega.T, tensor, body_omega]) / 2
        potential = potential - mass * p['g'] * center[2]

    def contact_rows(frame, center, point):
        omega = frames[frame][1]
        v = velocity(center) + ca.cross(omega, point - center)
        return [v[0], v[1]]

    rows = (contact_rows('rear_wheel', rear_hub, rear_contact)
            + contact_rows('front_wheel', front_hub, front_contact)
            + [velocity(front_contact[2])])
    forces = ca.vertcat(0, 0, 0, u[0], 0, u[1], 0, 0)
    return q, qd, u, kinetic, ca.vertcat(*rows), forces, potential


def main():
    model = bicycle()
    with tempfile.TemporaryDirectory() as directory:
        function = study('bicycle', model, directory)
    state = [[0.3 * (k + 1) / (i + 2.0) for k in range(size)] for i, size in enumerate([8, 8, 2])]
    values = function(*state).full().ravel()
    print('BICYCLE_STATE ' + ' '.join(f'{x:.15e}' for x in values))


if __name__ == '__main__':
    main()
