"""Progress lines on stderr for long report work: quiet for work that ends
within a few seconds, then a line every few seconds."""

import sys
import time

# Work shorter than this says nothing; longer work says where it is this often.
QUIET_S = 2.0


class Progress:
    """Counts items of one task and prints "report: <task> i/n" now and then."""

    def __init__(self, task, total, clock=time.monotonic, out=sys.stderr):
        self.task, self.total, self.done = task, total, 0
        self.clock, self.out = clock, out
        self.next_line = clock() + QUIET_S
        self.printed = False

    def advance(self, count=1):
        self.done += count
        now = self.clock()
        if now >= self.next_line:
            print(f"report: {self.task} {self.done}/{self.total}", file=self.out, flush=True)
            self.next_line = now + QUIET_S
            self.printed = True

    def finish(self):
        if self.printed:
            print(f"report: {self.task} {self.done}/{self.total} done", file=self.out, flush=True)
