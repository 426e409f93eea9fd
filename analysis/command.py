"""The contract of every analysis script run as a command (latsim report,
compare's plots, fidelity's plot): whatever goes wrong is one line on stderr
naming the file, never a traceback, and what the command wrote so far is
taken back. Exit 0; 1 when a file cannot be written; 2 when a file read is
damaged; 130 or 143 when SIGINT or SIGTERM stopped it (latsim passes its
own stop request on as SIGTERM or SIGINT).
"""

import os
import signal
import sys


def _take_back():
    """Removes the files this process wrote (plotting.WRITTEN), when it wrote any."""
    plotting = sys.modules.get("plotting")
    if plotting is not None:
        plotting.remove_written()


def _one_line(text, limit=400):
    text = " ".join(str(text).split())
    return text if len(text) <= limit else text[:limit] + "…"


def readable(line, limit=400):
    """A line as latsim prints what a user gave (scenario/readable.hpp): control
    characters escaped (\\t, \\xNN), and past `limit` characters its start
    and its size."""
    out = "".join(("\\t" if c == "\t" else f"\\x{ord(c):02X}") if ord(c) < 0x20 or ord(c) == 0x7F else c
                  for c in line[:limit + 1])
    if len(line) > limit:
        out = out[:limit] + f"… ({len(line.encode('utf-8', 'replace'))} bytes)"
    return out


class ReadableLines:
    """stderr whose every line is readable(): whatever a script prints, an
    option or a cell it quotes included (report --figure once echoed an
    escape sequence raw and 3,000 characters whole), stays one line of a
    readable length."""

    def __init__(self, stream, limit=400):
        self._stream, self._limit, self._pending = stream, limit, ""

    def write(self, text):
        self._pending += text
        while "\n" in self._pending:
            line, self._pending = self._pending.split("\n", 1)
            self._stream.write(readable(line, self._limit) + "\n")
        return len(text)

    def flush(self):
        if self._pending:
            self._stream.write(readable(self._pending, self._limit))
            self._pending = ""
        self._stream.flush()

    def __getattr__(self, name):
        return getattr(self._stream, name)


def _main_flushed(main, argv):
    try:
        return main(argv)
    finally:
        sys.stderr.flush()


def run_main(name, main, argv, reads=None):
    """main(argv)'s exit code, under the contract above. `reads`: the file or directory the command reads,
    which the line names when what went wrong is a damage no check of the reader foresaw."""
    stopped_by = []
    sys.stderr = ReadableLines(sys.stderr)

    def on_term(signum, _frame):
        stopped_by.append(signum)
        raise KeyboardInterrupt
    signal.signal(signal.SIGTERM, on_term)
    try:
        return _main_flushed(main, argv)
    except KeyboardInterrupt:
        _take_back()
        print(f"{name}: stopped by {'SIGTERM' if stopped_by else 'SIGINT'}; nothing written", file=sys.stderr)
        sys.stderr.flush()
        # At once: an interpreter that unloads matplotlib takes longer than
        # the second a stop may take (latsim's watchdog would kill it).
        os._exit(143 if stopped_by else 130)
    except OSError as e:
        # A full disk or a read-only directory.
        _take_back()
        where = f"{e.filename}: " if e.filename else ""
        print(_one_line(f"{name}: cannot write {where}{e.strerror or e}"), file=sys.stderr)
        return 1
    except RecursionError as e:
        _take_back()
        print(_one_line(f"{name}: a file read is nested too deeply ({e}); nothing written"), file=sys.stderr)
        return 2
    except ValueError as e:
        # latsim_results.DamagedFile names the file; a ValueError of its own still gets one line.
        _take_back()
        print(_one_line(f"{name}: {e}; nothing written"), file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001  (what no check foresaw: still one line, never a traceback)
        _take_back()
        where = f"{reads}: " if reads else ""
        print(_one_line(f"{name}: {where}a file read is not as latsim writes it ({type(e).__name__}: {e}); "
                        "nothing written"), file=sys.stderr)
        return 2
