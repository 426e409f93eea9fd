#!/usr/bin/python3
"""latsim against its SimPy peer and an older latsim on the same HMD scenario.

    bench/hmd_bench.py [--latsim build/latsim] [--before OLD_LATSIM]
                       [--simpy ../shared/bench/hmd_simpy.py] [--runs N] [--out DIR]
                       [--parts peers,ladder]
                       [--kernels simpy2,simpy3] [--durations 60,600]

peers:  scenarios/hmd_60hz_direct.json at line and field scanout, 60 s and
        600 s, run by latsim, by the older latsim (--before) and by the SimPy
        model with both kernels (SimPy 2 and SimPy 3), round-robin, N runs
        each; simulation wall time (each program's own wall_s: the event loop
        only), process wall time and peak memory (wait4), events, and the mean
        motion-to-photon latency, which must agree to 9 digits.
ladder: scanout field, line and pixel of 10 s of hmd_60hz_direct and
        hmd_60hz_tearing, by latsim and the older latsim: wall, events, peak
        memory, the mean latency.

Every latsim run writes its result files (timeline included) into DIR, as a
user's run would. Prints Markdown tables; the raw rows go to DIR/rows.json.
The machine's load average is printed before and after: compare the ratios,
which are measured in one invocation.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def run(argv):
    """Runs argv; returns (stdout, process wall s, process CPU s, peak RSS MB)."""
    t0 = time.perf_counter()
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    out = proc.stdout.read()
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - t0
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"failed: {' '.join(argv)}\n{err.decode()}")
    return out.decode(), wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024.0


def latsim_run(binary, scenario, sets, out_dir):
    argv = [binary, 'run', scenario, '--quiet', '--out', out_dir]
    for s in sets:
        argv += ['--set', s]
    _, wall, cpu, rss = run(argv)
    with open(os.path.join(out_dir, 'summary.json')) as f:
        summary = json.load(f)
    mtp = summary['figures']['motion_to_photon_ms']['mean']
    return {'sim_s': summary['wall_s'], 'proc_s': wall, 'cpu_s': cpu, 'rss_mb': rss, 'events': summary['events'],
            'mtp': mtp}


def simpy_run(script, kernel, scenario, sets):
    argv = ['/usr/bin/python3', script, scenario, '--kernel', kernel]
    for s in sets:
        argv += ['--set', s]
    out, wall, cpu, rss = run(argv)
    r = json.loads(out)
    return {'sim_s': r['wall_s'], 'proc_s': wall, 'cpu_s': cpu, 'rss_mb': rss, 'events': r['events'],
            'mtp': r['figures']['motion_to_photon_ms']['mean']}


def median_row(rows):
    return {k: statistics.median(r[k] for r in rows) for k in ('sim_s', 'proc_s', 'cpu_s', 'rss_mb')} | {
        'events': rows[0]['events'], 'mtp': rows[0]['mtp'], 'runs': len(rows)}


# latsim draws each clock's phase per replication; the SimPy model and an
# older latsim without phase keys (c7a6d13) start every clock at zero.
PINNED = ['/display/phase_ms=0', '/tracker/phase_ms=0']


def knows_phases(binary):
    """Whether a latsim binary has the clock phase keys (then it is pinned like latsim)."""
    out = subprocess.run([binary, 'schema', '--format', 'json-schema'], capture_output=True, text=True).stdout
    return '"phase_ms"' in out


def peers(args, rows):
    scenario = os.path.join(ROOT, 'scenarios', 'hmd_60hz_direct.json')
    before_pinned = bool(args.before) and knows_phases(args.before)
    programs = [('latsim', None), ('latsim before', None), ('SimPy 2', 'simpy2'), ('SimPy 3', 'simpy3')]
    programs = [p for p in programs if p[1] is None or p[1] in args.kernels.split(',')]
    if not args.before:
        programs = [p for p in programs if p[0] != 'latsim before']
    print('\n### latsim and the SimPy model, hmd_60hz_direct\n')
    print('| scanout | sim s | program | events | sim wall (s) | process wall (s) | process CPU (s) | peak MB '
          '| MTP mean (ms) | latsim is x faster: sim wall | process CPU |')
    print('|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|')
    for scanout in ('field', 'line'):
        for duration in map(int, args.durations.split(',')):
            sets = [f'/duration_s={duration}', f'/display/scanout="{scanout}"']
            got = {name: [] for name, _ in programs}
            for _ in range(args.runs):
                for name, kernel in programs:
                    if kernel:
                        got[name].append(simpy_run(args.simpy, kernel, scenario, sets + PINNED))
                    else:
                        binary = args.latsim if name == 'latsim' else args.before
                        out_dir = os.path.join(args.out, f'{name.replace(" ", "_")}_{scanout}_{duration}')
                        pinned = PINNED if name == 'latsim' or before_pinned else []
                        got[name].append(latsim_run(binary, scenario, sets + pinned, out_dir))
            med = {name: median_row(r) for name, r in got.items()}
            ours = med['latsim']
            for name, _ in programs:
                m = med[name]
                if abs(m['mtp'] - ours['mtp']) > 1e-9 * abs(ours['mtp']):
                    sys.exit(f'{name} disagrees on the mean latency: {m["mtp"]} vs {ours["mtp"]}')
                print(f"| {scanout} | {duration} | {name} | {m['events']:,} | {m['sim_s']:.4f} | {m['proc_s']:.3f} "
                      f"| {m['cpu_s']:.3f} | {m['rss_mb']:.1f} | {m['mtp']:.9f} | {m['sim_s'] / ours['sim_s']:.1f} "
                      f"| {m['cpu_s'] / ours['cpu_s']:.1f} |")
                rows.append({'part': 'peers', 'scanout': scanout, 'duration_s': duration, 'program': name} | m)
            sys.stdout.flush()


def ladder(args, rows):
    print('\n### Fidelity ladder, 10 s\n')
    print('| scenario | scanout | program | events | sim wall (s) | process wall (s) | process CPU (s) | peak MB '
          '| MTP mean (ms) | x line level: sim wall | process CPU |')
    print('|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|')
    programs = [('latsim', args.latsim)] + ([('latsim before', args.before)] if args.before else [])
    for scenario in ('hmd_60hz_direct', 'hmd_60hz_tearing'):
        path = os.path.join(ROOT, 'scenarios', scenario + '.json')
        for name, binary in programs:
            line = None
            for scanout in ('line', 'field', 'pixel'):
                sets = ['/duration_s=10', f'/display/scanout="{scanout}"']
                out_dir = os.path.join(args.out, f'ladder_{name.replace(" ", "_")}_{scenario}_{scanout}')
                r = latsim_run(binary, path, sets + (PINNED if name == 'latsim' else []), out_dir)
                line = r if scanout == 'line' else line
                print(f"| {scenario} | {scanout} | {name} | {r['events']:,} | {r['sim_s']:.4f} | {r['proc_s']:.3f} "
                      f"| {r['cpu_s']:.3f} | {r['rss_mb']:.1f} | {r['mtp']:.9f} | {r['sim_s'] / line['sim_s']:.2f} "
                      f"| {r['cpu_s'] / line['cpu_s']:.2f} |")
                rows.append({'part': 'ladder', 'scenario': scenario, 'scanout': scanout, 'program': name} | r)
                sys.stdout.flush()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--latsim', default=os.path.join(ROOT, 'build', 'latsim'))
    ap.add_argument('--before', help='an older latsim binary to compare with')
    ap.add_argument('--simpy', default=os.path.join(ROOT, '..', 'shared', 'bench', 'hmd_simpy.py'))
    ap.add_argument('--runs', type=int, default=1)
    ap.add_argument('--out', default='/tmp/latsim_hmd_bench')
    ap.add_argument('--parts', default='peers,ladder')
    ap.add_argument('--kernels', default='simpy2,simpy3', help='SimPy kernels to run (peers)')
    ap.add_argument('--durations', default='60,600', help='simulated seconds (peers)')
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    print(f'load average before: {os.getloadavg()}')
    rows = []
    parts = args.parts.split(',')
    if 'peers' in parts:
        peers(args, rows)
    if 'ladder' in parts:
        ladder(args, rows)
    print(f'\nload average after: {os.getloadavg()}')
    with open(os.path.join(args.out, 'rows.json'), 'w') as f:
        json.dump(rows, f, indent=1)


if __name__ == '__main__':
    main()
