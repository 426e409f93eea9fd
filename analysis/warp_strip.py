#!/usr/bin/env python3
"""Strips of a time-warp run's captures: what the application rendered, what the warp made of it, the truth.

usage: warp_strip.py RUN OUT_DIR [--scale N] [--gap PX] [--diff]

Reads only result files: the run's figures.json (the "frames" list) and the
PNG files it names. For every capture that has an un-warped image (the field
showed a time-warped image) it writes OUT_DIR/NNNN_warp.png =
[un-warped | displayed (warped) | truth], with the difference image last when
--diff is given, and prints one line per capture: image error and the pixels
the warp left undefined. Needs only the Python standard library.
"""

import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from side_by_side import captures, file_of, read_png, strip, upscale, write_png  # noqa: E402


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run")
    parser.add_argument("out_dir")
    parser.add_argument("--scale", type=int, default=1, help="upscale factor of the strips (nearest neighbour)")
    parser.add_argument("--gap", type=int, default=4, help="white columns between images")
    parser.add_argument("--diff", action="store_true", help="add the difference image")
    args = parser.parse_args(argv)
    entries = [e for _, e in sorted(captures(args.run).items()) if any(f.endswith("_unwarped.png") for f in e["files"])]
    if not entries:
        raise SystemExit("%s: no capture shows a time-warped image" % args.run)
    os.makedirs(args.out_dir, exist_ok=True)
    print("index  t_ms      error     undefined_px  strip")
    for e in entries:
        kinds = ["unwarped", "displayed", "truth"] + (["diff"] if args.diff else [])
        images = [read_png(file_of(args.run, e, kind)) for kind in kinds]
        name = "%04d_warp.png" % e["index"]
        write_png(os.path.join(args.out_dir, name), upscale(strip(images, args.gap), args.scale))
        print("%5d  %8.1f  %.5f   %12d  %s" % (e["index"], e["t_ms"], e["image_error"], e.get("undefined_px", 0), name))
    return 0


if __name__ == "__main__":
    import command  # noqa: E402  (the contract of every analysis command: one line, never a traceback)
    sys.exit(command.run_main("warp_strip", main, sys.argv[1:]))
