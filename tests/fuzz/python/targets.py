"""The Python readers under fuzzing: `latsim report` (analysis/report.py) and
compare's plotting step (analysis/compare.py), with the contract's oracle.

Each input is run in this process (fast: one import of matplotlib) and, when
it breaks the contract, again as the command latsim runs, in a process of its
own, which decides whether it is a finding. The contract (issue 47): a
damaged input reads fine (exit 0) or gives exit 2 and exactly one line on
stderr naming the damaged directory's file; never a traceback, never a hang,
nothing written.
"""

import contextlib
import hashlib
import io
import os
import shutil
import signal
import subprocess
import sys


class Hang(BaseException):
    """An input that ran past the time limit (a BaseException: no reader catches it)."""


def _on_alarm(_signum, _frame):
    raise Hang


def snapshot(directory):
    """Every file and folder under `directory` with its size and content's digest."""
    found = {}
    for root, dirs, files in os.walk(directory):
        for name in dirs:
            found[os.path.relpath(os.path.join(root, name), directory) + "/"] = None
        for name in files:
            path = os.path.join(root, name)
            with open(path, "rb") as f:
                found[os.path.relpath(path, directory)] = hashlib.blake2b(f.read(), digest_size=8).digest()
    return found


def _progress_line(line):
    """report's progress lines ("report: <task> i/n"), which may come before the error."""
    last = line.rsplit(" ", 1)[-1]
    return line.startswith("report: ") and "/" in last and last.replace("/", "").isdigit()


def verdict(directory, code, stderr, before, after):
    """None when the outcome keeps the contract, else what breaks it, in one line."""
    if code is None:
        return "hang: still running at the time limit"
    if "Traceback" in stderr:
        last = [line for line in stderr.splitlines() if line.strip()][-1]
        return f"traceback: {last.strip()[:200]}"
    lines = [line for line in stderr.splitlines() if line.strip() and not _progress_line(line)]
    if code == 0:
        return None
    if code != 2:
        return f"exit {code} (a damaged file is exit 2): {lines[0][:200] if lines else 'nothing on stderr'}"
    if len(lines) != 1:
        return f"{len(lines)} lines on stderr: {' | '.join(lines)[:200]}"
    if directory not in lines[0]:
        return f"the line names no file of the directory: {lines[0][:200]}"
    if before != after:
        changed = sorted(set(before.items()) ^ set(after.items()))
        return f"files left or changed: {', '.join(sorted({k for k, _ in changed}))[:200]}"
    return None


class _Whole:
    """A seed directory as latsim wrote it (no file replaced)."""

    def __init__(self, seed):
        self.seed, self.file = seed, None


class ReaderTarget:
    """One reader: its script, its seed directories and which of their files are damaged."""

    def __init__(self, name, script, seeds, work, latsim, time_limit_s=20.0, fast_plots=True):
        self.name, self.script, self.seeds = name, script, seeds
        self.work, self.latsim, self.time_limit_s = work, latsim, time_limit_s
        self.analysis = os.path.dirname(os.path.abspath(script))
        self._files = {}
        self._opened = None  # while files() looks: every file the reader opened for reading
        self._recording = False
        sys.addaudithook(self._audit)
        sys.path.insert(0, self.analysis)
        import command
        import latsim_results
        import plotting
        import progress
        self.command, self.results, self.plotting = command, latsim_results, plotting
        progress.QUIET_S = float("inf")  # progress lines depend on the clock: none here
        if fast_plots:
            plotting.save = self._save_small
        module = os.path.splitext(os.path.basename(script))[0]
        self.module = __import__(module)

    def _save_small(self, fig, base_path, formats=("png", "svg")):
        """plotting.save drawing one small PNG: the figure is laid out and drawn as in a
        report (what overflows there overflows here), and the file is written and taken
        back alike; the confirming process draws in full."""
        final = f"{base_path}.png"
        try:
            fig.savefig(io.BytesIO(), format="png", dpi=10)
            with open(final, "wb") as f:
                f.write(b"")
            self.plotting.WRITTEN.append(final)
        finally:
            self.plotting.plt.close(fig)

    def files(self, seed):
        """The seed's files the reader opens (seen by an audit hook while it reads the seed once), with
        their kind: damaging a file it never opens would only run it again on a whole directory."""
        if seed not in self._files:
            where = os.path.join(self.work, "exec", self.name)
            self._opened = set()
            try:
                outcome = self.execute(_Whole(seed))
            finally:
                opened, self._opened = self._opened, None
            if outcome is not None:
                raise SystemExit(f"fuzz: the undamaged seed {seed} fails the contract: {outcome}")
            pristine = snapshot(self.seeds[seed])
            found = []
            for path in sorted(opened):
                relative = os.path.relpath(path, where)
                if relative in pristine and pristine[relative] is not None:
                    kind = "csv" if relative.endswith(".csv") else "json" if relative.endswith(".json") else "bytes"
                    found.append((relative, kind))
            self._files[seed] = found
        return self._files[seed]

    def _audit(self, event, args):
        if self._recording and self._opened is not None and event == "open" and isinstance(args[0], str):
            mode = args[1] if len(args) > 1 and isinstance(args[1], str) else "r"
            if "r" in mode and "+" not in mode:
                self._opened.add(os.path.abspath(args[0]))

    def materialise(self, item, where):
        """The seed directory copied to `where` with the input's file in place."""
        shutil.rmtree(where, ignore_errors=True)
        shutil.copytree(self.seeds[item.seed], where)
        if item.file is None:
            return where
        path = os.path.join(where, item.file)
        os.remove(path)
        if item.content is not None:
            with open(path, "wb") as f:
                f.write(item.content)
        return where

    def argv(self, directory):
        return [self.script, directory]

    def execute(self, item):
        directory = self.materialise(item, os.path.join(self.work, "exec", self.name))
        before = snapshot(directory)
        self.results.AXIS_LABELS.clear()
        self.plotting.WRITTEN.clear()
        getattr(self.module, "CHOSEN", []).clear()
        out, err = io.StringIO(), io.StringIO()
        previous = signal.signal(signal.SIGALRM, _on_alarm)
        signal.setitimer(signal.ITIMER_REAL, self.time_limit_s)
        try:
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                argv = self.argv(directory)
                main = self.module.main
                self._recording = True
                code = self.command.run_main(self.name, (lambda a: main(a[1:])) if self.name == "compare" else main,
                                             argv)
        except Hang:
            code = None
        except SystemExit as e:
            code = e.code
        finally:
            self._recording = False
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGALRM, previous)
            signal.signal(signal.SIGTERM, signal.SIG_DFL)
            self.plotting.plt.close("all")
        return verdict(directory, code, err.getvalue(), before, snapshot(directory))

    def command_line(self, directory):
        """What latsim runs: `latsim report DIR`; compare's plotting step as latsim starts it."""
        if self.name == "report":
            return [self.latsim, "report", directory]
        return [sys.executable, self.script, directory]

    def confirm(self, item, _verdict):
        """The verdict of the command in a process of its own (None: it keeps the contract there)."""
        directory = self.materialise(item, os.path.join(self.work, "confirm", self.name))
        before = snapshot(directory)
        try:
            proc = subprocess.run(self.command_line(directory), capture_output=True, text=True,
                                  timeout=max(60.0, 3 * self.time_limit_s), errors="replace")
            code, stderr = proc.returncode, proc.stderr
        except subprocess.TimeoutExpired as e:
            code, stderr = None, (e.stderr or b"").decode(errors="replace") if isinstance(e.stderr, bytes) else ""
        return verdict(directory, code, stderr, before, snapshot(directory))
