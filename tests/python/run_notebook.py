"""Executes a notebook headless with nbclient (kernel python3 from
ipykernel, this interpreter) and fails on the first cell that raises.

Usage: run_notebook.py NOTEBOOK   (the kernel inherits PYTHONPATH and the working directory)
"""
import os
import sys
import time

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

path = sys.argv[1]
# ipykernel's debugger warns on stderr about Python's frozen modules; not our concern.
os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")
notebook = nbformat.read(path, as_version=4)
client = NotebookClient(notebook, timeout=120, kernel_name="python3",
                        resources={"metadata": {"path": os.getcwd()}})
start = time.monotonic()
try:
    client.execute()
except CellExecutionError as e:
    print(f"FAIL: {path}: {e}")
    sys.exit(1)
errors = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.get("outputs", [])
          if o.get("output_type") == "error"]
if errors:
    print(f"FAIL: {path}: {len(errors)} cell(s) raised: {errors[0].get('ename')}: {errors[0].get('evalue')}")
    sys.exit(1)
cells = sum(1 for c in notebook.cells if c.cell_type == "code")
print(f"ok: {path}: {cells} code cells ran in {time.monotonic() - start:.1f} s")
