"""SymPy mechanics (KanesMethod) on the Whipple-Carvallo benchmark bicycle,
timed from the declaration of bodies to the canonical matrices.

The model is SymPy's own test of the bicycle
(`sympy/physics/mechanics/tests/test_kane3.py`, a port of an Autolev
derivation): yaw q1, roll q2, pitch q4 (dependent, through the front
contact's height), steer q5; speeds u1..u6 with u2 (roll rate), u3 (rear
wheel rate) and u5 (steer rate) independent, and the front contact's
velocity as three velocity constraints.

Three phases are timed:

- derive: frames, points, bodies, loads and constraints, `kanes_equations`;
- linearize: `KanesMethod.linearize` about upright straight running at a
  symbolic speed v, all parameters symbolic (the implicit form
  `M [q', u'] = A [q_ind, u_ind]`);
- extract: the benchmark's parameters substituted, and the canonical
  `M, C1, K0, K2` of Meijaard, Papadopoulos, Ruina and Schwab (2007),
  `M qdd + v C1 qd + (g K0 + v^2 K2) q = 0`, q = (roll, steer), read off.

The dynamic rows are Kane's equations `Fr + Fr* = 0`, with `Fr*` holding
`-M_red u_ind'` and the generalized input forces entering `Fr` only; so
`M_red = -inv(inv(M)[u_ind', dynamic rows])`. The stiffness and damping
are `-M_red` times the roll and steer rows of the explicit state matrix
`inv(M) A`, at v = 0 (`g K0`) and v = 1 (`g K0 + K2`, `C1`).

The matrices are compared with the paper's published values; printed: the
matrices and one line `SYMPY_BICYCLE derive_s=... linearize_s=...
extract_s=... total_s=... cpu_s=... max_rel_err=...` (wall-clock seconds per
phase, their sum, the process's CPU seconds, and the largest relative error
of an entry against the published matrices, absolute for published zeros).

Usage: python sympy_bicycle.py
"""

import time

import sympy as sp
from sympy.physics.mechanics import (
    KanesMethod, Point, ReferenceFrame, RigidBody, dot, dynamicsymbols, inertia,
)

# Table 1 of Meijaard et al. (2007), the benchmark's parameters.
BENCHMARK = {
    'w': 1.02, 'c': 0.08, 'lam': sp.pi / 10, 'g': 9.81,
    'rR': 0.3, 'mR': 2.0, 'IRxx': 0.0603, 'IRyy': 0.12,
    'xB': 0.3, 'zB': -0.9, 'mB': 85.0,
    'IBxx': 9.2, 'IByy': 11.0, 'IBzz': 2.8, 'IBxz': 2.4,
    'xH': 0.9, 'zH': -0.7, 'mH': 4.0,
    'IHxx': 0.05892, 'IHyy': 0.06, 'IHzz': 0.00708, 'IHxz': -0.00756,
    'rF': 0.35, 'mF': 3.0, 'IFxx': 0.1405, 'IFyy': 0.28,
}

# The paper's canonical matrices at these parameters, as printed there.
PUBLISHED = {
    'M': [[80.81722, 2.31941332208709], [2.31941332208709, 0.29784188199686]],
    'C1': [[0.0, 33.86641391492494], [-0.85035641456978, 1.68540397397560]],
    'K0': [[-80.95, -2.59951685249872], [-2.59951685249872, -0.80329488458618]],
    'K2': [[0.0, 76.59734589573222], [0.0, 2.65431523794604]],
}


def derive():
    """The bicycle of test_kane3.py, up to `kanes_equations`."""
    q1, q2, q4, q5 = dynamicsymbols('q1 q2 q4 q5')
    q1d, q2d, q4d, q5d = dynamicsymbols('q1 q2 q4 q5', 1)
    u1, u2, u3, u4, u5, u6 = dynamicsymbols('u1 u2 u3 u4 u5 u6')
    p = sp.symbols(
        'WFrad WRrad htangle forkoffset forklength framelength forkcg1 forkcg3 '
        'framecg1 framecg3 Iwr11 Iwr22 Iwf11 Iwf22 Iframe11 Iframe22 Iframe33 '
        'Iframe31 Ifork11 Ifork22 Ifork33 Ifork31 g mframe mfork mwf mwr')
    p = dict(zip([s.name for s in p], p))

    N = ReferenceFrame('N')
    Y = N.orientnew('Y', 'Axis', [q1, N.z])
    R = Y.orientnew('R', 'Axis', [q2, Y.x])
    Frame = R.orientnew('Frame', 'Axis', [q4 + p['htangle'], R.y])
    WR = ReferenceFrame('WR')
    TempFrame = Frame.orientnew('TempFrame', 'Axis', [-p['htangle'], Frame.y])
    Fork = Frame.orientnew('Fork', 'Axis', [q5, Frame.x])
    TempFork = Fork.orientnew('TempFork', 'Axis', [-p['htangle'], Fork.y])
    WF = ReferenceFrame('WF')

    WR_cont = Point('WR_cont')
    WR_mc = WR_cont.locatenew('WR_mc', p['WRrad'] * R.z)
    Steer = WR_mc.locatenew('Steer', p['framelength'] * Frame.z)
    Frame_mc = WR_mc.locatenew('Frame_mc', -p['framecg1'] * Frame.x + p['framecg3'] * Frame.z)
    Fork_mc = Steer.locatenew('Fork_mc', -p['forkcg1'] * Fork.x + p['forkcg3'] * Fork.z)
    WF_mc = Steer.locatenew('WF_mc', p['forklength'] * Fork.x + p['forkoffset'] * Fork.z)
    WF_cont = WF_mc.locatenew(
        'WF_cont', p['WFrad'] * (dot(Fork.y, Y.z) * Fork.y - Y.z).normalize())

    Y.set_ang_vel(N, u1 * Y.z)
    R.set_ang_vel(Y, u2 * R.x)
    WR.set_ang_vel(Frame, u3 * Frame.y)
    Frame.set_ang_vel(R, u4 * Frame.y)
    Fork.set_ang_vel(Frame, u5 * Fork.x)
    WF.set_ang_vel(Fork, u6 * Fork.y)

    WR_cont.set_vel(N, 0)
    WR_mc.v2pt_theory(WR_cont, N, WR)
    Steer.v2pt_theory(WR_mc, N, Frame)
    Frame_mc.v2pt_theory(WR_mc, N, Frame)
    Fork_mc.v2pt_theory(Steer, N, Fork)
    WF_mc.v2pt_theory(Steer, N, Fork)
    WF_cont.v2pt_theory(WF_mc, N, WF)

    Frame_I = (inertia(TempFrame, p['Iframe11'], p['Iframe22'], p['Iframe33'], 0, 0,
                       p['Iframe31']), Frame_mc)
    Fork_I = (inertia(TempFork, p['Ifork11'], p['Ifork22'], p['Ifork33'], 0, 0,
                      p['Ifork31']), Fork_mc)
    WR_I = (inertia(Frame, p['Iwr11'], p['Iwr22'], p['Iwr11']), WR_mc)
    WF_I = (inertia(Fork, p['Iwf11'], p['Iwf22'], p['Iwf11']), WF_mc)
    bodies = [
        RigidBody('BodyFrame', Frame_mc, Frame, p['mframe'], Frame_I),
        RigidBody('BodyFork', Fork_mc, Fork, p['mfork'], Fork_I),
        RigidBody('BodyWR', WR_mc, WR, p['mwr'], WR_I),
        RigidBody('BodyWF', WF_mc, WF, p['mwf'], WF_I),
    ]
    loads = [
        (Frame_mc, -p['mframe'] * p['g'] * Y.z),
        (Fork_mc, -p['mfork'] * p['g'] * Y.z),
        (WF_mc, -p['mwf'] * p['g'] * Y.z),
        (WR_mc, -p['mwr'] * p['g'] * Y.z),
    ]
    kd = [q1d - u1, q2d - u2, q4d - u4, q5d - u5]
    speed_constraints = [WF_cont.vel(N) & Y.x, WF_cont.vel(N) & Y.y, WF_cont.vel(N) & Y.z]
    coordinate_constraints = [WF_cont.pos_from(WR_cont) & Y.z]

    kane = KanesMethod(
        N, q_ind=[q1, q2, q5], q_dependent=[q4],
        configuration_constraints=coordinate_constraints,
        u_ind=[u2, u3, u5], u_dependent=[u1, u4, u6],
        velocity_constraints=speed_constraints, kd_eqs=kd,
        constraint_solver='CRAMER')
    kane.kanes_equations(bodies, loads)
    return kane, p, (q1, q2, q4, q5), (u1, u2, u3, u4, u5, u6)


def benchmark_values(p, v):
    """test_kane3.py's map from table 1 to its model's parameters."""
    b = BENCHMARK
    hta = (sp.pi / 2 - b['lam']).evalf()
    rake = (-(b['c'] * sp.sin(hta) - b['rF'] * sp.cos(hta))).evalf()
    frame_length = (b['w'] * sp.sin(hta) - (rake - (b['rF'] - b['rR']) * sp.cos(hta))).evalf()
    frame_cg_norm = ((-b['zB'] - b['rR'] - (b['xB'] / sp.sin(hta)) * sp.cos(hta))
                     * sp.sin(hta)).evalf()
    frame_cg_par = (b['xB'] / sp.sin(hta) + (-b['zB'] - b['rR'] - b['xB'] / sp.sin(hta)
                                            * sp.cos(hta)) * sp.cos(hta)).evalf()
    tempa = -b['zH'] - b['rF']
    tempb = b['w'] - b['xH']
    tempc = sp.sqrt(tempa**2 + tempb**2).evalf()
    fork_length = (b['w'] * sp.cos(hta) - (b['rF'] - b['rR']) * sp.sin(hta)).evalf()
    fork_cg_norm = (rake + tempc * sp.sin(sp.pi / 2 - hta - sp.acos(tempa / tempc))).evalf()
    fork_cg_par = (tempc * sp.cos((sp.pi / 2 - hta) - sp.acos(tempa / tempc))
                   - fork_length).evalf()
    values = {
        'WFrad': b['rF'], 'WRrad': b['rR'], 'htangle': hta, 'forkoffset': rake,
        'forklength': fork_length, 'framelength': frame_length,
        'forkcg1': fork_cg_par, 'forkcg3': fork_cg_norm,
        'framecg1': frame_cg_norm, 'framecg3': frame_cg_par,
        'Iwr11': b['IRxx'], 'Iwr22': b['IRyy'], 'Iwf11': b['IFxx'], 'Iwf22': b['IFyy'],
        # The model's frames differ from the paper's: products of inertia flip sign.
        'Ifork11': b['IHxx'], 'Ifork22': b['IHyy'], 'Ifork33': b['IHzz'],
        'Ifork31': -b['IHxz'],
        'Iframe11': b['IBxx'], 'Iframe22': b['IByy'], 'Iframe33': b['IBzz'],
        'Iframe31': -b['IBxz'],
        'mfork': b['mH'], 'mframe': b['mB'], 'mwf': b['mF'], 'mwr': b['mR'],
        'g': b['g'],
    }
    return {p[name]: value for name, value in values.items()} | {sp.Symbol('v'): v}


def linearize(kane, q, u):
    """Implicit linear form about upright straight running at speed v."""
    q1, q2, q4, q5 = q
    u1, u2, u3, u4, u5, u6 = u
    v = sp.Symbol('v')
    rr, rf = sp.symbols('WRrad WFrad')
    op_point = {
        **{s.diff(): 0 for s in u},
        u1: 0, u2: 0, u3: v / rr, u4: 0, u5: 0, u6: v / rf,
        q1: 0, q2: 0, q4: 0, q5: 0,
    }
    # Cramer's rule, as in the test: with the default LU solver the matrices
    # at the operating point come out nan.
    mass, state, *_ = kane.linearize(
        A_and_B=False, op_point=op_point, linear_solver='CRAMER')
    return mass, state


def canonical(mass, state, p):
    """M, C1, K0, K2 in (roll, steer) at the benchmark's parameters.

    Columns of `mass`: q1 q2 q5 q4 | u2 u3 u5 u1 u4 u6; rows: the four
    kinematic equations, the three velocity constraints, the three dynamic
    equations (for u2, u3, u5). Columns of `state`: q1 q2 q5 | u2 u3 u5."""
    independent_rates, dynamic_rows = [4, 5, 6], [7, 8, 9]
    roll_steer = [0, 2]
    coordinates, speeds = [1, 2], [3, 5]

    def at(v):
        values = benchmark_values(p, v)
        m = sp.Matrix(mass.xreplace(values)).evalf()
        a = sp.Matrix(state.xreplace(values)).evalf()
        m_inverse = m.inv()
        reduced_mass = -m_inverse.extract(independent_rates, dynamic_rows).inv()
        explicit = (m_inverse * a).extract(independent_rates, list(range(6)))
        forces = -reduced_mass * explicit
        return (reduced_mass.extract(roll_steer, roll_steer),
                forces.extract(roll_steer, coordinates),
                forces.extract(roll_steer, speeds))

    g = BENCHMARK['g']
    m0, stiffness0, _ = at(0)
    _, stiffness1, damping1 = at(1)
    return {'M': m0, 'C1': damping1, 'K0': stiffness0 / g, 'K2': stiffness1 - stiffness0}


def max_relative_error(matrices):
    """Largest relative error over the nonzero published entries; the
    absolute error for the published zeros."""
    worst = 0.0
    for name, published in PUBLISHED.items():
        for i in range(2):
            for j in range(2):
                got, want = float(matrices[name][i, j]), published[i][j]
                error = abs(got - want) / abs(want) if want != 0.0 else abs(got)
                worst = max(worst, error)
    return worst


def main():
    start, cpu_start = time.perf_counter(), time.process_time()
    kane, p, q, u = derive()
    derived = time.perf_counter()
    print(f'derived in {derived - start:.3f} s', flush=True)
    mass, state = linearize(kane, q, u)
    linearized = time.perf_counter()
    print(f'linearized in {linearized - derived:.3f} s', flush=True)
    matrices = canonical(mass, state, p)
    extracted, cpu_end = time.perf_counter(), time.process_time()
    for name in PUBLISHED:
        rows = [[float(x) for x in matrices[name].row(i)] for i in range(2)]
        print(f'{name} = {rows}')
    print(
        f'SYMPY_BICYCLE derive_s={derived - start:.3f} '
        f'linearize_s={linearized - derived:.3f} '
        f'extract_s={extracted - linearized:.3f} '
        f'total_s={extracted - start:.3f} '
        f'cpu_s={cpu_end - cpu_start:.3f} '
        f'max_rel_err={max_relative_error(matrices):.3e}',
        flush=True)


if __name__ == '__main__':
    main()
