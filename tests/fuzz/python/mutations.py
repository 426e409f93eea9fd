"""Structure-aware mutations of result files: one damaged file from one whole file.

Every mutation is a function (data, rng) -> bytes of what a crash, a full
disk, a hand edit or a hostile writer could leave: bytes cut, flipped or
added; a table's rows and columns duplicated, deleted or given cells no
result holds; a JSON document's values replaced by extreme numbers, other
types or deep nesting, its keys deleted or repeated. All randomness comes
from the random.Random given, so that a seed names one sequence of inputs.
"""

import json

# Numbers no result holds, and spellings of them (JSON has no NaN: Python writes one anyway).
EXTREME_TEXTS = ["1e308", "-1e308", "1.8e308", "-0", "-0.0", "NaN", "nan", "inf", "-inf", "Infinity",
                 "9223372036854775808", "18446744073709551616", "-9223372036854775809", "4.9e-324",
                 "1e-320", "0", "-1", "1e15", "1000000000000001", "0x10", "1_000", " 5", "٣", "1/0", "60000/1001",
                 "1" * 5001, ""]
EXTREME_VALUES = [1e308, -1e308, -0.0, 2 ** 63, -2 ** 63 - 1, 2 ** 64, 4.9e-324, 1e15 + 2, -1, 0, 10 ** 400]
WRONG_TYPES = [None, True, False, "", "text", "\u0000", "$x^$", "$\\frac{$", "a/../../b", [], {}, [[]], [None], {"": None}, "\u202e\n\r", "ä" * 300]
JUNK = [b"\x00", b"\xff\xfe", b"\n", b"\r\n", b",", b"\"", b"{", b"}", b"[", b"]", b":", b"\\", b"\xc3\x28",
        b"\xe2\x80\xae", b"\t", b" ", b"#", b"LSRF", b"LSSEG1\n\x00"]


def _cut(data, rng):
    """Truncation: the file as a crash mid-write leaves it."""
    return data[:rng.randrange(len(data))] if data else b""


def _flip(data, rng):
    """One to eight bits flipped."""
    if not data:
        return data
    out = bytearray(data)
    for _ in range(rng.randint(1, 8)):
        i = rng.randrange(len(out))
        out[i] ^= 1 << rng.randrange(8)
    return bytes(out)


def _insert_junk(data, rng):
    i = rng.randrange(len(data) + 1)
    junk = rng.choice(JUNK) if rng.random() < 0.7 else bytes(rng.randrange(256) for _ in range(rng.randint(1, 16)))
    return data[:i] + junk * rng.randint(1, 4) + data[i:]


def _delete_range(data, rng):
    if not data:
        return data
    i = rng.randrange(len(data))
    return data[:i] + data[i + rng.randint(1, min(64, len(data) - i)):]


def _duplicate_range(data, rng):
    if not data:
        return data
    i = rng.randrange(len(data))
    j = min(len(data), i + rng.randint(1, 256))
    return data[:j] + data[i:j] + data[j:]


def _empty(data, rng):
    return b"" if rng.random() < 0.8 else rng.choice([b"\n", b" ", b"\x00", b"\xef\xbb\xbf"])


def _replace_number(data, rng):
    """A number in the text (any run of digits) replaced by an extreme spelling."""
    spans, i = [], 0
    while i < len(data):
        if data[i:i + 1].isdigit():
            j = i
            while j < len(data) and (data[j:j + 1].isdigit() or data[j:j + 1] in b".eE+-"):
                j += 1
            spans.append((i, j))
            i = j
        else:
            i += 1
    if not spans:
        return _insert_junk(data, rng)
    i, j = rng.choice(spans)
    return data[:i] + rng.choice(EXTREME_TEXTS[:-2]).encode() + data[j:]


BYTE_MUTATIONS = [_cut, _flip, _insert_junk, _delete_range, _duplicate_range, _empty, _replace_number]


# Tables (CSV): rows and columns.

def _split_table(data):
    lines = data.split(b"\n")
    ends = lines[-1] == b""
    return (lines[:-1] if ends else lines), ends


def _join_table(lines, ends):
    return b"\n".join(lines) + (b"\n" if ends else b"")


def _table_rows(data, rng):
    lines, ends = _split_table(data)
    if not lines:
        return data
    i = rng.randrange(len(lines))
    action = rng.randrange(4)
    if action == 0:
        lines.insert(i, lines[i])  # a row twice (the header too, now and then)
    elif action == 1 and len(lines) > 1:
        del lines[i]
    elif action == 2:
        lines[i] = lines[i] + b"," + rng.choice(EXTREME_TEXTS).encode()  # a row too wide
    else:
        lines.insert(rng.randrange(len(lines) + 1), b"")  # a blank line
    return _join_table(lines, ends)


def _table_columns(data, rng):
    lines, ends = _split_table(data)
    rows = [line.split(b",") for line in lines]
    width = max((len(r) for r in rows), default=0)
    if not width:
        return data
    c = rng.randrange(width)
    action = rng.randrange(3)
    for r in rows:
        if c >= len(r):
            continue
        if action == 0:
            r.insert(c, r[c])  # a column twice, its name too
        elif action == 1:
            del r[c]
        else:
            r[c], r[-1] = r[-1], r[c]  # two columns swapped under their names
    return _join_table([b",".join(r) for r in rows], ends)


def _table_cell(data, rng):
    lines, ends = _split_table(data)
    if not lines:
        return data
    i = rng.randrange(len(lines))
    cells = lines[i].split(b",")
    c = rng.randrange(len(cells))
    cells[c] = rng.choice(EXTREME_TEXTS + ["x", "\"", "\"a,b\"", "/", "..", "\x00"]).encode("utf-8")
    lines[i] = b",".join(cells)
    return _join_table(lines, ends)


TABLE_MUTATIONS = [_table_rows, _table_columns, _table_cell, _table_cell]


# JSON documents: values, keys and nesting.

def _nodes(doc, path=()):
    """Every (path, value) of a parsed document, in document order."""
    yield path, doc
    if isinstance(doc, dict):
        for k, v in doc.items():
            yield from _nodes(v, path + (k,))
    elif isinstance(doc, list):
        for i, v in enumerate(doc):
            yield from _nodes(v, path + (i,))


def _set(doc, path, value):
    if not path:
        return value
    node = doc
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    return doc


def _deep(rng):
    depth = rng.choice([64, 1000, 100000])
    return "[" * depth + "]" * depth if rng.random() < 0.5 else "{\"a\":" * depth + "1" + "}" * depth


class _Raw:
    """A value written into the document as raw text (NaN, 1e400, deep nesting)."""

    def __init__(self, text):
        self.text = text


def _dump(doc):
    raws = []

    def default(o):
        if isinstance(o, _Raw):
            raws.append(o.text)
            return f"\u0001raw{len(raws) - 1}\u0001"
        raise TypeError(type(o).__name__)
    text = json.dumps(doc, default=default, ensure_ascii=False)
    for i, raw in enumerate(raws):
        text = text.replace(json.dumps(f"\u0001raw{i}\u0001", ensure_ascii=False), raw)
    return text.encode("utf-8", "surrogatepass")


def _json_value(data, rng):
    try:
        doc = json.loads(data)
    except (ValueError, RecursionError):
        return _replace_number(data, rng)
    nodes = list(_nodes(doc))
    # Numbers are what a reader computes with: they are chosen more often.
    numbers = [n for n in nodes if isinstance(n[1], (int, float)) and not isinstance(n[1], bool)]
    path, value = rng.choice(numbers) if numbers and rng.random() < 0.5 else rng.choice(nodes)
    roll = rng.random()
    if roll < 0.35:
        new = rng.choice(EXTREME_VALUES)
    elif roll < 0.5:
        new = _Raw(rng.choice(["NaN", "Infinity", "-Infinity", "1e400", "-0", "1" * 400]))
    elif roll < 0.8:
        new = rng.choice(WRONG_TYPES)
    elif roll < 0.9:
        new = _Raw(_deep(rng))
    else:
        new = [value, value] if rng.random() < 0.5 else {"": value}
    return _dump(_set(doc, path, new))


def _json_keys(data, rng):
    try:
        doc = json.loads(data)
    except (ValueError, RecursionError):
        return _delete_range(data, rng)
    holders = [(p, v) for p, v in _nodes(doc) if isinstance(v, (dict, list)) and v]
    if not holders:
        return _dump(rng.choice(WRONG_TYPES))
    path, holder = rng.choice(holders)
    if isinstance(holder, dict):
        key = rng.choice(list(holder))
        if rng.random() < 0.6:
            del holder[key]
        else:
            # A key written twice (JSON allows it; the last one wins in Python).
            text = _dump(doc)
            dup = json.dumps(key).encode() + b":" + _dump(rng.choice(WRONG_TYPES + EXTREME_VALUES)) + b","
            at = text.find(json.dumps(key).encode() + b":")
            return text[:at] + dup + text[at:] if at >= 0 else text
    else:
        i = rng.randrange(len(holder))
        if rng.random() < 0.5:
            del holder[i]
        else:
            holder.insert(i, holder[i])
    return _dump(doc)


JSON_MUTATIONS = [_json_value, _json_value, _json_keys]


def mutate(data, kind, rng):
    """One damaged version of `data`, a file of `kind` ("csv", "json" or "bytes"), by one to three mutations."""
    pool = BYTE_MUTATIONS + (TABLE_MUTATIONS * 2 if kind == "csv" else JSON_MUTATIONS * 3 if kind == "json" else [])
    for _ in range(rng.choice([1, 1, 1, 2, 3])):
        data = rng.choice(pool)(data, rng)
    return data
