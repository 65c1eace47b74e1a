"""The snakeboard's plan of `opty_snakeboard.PROBLEM` solved by Chaplygin
(`chaplygin plan snakeboard`, release build) and by opty as the nodes
double, side by side.

The two transcriptions differ by their discretization error (their states,
input placement and quadrature differ), so both objectives tend to the
same optimum `J*` as `h = T/(N-1) -> 0`. `J*` is estimated by Richardson
extrapolation at the scheme's order `p` (`J* ~ J_h + (J_h - J_2h)/(2^p -
1)`) of the two finest of the finest three successive grids whose
differences shrink at that order (a grid where a solver stopped at another
local optimum is passed over); the reference is the midpoint rule's
estimate from the finest such grids (the mean if the tools tie), and every
estimate is printed against it. For each run the table gives the objective, its relative error
against the reference, the iterations, the whole-solve wall time
(Chaplygin: the process, derivation and JIT included; opty: its problem
construction, code generation and compilation included, and Ipopt), the
solver's own time (Chaplygin: `plan.json`'s `seconds`; opty: Ipopt's
solve) and the CPU seconds of the process and its children. Then, per
tool and scheme, the observed order `log2((J_2h - J_4h)/(J_h - J_2h))`
on the grids extrapolated, and the time of the coarsest grid within
`--accuracy` of the reference.

Every run is a fresh process. Arguments this script does not know are
passed to `chaplygin plan` (e.g. `--hessian exact`); a scheme opty lacks
(e.g. `--schemes hermite-simpson`) runs with Chaplygin alone.

Usage: python plan_peer.py [--nodes 11 21 41 81 161 321 641]
           [--schemes midpoint backward-euler] [--tools chaplygin opty-cython opty-numpy]
           [--chaplygin target/release/chaplygin] [--save results.json]
           [--load results.json...] [chaplygin plan flags...]
"""

import argparse
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from opty_snakeboard import PROBLEM, SCHEMES

HERE = Path(__file__).resolve().parent
ORDERS = {'backward-euler': 1, 'midpoint': 2, 'hermite-simpson': 4}


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(command):
    """The finished process, its wall and CPU seconds (children included)."""
    cpu, started = children_cpu(), time.perf_counter()
    finished = subprocess.run(command, capture_output=True, text=True)
    wall = time.perf_counter() - started
    if finished.returncode != 0:
        raise RuntimeError(f'{" ".join(command)} failed: {finished.stderr.strip()}')
    return finished, wall, children_cpu() - cpu


def chaplygin_command(binary, nodes, scheme, out, extra):
    """`chaplygin plan snakeboard` on `PROBLEM`."""
    command = [str(binary), 'plan', 'snakeboard', '--duration', str(PROBLEM['duration']),
               '--nodes', str(nodes), '--scheme', scheme, '--out', str(out)]
    for flag, values in (('--start', PROBLEM['start']), ('--goal', PROBLEM['goal'])):
        for name, value in values.items():
            command += [flag, f'{name}={value!r}']
    for name, (lo, hi) in PROBLEM['bounds'].items():
        command += ['--bound', f'{name}={lo!r}:{hi!r}']
    return command + list(extra)


def run_chaplygin(binary, nodes, scheme, extra):
    with tempfile.TemporaryDirectory() as out:
        _, wall, cpu = timed(chaplygin_command(binary, nodes, scheme, out, extra))
        report = json.loads(Path(out, 'plan.json').read_text())
    return dict(tool='chaplygin', scheme=scheme, nodes=nodes, objective=report['objective'],
                iterations=report['iterations'], seconds=wall, solver_seconds=report['seconds'],
                cpu_seconds=cpu, status=report['status'])


def run_opty(nodes, scheme, backend):
    finished, _, cpu = timed([sys.executable, str(HERE / 'opty_snakeboard.py'), str(nodes),
                              scheme, backend])
    line = next(l for l in finished.stdout.splitlines() if l.startswith('OPTY '))
    result = json.loads(line[len('OPTY '):])
    if not result['succeeded']:
        raise RuntimeError(f'opty at {nodes} nodes ({scheme}): {result["status"]}')
    return dict(tool=f'opty-{backend}', scheme=scheme, nodes=nodes, objective=result['objective'],
                iterations=result['iterations'], seconds=result['seconds'],
                solver_seconds=result['solve_seconds'], cpu_seconds=cpu,
                status=result['status'])


def series(results, tool, scheme):
    return sorted((r for r in results if r['tool'] == tool and r['scheme'] == scheme),
                  key=lambda r: r['nodes'])


def consistent(runs, order):
    """The finest three successive grids whose differences shrink at the
    scheme's order (observed within 0.5 of it), else the finest three: a
    grid where the solver stopped at another local optimum is passed over."""
    triples = [runs[k - 3:k] for k in range(len(runs), 2, -1)]
    return next((t for t in triples if abs(observed_order(t) - order) < 0.5),
                triples[0] if triples else runs)


def extrapolated(runs, order):
    """Richardson's estimate of the limit from the two finest consistent
    grids."""
    coarse, fine = (r['objective'] for r in consistent(runs, order)[-2:])
    return fine + (fine - coarse) / (2 ** order - 1)


def observed_order(runs):
    """`log2` of the ratio of the last three grids' successive differences."""
    if len(runs) < 3:
        return math.nan
    a, b, c = (r['objective'] for r in runs[-3:])
    return math.log2(abs((b - a) / (c - b))) if c != b else math.inf


def reference(results):
    """The midpoint rule's estimate (else any scheme's) from the finest
    consistent grids, averaged over the tools that reach them (opty's
    backends count once, their discrete problems being one; NaN without
    two grids), and every estimate."""
    estimates, finest = {}, {}
    for tool in sorted({r['tool'] for r in results}):
        for scheme in sorted({r['scheme'] for r in results}):
            runs = series(results, tool, scheme)
            if len(runs) >= 2:
                estimates[(tool, scheme)] = extrapolated(runs, ORDERS[scheme])
                family = (tool.split('-')[0], scheme)
                finest.setdefault(family, (consistent(runs, ORDERS[scheme])[-1]['nodes'],
                                           estimates[(tool, scheme)]))
    candidates = [v for (_, scheme), v in finest.items() if scheme == 'midpoint'] or list(
        finest.values())
    if not candidates:
        return math.nan, estimates
    top = max(nodes for nodes, _ in candidates)
    chosen = [value for nodes, value in candidates if nodes == top]
    return sum(chosen) / len(chosen), estimates


def print_table(results, accuracy):
    optimum, estimates = reference(results)
    print(f'reference optimum J* = {optimum:.10f} (the midpoint estimate from the finest grids)')
    for (tool, scheme), value in estimates.items():
        print(f'  Richardson {tool:9} {scheme:15} {value:.10f}  '
              f'({(value - optimum) / optimum:+.1e} of J*)')
    print()
    print('| tool | scheme | nodes | objective | rel. error | iterations | whole solve s '
          '| solver s | CPU s |')
    print('|---|---|---|---|---|---|---|---|---|')
    for r in sorted(results, key=lambda r: (r['scheme'], r['nodes'], r['tool'])):
        error = abs(r['objective'] - optimum) / abs(optimum)
        print(f"| {r['tool']} | {r['scheme']} | {r['nodes']} | {r['objective']:.8f} "
              f"| {error:.1e} | {r['iterations']} | {r['seconds']:.2f} "
              f"| {r['solver_seconds']:.2f} | {r['cpu_seconds']:.2f} |")
    print()
    print(f'| tool | scheme | grids extrapolated | observed order | first grid within {accuracy:g} '
          '| its whole solve s | its CPU s |')
    print('|---|---|---|---|---|---|---|')
    for tool in sorted({r['tool'] for r in results}):
        for scheme in sorted({r['scheme'] for r in results}):
            runs = series(results, tool, scheme)
            if not runs:
                continue
            within = [r for r in runs
                      if abs(r['objective'] - optimum) <= accuracy * abs(optimum)]
            reached = (f"{within[0]['nodes']} nodes | {within[0]['seconds']:.2f} "
                       f"| {within[0]['cpu_seconds']:.2f}") if within else 'not reached | - | -'
            used = consistent(runs, ORDERS[scheme])
            grids = ', '.join(str(r['nodes']) for r in used)
            print(f'| {tool} | {scheme} | {grids} | {observed_order(used):.2f} | {reached} |')


def record(results, result, save):
    """Keeps a run, prints it, and saves all so far."""
    results.append(result)
    print(json.dumps(result), flush=True)
    if save:
        save.write_text(json.dumps(results, indent=1) + '\n')


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--nodes', type=int, nargs='+', default=[11, 21, 41, 81, 161, 321, 641])
    parser.add_argument('--schemes', nargs='+', default=['midpoint', 'backward-euler'])
    parser.add_argument('--tools', nargs='+', default=['chaplygin', 'opty-numpy'],
                        help='chaplygin, opty-cython, opty-numpy (opty\'s backends)')
    parser.add_argument('--chaplygin', type=Path, default=Path(
        os.environ.get('CARGO_TARGET_DIR', HERE.parent.parent / 'target'),
        'release', 'chaplygin'))
    parser.add_argument('--accuracy', type=float, default=1e-4)
    parser.add_argument('--save', type=Path, help='write the runs as JSON')
    parser.add_argument('--load', type=Path, nargs='+',
                        help='print the table of the runs saved in these files')
    return parser.parse_known_args()


def main():
    options, extra = arguments()
    if options.load:
        results = [r for path in options.load for r in json.loads(path.read_text())]
    else:
        results = []
        for scheme in options.schemes:
            for nodes in options.nodes:
                if 'chaplygin' in options.tools:
                    record(results, run_chaplygin(options.chaplygin, nodes, scheme, extra),
                           options.save)
                for backend in ('cython', 'numpy'):
                    if f'opty-{backend}' in options.tools and scheme in SCHEMES:
                        record(results, run_opty(nodes, scheme, backend), options.save)
    print_table(results, options.accuracy)


if __name__ == '__main__':
    main()
