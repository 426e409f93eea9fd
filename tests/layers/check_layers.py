#!/usr/bin/env python3
"""The libraries of latsim form layers, and no include points up.

Each library may include its own headers and those of the libraries below it
(ALLOWED). The test reads every source and header of every library folder,
finds each `#include "latsim/<lib>/..."` and fails on an include of a library
that is not allowed, naming the file and line. A pipeline folder's own
headers ("frame_stages/spec.hpp") belong to the pipelines library. The Python
module (python/) is checked like the command line (app/): its C++ by its
includes, and its Python package (python/latsim/) by its imports, which may
name the standard library, its own package and its compiled part, and the
third-party packages in PYTHON_THIRD_PARTY, never analysis/ (which reads only
result files and the figure registry, and never imports the module back). A
new top-level folder with sources must be given its place here, or the test
fails: the layers are declared, not discovered.
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
# A Python import's first module name: "import a.b" and "from a.b import c"
# give "a"; a relative "from . import c" gives "" (the package itself).
IMPORT = re.compile(r'^\s*(?:import\s+([A-Za-z_][A-Za-z0-9_]*)|from\s+(\.*)([A-Za-z_][A-Za-z0-9_]*)?\s+import\b)')
# Packages not of the standard library that the Python package may import.
PYTHON_THIRD_PARTY = {"numpy", "pandas"}


def python_import_problems():
    """The imports of python/latsim/ that reach past its layer, and of analysis/ that reach the module."""
    problems = []
    analysis = {p.stem for p in (ROOT / "analysis").glob("*.py")}
    package = ROOT / "python" / "latsim"
    stdlib = set(sys.stdlib_module_names)
    for path in sorted(package.rglob("*.py")):
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            m = IMPORT.match(line)
            if not m:
                continue
            relative = bool(m.group(2))
            name = m.group(1) or m.group(3) or ""
            if relative or name in stdlib or name in PYTHON_THIRD_PARTY or name == "latsim":
                continue
            why = "analysis/, which is not below it" if name in analysis else "a module not declared here"
            problems.append(f"{path.relative_to(ROOT)}:{number}: the Python package imports {name}, {why}")
    for path in sorted((ROOT / "analysis").glob("*.py")):
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            m = IMPORT.match(line)
            if m and not m.group(2) and (m.group(1) or m.group(3)) in {"latsim", "_latsim"}:
                problems.append(f"{path.relative_to(ROOT)}:{number}: analysis/ imports the Python module, "
                                "which stands above it")
    return problems


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
    python_files = len(list((ROOT / "python" / "latsim").rglob("*.py")))
    problems += python_import_problems()
    for p in problems:
        print(p)
    if problems:
        print(f"FAIL: {len(problems)} include(s) or import(s) against the layers")
        return 1
    if files < 100:
        print(f"FAIL: only {files} files read; is {ROOT} the source tree?")
        return 1
    if python_files == 0:
        print(f"FAIL: no Python file under {ROOT / 'python' / 'latsim'}")
        return 1
    print(f"ok: {files} files, no include points up; {python_files} Python files of the module import "
          "nothing above them")
    return 0


if __name__ == "__main__":
    sys.exit(main())
