"""Reading one result file as latsim writes it, or refusing it as damaged.

summary.json, a results table and their numbers are checked as they are read:
a file that cannot be what latsim wrote (cut short, junk, a control character,
NaN, a number beyond any figure, a distribution whose statistics are not
numbers) is a DamagedFile whose one-line message names the file and says why.
"""

import csv
import io
import json
import math
import re

# A distribution's statistics as figures.json and results.sqlite give them.
STATISTICS = ("count", "mean", "stddev", "min", "p50", "p90", "p99", "p999", "max")


# No figure latsim writes comes near this (picoseconds of a 1e6 s run are 1e18,
# but result files hold milliseconds and counts): a larger number, like NaN
# or Infinity, marks a damaged file, which would otherwise overflow a plot.
LARGEST_NUMBER = 1e15


class DamagedFile(ValueError):
    """A result file that cannot be what latsim wrote: its one-line message names it and says why."""

    def __init__(self, path, reason):
        text = " ".join(str(reason).split())
        super().__init__(f"{path}: {text[:300] + '…' if len(text) > 300 else text}")
        self.path = path


def checked_number(text):
    """float(text) when it is a number within ±LARGEST_NUMBER, else ValueError."""
    value = float(text)
    if not math.isfinite(value) or abs(value) > LARGEST_NUMBER:
        raise ValueError(f"{str(text)[:40]} is beyond ±{LARGEST_NUMBER:g}")
    return value


def _refuse_constant(name):
    raise ValueError(f"{name} is not a number a result holds")


def read_json(path, expected=dict):
    """A result file's JSON object (or `expected`: list); DamagedFile when it is not one (truncated, junk, NaN,
    1e308)."""
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f, parse_float=checked_number, parse_int=lambda t: int(checked_number(t)),
                            parse_constant=_refuse_constant)
    except FileNotFoundError:
        raise DamagedFile(path, "missing (removed while the report read the directory?)") from None
    except OSError as e:
        # A folder where a file belongs, or no permission to read: an input that cannot be read, not a failed write.
        raise DamagedFile(path, f"cannot be read ({e.strerror or e})") from None
    except (ValueError, UnicodeDecodeError, RecursionError) as e:
        raise DamagedFile(path, f"not a whole result file ({e})") from None
    if not isinstance(doc, expected):
        raise DamagedFile(path, f"expected a JSON {'object' if expected is dict else 'array'}, found {type(doc).__name__}")
    return ResultDoc(doc, path) if isinstance(doc, dict) else doc


class ResultDoc(dict):
    """A result file's object, knowing its file: a value found damaged later names it."""

    def __init__(self, doc, source):
        super().__init__(doc)
        self.source = source


CONTROL_CHARACTER = re.compile("[\\x00-\\x08\\x0b\\x0c\\x0e-\\x1f\\x7f]")


def _is_number(value):
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def checked_distributions(path, node, pointer=""):
    """`node` (a summary) when every distribution in it is as latsim writes one: its statistics numbers, its
    histogram [lower edge, count] pairs with counts of 0 or more; DamagedFile naming the file and pointer."""
    if isinstance(node, list):
        for i, child in enumerate(node):
            checked_distributions(path, child, f"{pointer}/{i}")
    if not isinstance(node, dict):
        return node
    if "histogram" in node or "histogram_counts" in node:
        for stat in STATISTICS:
            if stat in node and not _is_number(node[stat]):
                raise DamagedFile(path, f"{pointer}/{stat}: expected a number")
        buckets = node.get("histogram", [])
        if not isinstance(buckets, list):
            raise DamagedFile(path, f"{pointer}/histogram: expected a list of [lower edge, count]")
        for i, bucket in enumerate(buckets):
            if not (isinstance(bucket, list) and len(bucket) == 2 and all(_is_number(v) for v in bucket)
                    and bucket[1] >= 0):
                raise DamagedFile(path, f"{pointer}/histogram/{i}: expected [lower edge, count of 0 or more]")
        return node
    for key, child in node.items():
        checked_distributions(path, child, f"{pointer}/{key}")
    return node


def read_summary_file(path):
    """A run's summary.json, its distributions checked (checked_distributions)."""
    return checked_distributions(path, read_json(path))


def read_csv(path, required=()):
    """A result table's rows as dicts, every row as wide as the header; DamagedFile otherwise."""
    try:
        with open(path, encoding="utf-8", newline="") as f:
            text = f.read()
        # latsim ends every line of a table: a last line without its end was cut short.
        if text and not text.endswith("\n"):
            raise DamagedFile(path, "its last line has no end: the file was cut short")
        # latsim writes no control character into a table (a NUL or an escape
        # sequence in a cell or a column's name was read as text, exit 0).
        bad = CONTROL_CHARACTER.search(text)
        if bad:
            raise DamagedFile(path, f"line {text.count(chr(10), 0, bad.start()) + 1}: a control character "
                              f"(\\x{ord(bad.group()):02X}): not a table latsim writes")
        reader = csv.DictReader(io.StringIO(text, newline=""))
        rows = list(reader)
        header = reader.fieldnames or []
    except FileNotFoundError:
        raise DamagedFile(path, "missing (removed while the report read the directory?)") from None
    except DamagedFile:
        raise
    except OSError as e:
        # A folder where a file belongs, or no permission to read: an input that cannot be read, not a failed write.
        raise DamagedFile(path, f"cannot be read ({e.strerror or e})") from None
    except (ValueError, UnicodeDecodeError, csv.Error) as e:
        raise DamagedFile(path, f"not a whole result table ({e})") from None
    missing = [c for c in required if c not in header]
    if missing:
        raise DamagedFile(path, f"no column {missing[0]} in its header")
    for number, row in enumerate(rows, start=2):
        if None in row or None in row.values():
            given = sum(1 for k, v in row.items() if k is not None and v is not None) + len(row.get(None) or [])
            raise DamagedFile(path, f"line {number}: {given} fields, the header has {len(header)}")
    return rows


def cell(path, line, row, column, kind=float):
    """row[column] as a checked number (int or float); DamagedFile naming the file, line and column."""
    text = row.get(column)
    try:
        value = checked_number(text)
        if kind is int:
            if value != int(value):
                raise ValueError(f"{text} is not an integer")
            return int(value)
        return value
    except (TypeError, ValueError) as e:
        raise DamagedFile(path, f"line {line}: {column}: {e}" if text else f"line {line}: {column}: empty") from None
