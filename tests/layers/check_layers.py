#!/usr/bin/env python3
"""The libraries of latsim form layers, and no include points up.

Each library may include its own headers and those of the libraries below it
(ALLOWED). The test reads every source and header of every library folder,
finds each `#include "latsim/<lib>/..."` and fails on an include of a library
that is not allowed, naming the file and line. A pipeline folder's own
headers ("frame_stages/spec.hpp") belong to the pipelines library. The Python
module (python/) is checked like the command line (app/). A new top-level
folder with sources must be given its place here, or the test fails: the
layers are declared, not discovered.
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")

MODELS = {"tracker", "display", "renderer", "pxpl5", "arp", "capture", "measurement", "radio"}
# The floor every library stands on: units and angle constants, the event
# kernel, statistics and input files.
BASE = {"units", "des", "stats", "io"}
# Library -> the latsim libraries it may include (its own included).
ALLOWED = {
    "units": {"units"},
    "des": {"units", "des"},
    "stats": {"units", "des", "stats"},
    "io": {"units", "io"},
    "scenario": {"units", "des", "io", "scenario"},
    "tracker": {"units", "des", "io", "tracker"},
    "display": {"units", "des", "stats", "display"},
    "capture": {"units", "des", "io", "capture"},
    "renderer": {"units", "des", "io", "tracker", "capture", "renderer"},
    "pxpl5": {"units", "des", "tracker", "pxpl5"},
    "arp": {"units", "des", "stats", "tracker", "renderer", "arp"},
    "measurement": {"units", "des", "tracker", "measurement"},
    "radio": {"units", "des", "radio"},
    "sections": BASE | {"scenario", "sections"} | MODELS,
    "results": BASE | {"scenario", "sections", "results"} | MODELS,
    "pipelines": BASE | {"scenario", "sections", "results", "pipelines"} | MODELS,
    "run": BASE | {"scenario", "sections", "results", "pipelines", "run"} | MODELS,
    "sweep": BASE | {"scenario", "sections", "results", "run", "sweep"} | MODELS,
    # The two programs on top: the command line and the Python module.
    "app": BASE | {"scenario", "sections", "results", "run", "sweep"} | MODELS,
    "python": BASE | {"scenario", "sections", "results", "run", "sweep"} | MODELS,
}
# Folder of each library, relative to the root.
FOLDERS = {name: (f"models/{name}" if name in MODELS else name) for name in ALLOWED}
# Top-level folders that hold no library.
NOT_LIBRARIES = {"tests", "bench", "analysis", "docs", "scenarios", "scripts", "cmake", "build", "models", "examples"}

INCLUDE = re.compile(r'^\s*#\s*include\s*"latsim/([a-z0-9_]+)/')


def main() -> int:
    problems = []
    for top in sorted(p for p in ROOT.iterdir() if p.is_dir() and not p.name.startswith(".")):
        if top.name in NOT_LIBRARIES or top.name.startswith("build"):
            continue
        if top.name not in FOLDERS and any(top.rglob("*.cpp")):
            problems.append(f"{top.name}/: a folder with sources that is no declared layer (add it to ALLOWED)")
    for models_dir in sorted((ROOT / "models").iterdir()):
        if models_dir.is_dir() and models_dir.name not in MODELS:
            problems.append(f"models/{models_dir.name}/: a model that is no declared layer (add it to ALLOWED)")
    files = 0
    for lib, folder in FOLDERS.items():
        for path in sorted((ROOT / folder).rglob("*")):
            if path.suffix not in {".cpp", ".hpp", ".h"}:
                continue
            files += 1
            for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
                m = INCLUDE.match(line)
                if m and m.group(1) not in ALLOWED[lib]:
                    problems.append(f"{path.relative_to(ROOT)}:{number}: {lib} includes latsim/{m.group(1)}/, "
                                    f"which is not below it")
    for p in problems:
        print(p)
    if problems:
        print(f"FAIL: {len(problems)} include(s) against the layers")
        return 1
    if files < 100:
        print(f"FAIL: only {files} files read; is {ROOT} the source tree?")
        return 1
    print(f"ok: {files} files, no include points up")
    return 0


if __name__ == "__main__":
    sys.exit(main())
