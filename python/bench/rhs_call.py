"""The cost of one right-hand-side call from Python: `Model.rhs` (the
model's derived programs compiled to native code) against PyDy's route,
SymPy's `lambdify` (NumPy backend) of the same model's reduced right-hand
side `xdot = J(x) dH/dx` built from `Model.sympy()`, both called with a
NumPy state as `scipy.integrate.solve_ivp` calls them. The two agree to
round-off before they are timed. Run after `pip install ./python`:

    python python/bench/rhs_call.py [MODEL ...]
"""

import sys
import time
import timeit

import numpy
import sympy

import chaplygin


def lambdified(model):
    """PyDy's route: the reduced right-hand side from the SymPy matrices,
    lambdified, and the time that took."""
    started = time.perf_counter()
    derived = model.sympy()
    state = [sympy.Symbol(name) for name in model.coordinates + model.momenta]
    gradient = sympy.Matrix([derived["hamiltonian"].diff(s) for s in state])
    expression = derived["structure_matrix"] * gradient
    parameters = model.parameters
    expression = expression.subs({sympy.Symbol(k): v for k, v in parameters.items()})
    function = sympy.lambdify([state], expression, modules="numpy", cse=True)
    return (lambda t, x: function(x).ravel()), time.perf_counter() - started


def per_call(function, t, x, repeat=7):
    """The best per-call time of `function(t, x)` in seconds."""
    timer = timeit.Timer(lambda: function(t, x))
    number, _ = timer.autorange()
    return min(timer.repeat(repeat=repeat, number=number)) / number


def main(names):
    print(f"{'model':<18} {'state':>5} {'chaplygin':>12} {'lambdify':>12} {'ratio':>7} {'sympy+lambdify':>15} {'load':>8}")
    for name in names:
        started = time.perf_counter()
        model = chaplygin.builtin(name)
        loaded = time.perf_counter() - started
        f = model.rhs("reduced")
        x = f.initial_state()
        reference, prepared = lambdified(model)
        ours, theirs = f(0.0, x), reference(0.0, x)
        scale = max(1.0, float(numpy.max(numpy.abs(ours))))
        assert numpy.max(numpy.abs(ours - theirs)) <= 1e-12 * scale, (ours, theirs)
        native = per_call(f, 0.0, x)
        pydy = per_call(reference, 0.0, x)
        print(
            f"{name:<18} {len(x):>5} {native * 1e6:>10.2f}us {pydy * 1e6:>10.2f}us "
            f"{pydy / native:>6.1f}x {prepared:>14.2f}s {loaded:>7.2f}s"
        )


if __name__ == "__main__":
    main(sys.argv[1:] or ["sleigh", "rolling-disk", "snakeboard", "rolling-disk-3d"])
