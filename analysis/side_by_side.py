#!/usr/bin/env python3
"""Side-by-side strips of two runs' captured frames, e.g. frameless and double buffering.

usage: side_by_side.py RUN_A RUN_B OUT_DIR [--scale N] [--gap PX]

Reads only result files: each run's figures.json (the "frames" list) and the
PNG files it names. For every capture index present in both runs it writes
OUT_DIR/NNNN_strip.png = [A displayed | B displayed | A truth], separated by
white columns, and prints one line per capture with both image errors. Runs
of the same scenario family capture the same refreshes of the same motion, so
A's truth is also B's. Needs only the Python standard library (zlib for PNG).
"""

import argparse
import json
import os
import struct
import sys
import zlib

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


class Image:
    """8-bit RGB pixels, row-major, as a bytearray of width * height * 3."""

    def __init__(self, width, height, rgb):
        self.width, self.height, self.rgb = width, height, rgb

    @staticmethod
    def filled(width, height, colour):
        return Image(width, height, bytearray(bytes(colour) * (width * height)))


def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    if pa <= pb and pa <= pc:
        return a
    return b if pb <= pc else c


def _unfilter(raw, width, height, bpp):
    stride = width * bpp
    out = bytearray(stride * height)
    prev = bytearray(stride)
    pos = 0
    for y in range(height):
        kind = raw[pos]
        line = bytearray(raw[pos + 1:pos + 1 + stride])
        pos += 1 + stride
        if kind == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 0xFF
        elif kind == 2:
            for i in range(stride):
                line[i] = (line[i] + prev[i]) & 0xFF
        elif kind == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 0xFF
        elif kind == 4:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                up_left = prev[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + _paeth(left, prev[i], up_left)) & 0xFF
        elif kind != 0:
            raise ValueError("unknown PNG filter type %d" % kind)
        out[y * stride:(y + 1) * stride] = line
        prev = line
    return out


def read_png(path):
    """Reads an 8-bit, non-interlaced RGB or RGBA PNG (alpha is dropped)."""
    with open(path, "rb") as f:
        data = f.read()
    if not data.startswith(PNG_SIGNATURE):
        raise ValueError("%s: not a PNG file" % path)
    pos, idat, header = len(PNG_SIGNATURE), [], None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        pos += 12 + length
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat.append(body)
        elif kind == b"IEND":
            break
    width, height, depth, colour, _, _, interlace = header
    if depth != 8 or colour not in (2, 6) or interlace != 0:
        raise ValueError("%s: only 8-bit non-interlaced RGB/RGBA PNGs are supported" % path)
    bpp = 3 if colour == 2 else 4
    pixels = _unfilter(zlib.decompress(b"".join(idat)), width, height, bpp)
    if bpp == 4:
        pixels = bytearray(b for i, b in enumerate(pixels) if i % 4 != 3)
    return Image(width, height, pixels)


def write_png(path, image):
    """Writes an 8-bit RGB PNG (filter 0 on every row), atomically."""
    stride = image.width * 3
    raw = b"".join(b"\x00" + bytes(image.rgb[y * stride:(y + 1) * stride]) for y in range(image.height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    png = (PNG_SIGNATURE + chunk(b"IHDR", struct.pack(">IIBBBBB", image.width, image.height, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(png)
    os.replace(tmp, path)


def strip(images, gap, colour=(255, 255, 255)):
    """Images side by side, top-aligned, gap columns of colour between them."""
    width = sum(im.width for im in images) + gap * (len(images) - 1)
    height = max(im.height for im in images)
    out = Image.filled(width, height, colour)
    x0 = 0
    for im in images:
        for y in range(im.height):
            src = im.rgb[y * im.width * 3:(y + 1) * im.width * 3]
            dst = (y * width + x0) * 3
            out.rgb[dst:dst + len(src)] = src
        x0 += im.width + gap
    return out


def upscale(image, factor):
    """Each pixel repeated factor x factor times."""
    if factor == 1:
        return image
    rows = []
    for y in range(image.height):
        line = image.rgb[y * image.width * 3:(y + 1) * image.width * 3]
        wide = bytearray()
        for x in range(image.width):
            wide += line[x * 3:x * 3 + 3] * factor
        rows.extend([wide] * factor)
    return Image(image.width * factor, image.height * factor, bytearray(b"".join(rows)))


def captures(run_dir):
    with open(os.path.join(run_dir, "figures.json")) as f:
        figures = json.load(f)["figures"]
    if "frames" not in figures:
        raise SystemExit("%s: no frames were captured (the scenario needs a /frames section)" % run_dir)
    return {entry["index"]: entry for entry in figures["frames"]}


def file_of(run_dir, entry, what):
    for name in entry["files"]:
        if name.endswith("_%s.png" % what):
            return os.path.join(run_dir, name)
    raise SystemExit("%s: capture %d has no %s image (was the run written with --out?)" % (run_dir, entry["index"], what))


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_a")
    parser.add_argument("run_b")
    parser.add_argument("out_dir")
    parser.add_argument("--scale", type=int, default=1, help="upscale factor of the strips (nearest neighbour)")
    parser.add_argument("--gap", type=int, default=4, help="white columns between images")
    args = parser.parse_args(argv)
    a, b = captures(args.run_a), captures(args.run_b)
    common = sorted(set(a) & set(b))
    if not common:
        raise SystemExit("the two runs share no capture index")
    os.makedirs(args.out_dir, exist_ok=True)
    print("index  t_ms      error_A   error_B   strip")
    for index in common:
        ea, eb = a[index], b[index]
        images = [read_png(file_of(args.run_a, ea, "displayed")), read_png(file_of(args.run_b, eb, "displayed")),
                  read_png(file_of(args.run_a, ea, "truth"))]
        name = "%04d_strip.png" % index
        write_png(os.path.join(args.out_dir, name), upscale(strip(images, args.gap), args.scale))
        print("%5d  %8.1f  %.5f   %.5f   %s" % (index, ea["t_ms"], ea["image_error"], eb["image_error"], name))
    return 0


if __name__ == "__main__":
    import command  # noqa: E402  (the contract of every analysis command: one line, never a traceback)
    sys.exit(command.run_main("side_by_side", main, sys.argv[1:]))
