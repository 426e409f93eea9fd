"""What every stop test checks: a command started, waited for until it is
in the phase named (its CPU time, a child process, a file: never a fixed
sleep), sent SIGTERM or SIGINT, then held to the contract (issue 47): exit
128 + the signal's number within BOUND_S, one line naming the signal, no
temporary ("*.tmp*") and no output of unfinished work left.
"""

import glob
import os
import re
import signal
import subprocess
import time

from sweep_checks import check

# The contract's bound on the time from the signal to the exit.
BOUND_S = 1.0


def leftovers(path):
    """Temporaries under or beside `path`."""
    parent, name = os.path.split(path.rstrip("/"))
    inside = [p for p in glob.glob(os.path.join(path, "**", "*"), recursive=True) if ".tmp" in os.path.basename(p)]
    return inside + glob.glob(os.path.join(parent, name + ".tmp*"))


def cpu_seconds(pid):
    """User plus system CPU time of a process (fields 14 and 15 of /proc/PID/stat), 0 when gone."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
    except OSError:
        return 0.0
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def children_of(pid):
    """Process ids whose parent is `pid` (from /proc)."""
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open(f"/proc/{entry}/stat") as f:
                    if int(f.read().rsplit(")", 1)[1].split()[1]) == pid:
                        found.append(int(entry))
            except (OSError, IndexError, ValueError):
                pass
    return found


def alive(pid):
    """Whether `pid` is a process that is not a zombie."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def wait_until(child, ready, what, limit_s=300):
    """Polls ready() while the child runs; a bounded wait, never a guess of the time."""
    deadline = time.monotonic() + limit_s
    while time.monotonic() < deadline and child.poll() is None and not ready():
        time.sleep(0.01)
    ok = child.poll() is None and ready()
    check(ok, f"{what}: never reached the phase to stop in (exit {child.poll()})")
    return ok


def stop(child, sig):
    """Sends `sig`; (exit status, seconds it took, stderr lines)."""
    sent = time.monotonic()
    child.send_signal(sig)
    try:
        _, err = child.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        child.kill()
        _, err = child.communicate()
    return child.returncode, time.monotonic() - sent, err.splitlines()


def expect_stopped(what, sig, result, out=None, phase_text=None):
    code, took, lines = result
    # Progress lines, and what finished levels of fidelity said before the stop.
    # The report's progress lines ("report: <task> i/n") come when its work takes seconds.
    lines = [line for line in lines if not (line.startswith(("run: simulated", "fidelity: ")) or ": warning: " in line
                                            or re.match(r"^report: .+ \d+/\d+( done)?$", line))
             or "stopped" in line]
    check(code == 128 + sig, f"{what}: exit {code}, want {128 + sig}")
    check(took < BOUND_S, f"{what}: took {took:.3f} s to stop")
    check(len(lines) == 1 and f"stopped by {signal.Signals(sig).name}" in lines[0], f"{what}: stderr {lines}")
    if phase_text:
        check(bool(lines) and phase_text in lines[-1], f"{what}: stopped elsewhere than {phase_text!r}: {lines}")
    if out:
        check(not os.path.exists(out), f"{what}: {out} left")
        check(not leftovers(out), f"{what}: temporaries left: {leftovers(out)}")


def gone_within(pids, seconds=BOUND_S):
    """Whether every process of `pids` has ended (or become a zombie) within `seconds`."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline and any(alive(p) for p in pids):
        time.sleep(0.01)
    return not any(alive(p) for p in pids)
