"""A coverage-guided mutation fuzzer for Python readers, standard library only.

Coverage is line to line transitions (sys.settrace, Python 3.11 has no
sys.monitoring) in the files of the code under test only; an input that
reaches a transition no earlier input reached is kept in the corpus and
mutated further. The i-th input is a function of the seed and i alone (one
random.Random, the corpus in the order inputs were kept, hash seed 0 set by
the command), so a run of N executions is the same for the same seed; a run
bounded by seconds stops somewhere along that same sequence.
"""

import os
import random
import sys
import time

from mutations import mutate


class Coverage:
    """The set of (previous line, line) transitions in files under `roots` while on."""

    def __init__(self, roots):
        self.roots = tuple(os.path.abspath(r) + os.sep for r in roots)
        self._traced = {}  # code object's file name -> traced or not (the check is costly)
        self.features = set()
        self._last = 0

    def _wanted(self, filename):
        wanted = self._traced.get(filename)
        if wanted is None:
            wanted = self._traced[filename] = os.path.abspath(filename).startswith(self.roots)
        return wanted

    def _line(self, frame, event, _arg):
        if event == "line":
            here = hash((frame.f_code.co_filename, frame.f_lineno))
            self.features.add((self._last, here))
            self._last = here
        return self._line

    def _call(self, frame, _event, _arg):
        return self._line if self._wanted(frame.f_code.co_filename) else None

    def run(self, function):
        """function()'s result and the transitions it made."""
        self.features, self._last = set(), 0
        sys.settrace(self._call)
        try:
            return function(), self.features
        finally:
            sys.settrace(None)


class Input:
    """One damaged directory: a seed directory with one of its files replaced (content None: removed)."""

    def __init__(self, seed, file, kind, content):
        self.seed, self.file, self.kind, self.content = seed, file, kind, content


class Fuzzer:
    """Runs a target's inputs, keeps those that reach new transitions, collects the oracle's findings.

    A target has: seeds (name -> pristine directory), files(seed) -> [(relative path, kind)],
    execute(input) -> verdict (None when the contract holds, else a one-line description), and
    confirm(input, verdict) -> the verdict of a separate process (None: not reproduced)."""

    def __init__(self, target, seed, roots):
        self.target, self.rng = target, random.Random(seed)
        self.coverage = Coverage(roots)
        self.seen = set()
        self.corpus = []
        self.findings = {}  # signature -> (input, verdict)
        self.unconfirmed = 0
        self.executions = 0

    def _fresh(self):
        seed = self.rng.choice(sorted(self.target.seeds))
        file, kind = self.rng.choice(self.target.files(seed))
        with open(os.path.join(self.target.seeds[seed], file), "rb") as f:
            return Input(seed, file, kind, f.read())

    def _next(self):
        """The next input: a kept one or a seed's file, mutated (now and then the file removed)."""
        parent = self.rng.choice(self.corpus) if self.corpus and self.rng.random() < 0.8 else self._fresh()
        if self.rng.random() < 0.02:
            return Input(parent.seed, parent.file, parent.kind, None)
        return Input(parent.seed, parent.file, parent.kind, mutate(parent.content or b"", parent.kind, self.rng))

    def one(self, item):
        verdict, features = self.coverage.run(lambda: self.target.execute(item))
        self.executions += 1
        new = features - self.seen
        if new:
            self.seen |= new
            if item.content is not None:
                self.corpus.append(item)
        if verdict is not None:
            signature = _signature(verdict)
            if signature not in self.findings:
                confirmed = self.target.confirm(item, verdict)
                if confirmed is None:
                    self.unconfirmed += 1
                else:
                    self.findings[signature] = (item, confirmed)
                    print(f"fuzz: finding {len(self.findings)}: {confirmed}", file=sys.__stderr__, flush=True)
        return verdict

    def run(self, seconds, max_runs=None):
        """Executes every seed's files unchanged, then mutated inputs until the time or the count is spent."""
        start = time.monotonic()
        for seed in sorted(self.target.seeds):
            for file, kind in self.target.files(seed):
                with open(os.path.join(self.target.seeds[seed], file), "rb") as f:
                    verdict = self.one(Input(seed, file, kind, f.read()))
                if verdict is not None:
                    raise SystemExit(f"fuzz: the undamaged seed {seed} fails the contract: {verdict}")
        while time.monotonic() - start < seconds and (max_runs is None or self.executions < max_runs):
            self.one(self._next())
        return time.monotonic() - start


def _signature(verdict):
    """What tells two findings apart: the verdict without paths and numbers."""
    words = []
    for word in verdict.split():
        if "/" in word:
            word = "PATH"
        words.append("".join("9" if ch.isdigit() else ch for ch in word))
    return " ".join(words)[:160]
