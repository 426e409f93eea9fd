"""Matplotlib set up for reproducible figures: Agg backend, fixed SVG ids, no dates."""

import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)

# Random SVG element ids and embedded dates would make every rendering differ.
plt.rcParams["svg.hashsalt"] = "latsim"
plt.rcParams["svg.fonttype"] = "path"
plt.rcParams["figure.dpi"] = 100
plt.rcParams["axes.grid"] = True
plt.rcParams["grid.alpha"] = 0.3

PNG_METADATA = {"Software": None}
SVG_METADATA = {"Date": None, "Creator": "latsim analysis"}


def save(fig, base_path):
    """Writes base_path.png and base_path.svg (each atomically) and closes the figure."""
    for ext, metadata in (("png", PNG_METADATA), ("svg", SVG_METADATA)):
        final = f"{base_path}.{ext}"
        temp = f"{final}.tmp.{os.getpid()}"
        fig.savefig(temp, format=ext, metadata=metadata, bbox_inches="tight", dpi=120)
        os.replace(temp, final)
    plt.close(fig)


def write_text(path, text):
    """Writes a text file atomically: a temporary file, then rename."""
    temp = f"{path}.tmp.{os.getpid()}"
    with open(temp, "w", encoding="utf-8", newline="") as f:
        f.write(text)
    os.replace(temp, path)


def colours(n):
    """n distinguishable colours, the same for the same n."""
    cmap = plt.get_cmap("tab10" if n <= 10 else "tab20")
    return [cmap(i % cmap.N) for i in range(n)]
