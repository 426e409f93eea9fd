"""Frame-timing captures for latsim compare: a PresentMon CSV of any of its
three column generations, or a run's presentmon.csv, read into the four
per-frame quantities compare sets side by side.

A quantity is read from the first of its columns the header has (the current
PresentMon name first, then v2's, then v1's); a capture without any of them
has no values for it. `NA` and empty cells are frames without that value and
are counted, not used; any other cell that is not a number is bad input. In v1
captures a frame with `Dropped` = 1 was never displayed: no display latency.
"""

import csv

# (key as written in compare's outputs, label, columns that hold it, by generation).
QUANTITIES = [
    ("MsBetweenPresents", "frame interval (ms)", ["MsBetweenPresents", "FrameTime", "msBetweenPresents"]),
    ("MsCPUBusy", "CPU busy (ms)", ["MsCPUBusy", "CPUBusy"]),
    ("MsGPUBusy", "GPU busy (ms)", ["MsGPUBusy", "GPUBusy", "msGPUActive"]),
    ("MsUntilDisplayed", "present to display (ms)", ["MsUntilDisplayed", "msUntilDisplayed"]),
]
# Columns of the quantities that only a displayed frame has.
DISPLAY_COLUMNS = {"MsUntilDisplayed", "msUntilDisplayed"}
# Larger files are refused before they are read (PresentMon writes about 300 bytes a frame).
MAX_BYTES = 256 * 1024 * 1024


class BadCapture(Exception):
    """A capture that cannot be read: the message names the file and, for a cell, line, column and value."""


class Capture:
    """The selected process's values of each quantity, and what was skipped."""

    def __init__(self, path, process):
        self.path = path
        self.process = process  # (Application, ProcessID) selected, or None for a file without them
        self.columns = {}  # quantity key -> the column read (absent: the file has none)
        self.values = {key: [] for key, _, _ in QUANTITIES}
        self.skipped = {key: 0 for key, _, _ in QUANTITIES}  # NA or empty cells, frames not displayed
        self.rows = 0


def _open_rows(path):
    import os
    import stat
    try:
        st = os.stat(path)
    except OSError as e:
        raise BadCapture(f"{path}: {e.strerror}") from None
    if not stat.S_ISREG(st.st_mode):
        raise BadCapture(f"{path}: not a regular file")
    if st.st_size > MAX_BYTES:
        raise BadCapture(f"{path}: larger than {MAX_BYTES // (1024 * 1024)} MiB")
    try:
        with open(path, encoding="utf-8-sig", newline="") as f:
            return list(csv.reader(f))
    except UnicodeDecodeError as e:
        raise BadCapture(f"{path}: not UTF-8 text (byte {e.start})") from None
    except (OSError, csv.Error) as e:
        raise BadCapture(f"{path}: {e}") from None


def _processes(header, rows):
    """(Application, ProcessID) of each data row; None when the file does not say."""
    app = header.index("Application") if "Application" in header else None
    pid = header.index("ProcessID") if "ProcessID" in header else None
    if app is None and pid is None:
        return None
    return [(row[app] if app is not None else "", row[pid] if pid is not None else "") for row in rows]


def _select(path, keys, application, process_id):
    """The one process the capture is read for: the chosen one, or the only one."""
    present = sorted(set(keys))
    chosen = [k for k in present if (application is None or k[0] == application) and
              (process_id is None or k[1] == str(process_id))]
    listing = ", ".join(f"{a} {p}".strip() for a, p in present)
    if not chosen:
        raise BadCapture(f"{path}: no frames of the process asked for; it holds {listing}")
    if len(chosen) > 1:
        raise BadCapture(f"{path}: holds several processes ({listing}): choose one with --application or --process-id")
    return chosen[0]


def read_capture(path, application=None, process_id=None):
    """Reads the quantities of one process of the CSV at `path` (raises BadCapture)."""
    table = _open_rows(path)
    if not table or not table[0]:
        raise BadCapture(f"{path}: empty file, no header")
    header = [h.strip() for h in table[0]]
    # Data rows, with their line numbers (the header is line 1); blank lines are not frames.
    rows = [(n, row) for n, row in enumerate(table[1:], 2) if any(cell.strip() for cell in row)]
    for n, row in rows:
        if len(row) != len(header):
            raise BadCapture(f"{path}: line {n}: {len(row)} fields where the header has {len(header)}")
    keys = _processes(header, [row for _, row in rows])
    process = None
    if keys is not None and rows:
        process = _select(path, keys, application, process_id)
        rows = [r for r, k in zip(rows, keys) if k == process]
    capture = Capture(path, process)
    capture.rows = len(rows)
    dropped = header.index("Dropped") if "Dropped" in header else None
    for key, _, names in QUANTITIES:
        name = next((c for c in names if c in header), None)
        if name is None:
            continue
        capture.columns[key] = name
        col = header.index(name)
        for n, row in rows:
            cell = row[col].strip()
            not_displayed = name in DISPLAY_COLUMNS and dropped is not None and row[dropped].strip() == "1"
            if cell in ("", "NA") or not_displayed:
                capture.skipped[key] += 1
                continue
            try:
                value = float(cell)
            except ValueError:
                raise BadCapture(f"{path}: line {n}, column {name}: {cell!r} is not a number") from None
            if value != value or value in (float("inf"), float("-inf")):
                raise BadCapture(f"{path}: line {n}, column {name}: {cell!r} is not a finite number")
            capture.values[key].append(value)
    if not capture.columns:
        wanted = ", ".join(names[0] for _, _, names in QUANTITIES)
        raise BadCapture(f"{path}: none of the columns compared ({wanted}) is in its header")
    return capture
