"""Reading a sweep's results store: DIR/store/*.seg, every finished run's summary.

The format (sweep/include/latsim/sweep/segment.hpp and record.hpp): a segment
is b"LSSEG1\\n\\0" and then frames of a 20-byte header (b"LSRF", the payload's
length and CRC-32, the run id as a little-endian 64-bit number) and the
payload, the run's record deflated (raw) with the first line of the
segment's first record as its preset dictionary (the first record without
one). A frame cut short or damaged ends its segment. A record is one line of
JSON (the summary without its scenario; a histogram whose edges are min +
(max - min) / n * b keeps its counts alone as "histogram_counts") and then the
scenario: whole in a segment's first record, otherwise as what it changes in
that one's, a list of ["=", pointer, value] and ["-", pointer]. Where a run
has two records, the first segment in name order, then its first frame, is read.
"""

import copy
import json
import mmap
import os
import struct
import zlib

SEGMENT_MAGIC = b"LSSEG1\n\0"
FRAME_MAGIC = b"LSRF"
HEADER = 20


def inflate(payload, dictionary):
    d = zlib.decompressobj(wbits=-15, zdict=dictionary) if dictionary else zlib.decompressobj(wbits=-15)
    return d.decompress(payload) + d.flush()


def expand_histograms(node):
    """Puts back every histogram kept as its counts alone, below `node`."""
    if not isinstance(node, dict):
        return
    counts = node.pop("histogram_counts", None)
    if counts is not None:
        lo, hi, n = node["min"], node["max"], len(counts)
        width = (hi - lo) / n
        node["histogram"] = [[lo + width * b, c] for b, c in enumerate(counts)]
        return
    for child in node.values():
        expand_histograms(child)


def pointer_keys(pointer):
    return [p.replace("~1", "/").replace("~0", "~") for p in pointer.split("/")[1:]]


def patched(base, ops):
    """`base` with the changes of a scenario line's patch."""
    doc = copy.deepcopy(base)
    for op in ops:
        keys = pointer_keys(op[1])
        if not keys:
            doc = copy.deepcopy(op[2])
            continue
        parent = doc
        for key in keys[:-1]:
            parent = parent[int(key)] if isinstance(parent, list) else parent.setdefault(key, {})
        if op[0] == "=":
            parent[keys[-1]] = copy.deepcopy(op[2])
        else:
            del parent[keys[-1]]
    return doc


def decode_record(text, base=None):
    """The summary of a record's text, as summary.json holds it; `base` is the
    scenario of its segment's first record, which a later one's patches."""
    head, _, scenario = text.partition(b"\n")
    summary = json.loads(head)
    expand_histograms(summary.get("figures"))
    scenario = json.loads(scenario)
    summary["scenario"] = patched(base, scenario) if isinstance(scenario, list) else scenario
    return summary


class SweepStore:
    """Every record of DIR/store, found by run id; segments are mapped, records inflated when read."""

    def __init__(self, directory):
        self.segments = []  # (mapped bytes, first record's text, its scenario)
        self.spots = {}     # run id -> (segment, offset, length)
        store = os.path.join(directory, "store")
        names = sorted(n for n in os.listdir(store) if n.endswith(".seg")) if os.path.isdir(store) else []
        for name in names:
            with open(os.path.join(store, name), "rb") as f:
                size = os.fstat(f.fileno()).st_size
                if size < len(SEGMENT_MAGIC):
                    continue
                data = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)
            if data[:len(SEGMENT_MAGIC)] != SEGMENT_MAGIC:
                continue
            self._index(data, len(self.segments))

    def _index(self, data, segment):
        at, first = len(SEGMENT_MAGIC), None
        while at + HEADER <= len(data):
            if data[at:at + 4] != FRAME_MAGIC:
                break
            length, crc, run = struct.unpack_from("<IIQ", data, at + 4)
            payload = data[at + HEADER:at + HEADER + length]
            if len(payload) != length or zlib.crc32(payload) != crc:
                break
            if first is None:
                first = inflate(payload, None)
            self.spots.setdefault(f"{run:016x}", (segment, at + HEADER, length))
            at += HEADER + length
        base = json.loads(first.partition(b"\n")[2]) if first is not None else None
        self.segments.append((data, first, base))

    def __contains__(self, run_id):
        return run_id in self.spots

    def summary(self, run_id):
        """The run's summary (its summary.json's content), or None when the store has no record of it."""
        spot = self.spots.get(run_id)
        if spot is None:
            return None
        segment, offset, length = spot
        data, first, base = self.segments[segment]
        dictionary = first.partition(b"\n")[0]
        text = first if offset == len(SEGMENT_MAGIC) + HEADER else inflate(data[offset:offset + length], dictionary)
        return decode_record(text, base)
