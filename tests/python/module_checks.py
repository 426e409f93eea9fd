"""What the Python module's tests share: recorded checks and the command line beside the module."""

import subprocess
import sys

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)
        print(f"FAIL: {what}")


def cli(latsim, *args, cwd=None):
    """`latsim ARGS` run to the end, its output as text."""
    return subprocess.run([latsim, *args], capture_output=True, text=True, cwd=cwd)


def finish(done):
    """Exits 1 after naming the count of failed checks, else prints `done`."""
    if failures:
        print(f"FAIL: {len(failures)} check(s)")
        sys.exit(1)
    print(done)
