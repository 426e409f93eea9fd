"""The independent hardening campaign (issue 47), re-runnable: hostile input to every command.

Each attack is checked against the contract, whatever it once did:
- bad input or options: exit 2, one line on stderr of a readable width
  (MAX_LINE) with no raw control character, naming the file (and for a
  scenario the JSON pointer, for an option the option), and nothing made;
- input that is legal passes validate and then runs (a short run here) to
  exit 0 or is refused (exit 2) by validate and run alike: a validated
  scenario never fails in its run (exit 1), spins or is killed;
- no Python command traces back, whatever it reads;
- SIGINT and SIGTERM end a command within BOUND_S, with 128 + the signal's
  number, one line naming it, and nothing left; a sweep stopped by SIGINT,
  SIGTERM or SIGKILL and run again ends with the table of an undisturbed one.

Attacks (the counts are printed at the end):
  keys      hostile values (huge, tiny, negative, 2^63, 1e308, 1e-308, NaN
            as a string, NUL and escape sequences in strings, 5,000
            characters, deep nesting, unicode, wrong types) at every leaf
            key of scenarios of several kinds (a plain HMD, a device
            profile with controllers, the measurement rig, a serial host);
  options   every command's options at extremes (-1, 2^64, "", nan, inf,
            1e-400, 3,000 digits, an escape sequence, an --out no file
            system holds);
  captures  PresentMon (current and v1), OVR Metrics, VrApi and SteamVR
            captures damaged (NUL byte, a column twice, truncated, empty,
            header only, binary, a 200,000-byte line) given to compare;
  results   run and sweep directories damaged (NUL and escape sequences in
            tables, UTF-16, a file turned into a directory, 100,000-deep
            JSON, out-of-range numbers) given to report;
  signals   SIGINT and SIGTERM while run and compare read a large capture;
            a sweep interrupted three ways, then resumed.

Usage: campaign.py LATSIM SOURCE_DIR SCRATCH_DIR [--full]
(--full: every scenario kind and every hostile value; the default is a
sample that takes under two minutes on two cores.)
"""

import glob
import json
import os
import resource
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "sweep"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sweep_checks import check, finish, table  # noqa: E402
from stop_checks import cpu_seconds  # noqa: E402

LATSIM, SOURCE_DIR, SCRATCH = sys.argv[1:4]
FULL = "--full" in sys.argv[4:]
# readable() keeps 400 characters of a line and adds "… (N bytes)".
MAX_LINE = 430
BOUND_S = 1.0
BASE = os.path.abspath(os.path.join(SOURCE_DIR, "scenarios", "hmd_60hz_direct.json"))
counts = {}


def source(*parts):
    return os.path.join(SOURCE_DIR, *parts)


def cpu_limit(seconds):
    return lambda: resource.setrlimit(resource.RLIMIT_CPU, (seconds, seconds))


def latsim(*args, cpu_s=60):
    return subprocess.run([LATSIM, *args], capture_output=True, preexec_fn=cpu_limit(cpu_s))


def one_line_error(what, proc, names=()):
    """The contract of a refusal: exit 2, one line, readable, naming each of `names`."""
    err = proc.stderr.decode("utf-8", "replace")
    lines = [x for x in err.splitlines() if ": warning: " not in x]
    check(proc.returncode == 2, f"{what}: exit {proc.returncode}, want 2: {err[-300:]!r}")
    check(len(lines) == 1, f"{what}: {len(lines)} lines on stderr, want 1: {err[-300:]!r}")
    check("Traceback" not in err, f"{what}: a traceback")
    check(all(len(x) <= MAX_LINE for x in lines), f"{what}: a line of {max(map(len, lines), default=0)} characters")
    check(not any(ord(c) < 0x20 and c != "\n" for c in err), f"{what}: a raw control character: {err[:200]!r}")
    for name in names:
        check(bool(lines) and name in lines[0], f"{what}: the line names no {name!r}: {lines[:1]}")


def count(kind, n=1):
    counts[kind] = counts.get(kind, 0) + n


def leftovers(directory):
    return [p for p in glob.glob(os.path.join(directory, "*")) if ".tmp" in os.path.basename(p)]


# ---------------------------------------------------------------- keys
HOSTILE = ["1e308", "-1e308", "9223372036854775808", "1e-308", '"NaN"', '"x\\u0000y"', '"\\u001b[31m"',
           '"' + "z" * 5000 + '"', "[[[[[[[[[[1]]]]]]]]]]", '"\\u00e9\\u6f22\\ud83d\\ude42"', "-1", "{}"]
if not FULL:
    HOSTILE = ["1e308", "-1e308", "9223372036854775808", "1e-308", '"x\\u0000y"', '"' + "z" * 5000 + '"', "-1"]
KEY_SCENARIOS = ["hmd_60hz_direct.json", "measurement/min_jerk_rig.json"]
if FULL:
    KEY_SCENARIOS += ["devices/quest2_72hz.json", "measurement/controller_rig.json", "hmd_60hz_serial_interrupt.json",
                      "pxpl5/rc_room_walk.json", "arp/gallery.json", "modern/timewarp.json", "pacing/capture.json",
                      "passthrough/quest3_passthrough.json", "prediction/real_head_motion_kalman.json",
                      "measured/quest2_ovr_72hz.json", "frameless/side_by_side.json"]


def leaves(value, pointer=""):
    if isinstance(value, dict):
        for k, v in value.items():
            yield from leaves(v, pointer + "/" + k.replace("~", "~0").replace("/", "~1"))
    elif isinstance(value, list) and value and not any(isinstance(x, (dict, list)) for x in value):
        yield pointer
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from leaves(v, f"{pointer}/{i}")
    else:
        yield pointer


def attack_keys():
    out = os.path.join(SCRATCH, "keys_run")
    for name in KEY_SCENARIOS:
        scenario = source("scenarios", name)
        resolved = json.loads(latsim("validate", scenario, "--resolved").stdout)
        for pointer in leaves(resolved):
            if pointer.startswith(("/description", "/include")):
                continue
            for value in HOSTILE:
                count("keys/validate")
                sets = ["--set", f"{pointer}={value}"]
                what = f"{name} {pointer}={value[:20]}"
                proc = latsim("validate", scenario, *sets, cpu_s=20)
                if proc.returncode != 0:
                    one_line_error(f"validate {what}", proc, [scenario, "/"])
                    continue
                if value == "-1":
                    continue
                # Validated: a short run ends, exit 0 or 2, and leaves nothing.
                count("keys/run")
                shutil.rmtree(out, ignore_errors=True)
                proc = latsim("run", scenario, *sets, "--set", "/duration_s=0.3", "-q", "--out", out, cpu_s=20)
                check(proc.returncode in (0, 2), f"run {what}: exit {proc.returncode} after validate passed: "
                      f"{proc.stderr[-300:]!r}")
                if proc.returncode == 2:
                    one_line_error(f"run {what}", proc, [scenario])
                check(not leftovers(SCRATCH), f"run {what}: left {leftovers(SCRATCH)}")
                for left in leftovers(SCRATCH):
                    shutil.rmtree(left, ignore_errors=True)


# ---------------------------------------------------------------- options
# 2^64 is refused by integer options only (a float of 1.8e19 is a legal bound).
NUMBER_VALUES = ["-1", "", "nan", "inf", "1e-400", "9" * 3000, "\x1b[31m"]
INTEGER_OPTIONS = {"--seed", "--replication", "--max", "-j", "--stale-after", "--replications", "--top",
                   "--gantt-limit", "--process-id"}
TEXT_VALUES = ["", "\x1b[31m", "9" * 3000]


def corpus(kind, duration_s, ledger=False, sweep_keep=None):
    """A scratch folder for one attack with a run of BASE in it (and, given sweep_keep, a sweep of two points
    whose `keep` is sweep_keep, "" for none): (folder, run directory, sweep directory or None)."""
    work = os.path.join(SCRATCH, kind)
    os.makedirs(work)
    run_dir = os.path.join(work, "run")
    proc = latsim("run", BASE, "--set", f"/duration_s={duration_s}", *(["--ledger"] if ledger else []), "-q",
                  "--out", run_dir)
    check(proc.returncode == 0, f"{kind} corpus run: {proc.stderr[-300:]!r}")
    if sweep_keep is None:
        return work, run_dir, None
    sweep_file = os.path.join(work, "sweep.json")
    with open(sweep_file, "w") as f:
        json.dump({"base": BASE, "overrides": {"/duration_s": duration_s}, **({"keep": sweep_keep} if sweep_keep else {}),
                   "axes": [{"pointer": "/tracker/rate_hz", "values": [60, 120]}]}, f)
    sweep_dir = os.path.join(work, "sweep")
    proc = latsim("sweep", sweep_file, "--out", sweep_dir, "-j", "2")
    check(proc.returncode == 0, f"{kind} corpus sweep: {proc.stderr[-300:]!r}")
    return work, run_dir, sweep_dir


def attack_options():
    work, run_dir, sweep_dir = corpus("options", 0.5, sweep_keep="")
    sweep_file = os.path.join(work, "sweep.json")
    capture = source("scenarios", "measured", "captures", "test_case_0.csv")
    out = os.path.join(work, "out")
    vary = ["--vary", "/pipeline/render/fixed_ms=1:10", "--minimise", "motion_to_photon_ms.mean"]
    levels = ["--vary", "/tracker/rate_hz=60,120", "--metric", "motion_to_photon_ms.mean"]
    # (option, command line before it): numbers, whose every value above is refused.
    numbers = [("--seed", ["run", BASE, "--out", out]), ("--replication", ["run", BASE, "--out", out]),
               ("--max-events", ["run", BASE, "--out", out]), ("--max-events", ["validate", BASE]),
               ("--threshold", ["capacity", BASE]), ("--max", ["capacity", BASE]),
               ("-j", ["sweep", sweep_file, "--out", out]), ("--stale-after", ["sweep", sweep_file, "--out", out]),
               ("--tolerance", ["optimise", BASE, *vary]), ("--replications", ["optimise", BASE, *vary]),
               ("--seed", ["fidelity", BASE, "--out", out, *levels]), ("--top", ["report", run_dir]),
               ("--gantt-limit", ["report", run_dir]), ("--ks-threshold", ["compare", capture, run_dir, "--out", out]),
               ("--mean-tolerance", ["compare", capture, run_dir, "--out", out]),
               ("--process-id", ["compare", capture, run_dir, "--out", out])]
    texts = [("--shard", ["sweep", sweep_file, "--out", out]), ("--keep", ["sweep", sweep_file, "--out", out]),
             ("--pointer", ["capacity", BASE]), ("--metric", ["capacity", BASE]),
             ("--minimise", ["optimise", BASE, "--vary", "/pipeline/render/fixed_ms=1:10"]),
             ("--constraint", ["optimise", BASE, *vary]), ("--vary", ["optimise", BASE, "--minimise", "frames_missed"]),
             ("--metric", ["fidelity", BASE, "--out", out, "--vary", "/tracker/rate_hz=60,120"]),
             ("--vary", ["fidelity", BASE, "--out", out, "--metric", "frames_missed"]),
             ("--figure", ["report", sweep_dir]), ("--figures", ["report", sweep_dir]),
             ("--format", ["schema"]), ("--set", ["run", BASE, "--out", out])]
    cases = [(option, prefix, value, True) for option, prefix in numbers for value in NUMBER_VALUES]
    cases += [(option, prefix, "18446744073709551616", True) for option, prefix in numbers if option in INTEGER_OPTIONS]
    cases += [(option, prefix, value, False) for option, prefix in texts for value in TEXT_VALUES]
    # An --out that no file system holds: refused before the run, not after it (exit 1).
    for prefix in (["run", BASE], ["fidelity", BASE, *levels], ["sweep", sweep_file], ["compare", capture, run_dir]):
        cases.append(("--out", prefix, "n" * 300, True))
        cases.append(("--out", prefix, "/".join(["d"] * 2100), True))
    for option, prefix, value, must_refuse in cases:
        count("options/" + prefix[0])
        shutil.rmtree(out, ignore_errors=True)
        before = {d: sorted(os.listdir(d)) for d in (work, run_dir, sweep_dir)}
        proc = latsim(*prefix, option, value, cpu_s=30)
        what = f"{prefix[0]} {option} {value[:12]!r}"
        if must_refuse or proc.returncode != 0:
            # A number option's line names the option; a text option's may
            # instead quote the value where it says what is wrong with it.
            named = proc.stderr.decode("utf-8", "replace")
            shown = option if option != "-j" else "--jobs"
            quoted = '"' + value.replace("\x1b", "\\x1B")[:12]
            one_line_error(what, proc, [shown] if must_refuse or quoted not in named else [])
            check(not os.path.exists(out) and before == {d: sorted(os.listdir(d)) for d in before},
                  f"{what}: made files")
            check(b"1.79769" not in proc.stderr and b"e+308" not in proc.stderr, f"{what}: DBL_MAX printed")


# ---------------------------------------------------------------- captures
CAPTURES = {"presentmon": "test_case_0.csv", "presentmon_v1": "test_case_0_v1.csv",
            "ovr_metrics": "ovr-metrics/OGMP_1.csv", "vrapi": "vrapi/vrapi_stats_lines.txt"}


def damaged_captures(data):
    """(name, bytes, must be refused)"""
    lines = data.split(b"\n")
    header, body = lines[0], lines[1:]
    third = len(data) // 3
    yield "nul_byte", data[:third] + b"\x00" + data[third:], True
    yield "column_twice", header + b"," + header + b"\n" + b"\n".join(x + b"," + x for x in body if x), True
    yield "empty", b"", True
    yield "binary", bytes(range(256)) * 64, True
    yield "long_line", header + b"\n" + b"9" * 200000 + b"\n" + b"\n".join(body), False
    yield "truncated", data[:len(data) * 2 // 3], False
    yield "header_only", header + b"\n", False
    yield "bom_crlf", b"\xef\xbb\xbf" + data.replace(b"\n", b"\r\n"), False


def attack_captures():
    work, run_dir, _ = corpus("captures", 1)
    files = {k: source("scenarios", "measured", "captures", v) for k, v in CAPTURES.items()}
    files["steamvr"] = source("tests", "models", "capture", "data", "steamvr_frame_timing.csv")
    for kind, path in files.items():
        with open(path, "rb") as f:
            data = f.read()
        for name, damaged, must_refuse in damaged_captures(data):
            count("captures/compare")
            capture = os.path.join(work, f"{kind}_{name}.csv")
            with open(capture, "wb") as f:
                f.write(damaged)
            out = os.path.join(work, "out")
            shutil.rmtree(out, ignore_errors=True)
            proc = latsim("compare", capture, run_dir, "--out", out, "--no-plots")
            what = f"compare {kind} {name}"
            check(proc.returncode in (0, 2), f"{what}: exit {proc.returncode}: {proc.stderr[-300:]!r}")
            if must_refuse or proc.returncode == 2:
                one_line_error(what, proc, [capture])
                check(not os.path.exists(out), f"{what}: made {out}")


# ---------------------------------------------------------------- results
def snapshot(directory):
    found = {}
    for root, dirs, files in os.walk(directory):
        for name in files + dirs:
            path = os.path.join(root, name)
            found[path] = open(path, "rb").read() if os.path.isfile(path) else None
    return found


def rewrite(path, transform):
    with open(path, "rb") as f:
        data = f.read()
    with open(path, "wb") as f:
        f.write(transform(data))


def to_directory(path):
    os.remove(path)
    os.mkdir(path)


def attack_results():
    work, run_dir, sweep_dir = corpus("results", 1, ledger=True, sweep_keep="first")
    nul = lambda d: d[:200] + b"\x00" + d[200:]  # noqa: E731
    escape = lambda d: d.replace(b"e", b"\x1b[2J", 3)  # noqa: E731
    utf16 = lambda d: d.decode("utf-8").encode("utf-16")  # noqa: E731
    # (directory, file, how, damage): every one is refused, naming the file.
    cases = [(run_dir, "summary.json", "NUL", nul), (run_dir, "summary.json", "escape", escape),
             (run_dir, "summary.json", "UTF-16", utf16),
             (run_dir, "summary.json", "deep", lambda d: b"[" * 100000 + b"]" * 100000),
             (run_dir, "summary.json", "-1e300", lambda d: d.replace(b'"mean": ', b'"mean": -1e300, "was": ', 1)),
             (sweep_dir, "results.csv", "NUL", nul), (sweep_dir, "results.csv", "escape", escape),
             (sweep_dir, "results.csv", "UTF-16", utf16)]
    for number, (pristine, name, how, damage) in enumerate(cases):
        count("results/report")
        case_dir = os.path.join(work, f"case_{number}")
        shutil.copytree(pristine, case_dir)
        rewrite(os.path.join(case_dir, name), damage)
        before = snapshot(case_dir)
        proc = latsim("report", case_dir)
        what = f"report {name} {how}"
        err = proc.stderr.decode("utf-8", "replace")
        # Progress lines come only when the work before the damage takes seconds.
        proc.stderr = "\n".join(x for x in err.splitlines() if not x.startswith("report: ") or name in x).encode()
        one_line_error(what, proc, [name])
        check(snapshot(case_dir) == before, f"{what}: the report changed the directory")
    # A file turned into a directory: one line naming the run directory, never a traceback.
    count("results/report")
    case_dir = os.path.join(work, "summary_directory")
    shutil.copytree(run_dir, case_dir)
    to_directory(os.path.join(case_dir, "summary.json"))
    one_line_error("report summary.json a directory", latsim("report", case_dir), [case_dir])


# ---------------------------------------------------------------- signals
def stop_while_busy(what, argv, out, sig, busy_cpu_s=0.2):
    """Starts argv, waits until it has spent busy_cpu_s of CPU (in the phase), signals it, checks the contract."""
    count("signals/" + os.path.basename(argv[1]))
    child = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while child.poll() is None and cpu_seconds(child.pid) < busy_cpu_s and time.monotonic() < deadline:
        time.sleep(0.005)
    check(child.poll() is None, f"{what}: ended before its signal (exit {child.returncode})")
    sent = time.monotonic()
    child.send_signal(sig)
    _, err = child.communicate(timeout=60)
    took = time.monotonic() - sent
    lines = [x for x in err.decode("utf-8", "replace").splitlines() if ": warning: " not in x]
    check(child.returncode == 128 + sig, f"{what}: exit {child.returncode}, want {128 + sig}")
    check(took < BOUND_S, f"{what}: {took:.2f} s to stop")
    check(len(lines) == 1 and f"stopped by {signal.Signals(sig).name}" in lines[0], f"{what}: stderr {lines}")
    check(not os.path.exists(out) and not glob.glob(out + ".tmp*"), f"{what}: left {out}")


def attack_signals():
    work = os.path.join(SCRATCH, "signals")
    os.makedirs(work)
    # A PresentMon capture of about 120 MB: its reading takes seconds.
    big = os.path.join(work, "big.csv")
    with open(source("scenarios", "measured", "captures", "test_case_0.csv"), "rb") as f:
        lines = f.read().split(b"\n")
    block = b"\n".join(x for x in lines[1:] if x.startswith(b"dwm.exe")) + b"\n"
    with open(big, "wb") as f:
        f.write(lines[0] + b"\n")
        while f.tell() < 120_000_000:
            f.write(block)
    scenario = os.path.join(work, "trace.json")
    with open(scenario, "w") as f:
        json.dump({"duration_s": 1, "motion": {"type": "still"}, "tracker": {"rate_hz": 60},
                   "display": {"refresh_hz": 60}, "pipeline": {"type": "double_buffer", "render": {
                       "trace": {"file": big, "column": "MsGPUBusy", "application": "dwm.exe"}}}}, f)
    run_dir = os.path.join(work, "run")
    proc = latsim("run", BASE, "--set", "/duration_s=1", "-q", "--out", run_dir)
    check(proc.returncode == 0, f"signals corpus run: {proc.stderr[-300:]!r}")
    for sig in (signal.SIGTERM, signal.SIGINT):
        out = os.path.join(work, "trace_run")
        stop_while_busy(f"run reading a capture, {sig.name}", [LATSIM, "run", scenario, "--out", out], out, sig)
        out = os.path.join(work, "compare")
        stop_while_busy(f"compare reading a capture, {sig.name}", [LATSIM, "compare", big, run_dir, "--out", out],
                        out, sig)
    os.remove(big)
    # A sweep interrupted three ways, then run again: the table of an undisturbed sweep.
    sweep_file = os.path.join(work, "sweep.json")
    with open(sweep_file, "w") as f:
        json.dump({"base": BASE, "overrides": {"/duration_s": 20}, "replications": 2,
                   "axes": [{"pointer": "/tracker/rate_hz", "values": [60, 90, 120]}]}, f)
    reference = os.path.join(work, "sweep_reference")
    proc = latsim("sweep", sweep_file, "--out", reference, "-j", "2")
    check(proc.returncode == 0, f"reference sweep: {proc.stderr[-300:]!r}")
    for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGKILL):
        count("signals/sweep")
        out = os.path.join(work, f"sweep_{sig.name}")
        child = subprocess.Popen([LATSIM, "sweep", sweep_file, "--out", out, "-j", "2"], stdout=subprocess.DEVNULL,
                                 stderr=subprocess.PIPE)
        done = os.path.join(out, "done")
        deadline = time.monotonic() + 120
        while child.poll() is None and time.monotonic() < deadline and not (
                os.path.isdir(done) and os.listdir(done)):
            time.sleep(0.01)
        child.send_signal(sig)
        child.communicate(timeout=60)
        check(child.returncode in (128 + sig, -sig), f"sweep {sig.name}: exit {child.returncode}")
        proc = latsim("sweep", sweep_file, "--out", out, "-j", "2")
        check(proc.returncode == 0, f"sweep resumed after {sig.name}: {proc.stderr[-300:]!r}")
        check(table(out) == table(reference), f"sweep resumed after {sig.name}: a table unlike the undisturbed one")


shutil.rmtree(SCRATCH, ignore_errors=True)
os.makedirs(SCRATCH)
for attack in (attack_options, attack_captures, attack_results, attack_signals, attack_keys):
    started = time.monotonic()
    attack()
    print(f"{attack.__name__}: {time.monotonic() - started:.1f} s")
print("attacks: " + ", ".join(f"{k} {v}" for k, v in sorted(counts.items())))
finish("hardening campaign")
