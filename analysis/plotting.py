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
# Every file this process wrote (save, write_text), for a command that fails
# halfway to take back: a report on a damaged directory leaves nothing.
WRITTEN = []


def remove_written():
    """Removes every file this process wrote so far (a failed command's partial output)."""
    while WRITTEN:
        _remove_quietly(WRITTEN.pop())
SVG_METADATA = {"Date": None, "Creator": "latsim analysis"}


def save(fig, base_path, formats=("png", "svg")):
    """Writes base_path.png and base_path.svg (each atomically; `formats` for fewer) and closes the figure."""
    for ext, metadata in (("png", PNG_METADATA), ("svg", SVG_METADATA)):
        if ext not in formats:
            continue
        final = f"{base_path}.{ext}"
        temp = f"{final}.tmp.{os.getpid()}"
        try:
            fig.savefig(temp, format=ext, metadata=metadata, bbox_inches="tight", dpi=120)
            os.replace(temp, final)
            WRITTEN.append(final)
        except OSError as e:
            _remove_quietly(temp)
            plt.close(fig)
            raise OSError(e.errno, e.strerror, final) from None
        except BaseException:
            _remove_quietly(temp)
            plt.close(fig)
            raise
    plt.close(fig)


def _remove_quietly(path):
    """Removes a temporary file of a failed write (it may not exist yet)."""
    try:
        os.remove(path)
    except OSError:
        pass


def write_text(path, text):
    """Writes a text file atomically: a temporary file, then rename."""
    temp = f"{path}.tmp.{os.getpid()}"
    try:
        with open(temp, "w", encoding="utf-8", newline="") as f:
            f.write(text)
        os.replace(temp, path)
        WRITTEN.append(path)
    except OSError as e:
        # A full disk leaves no partial or empty file behind, and the error names the file.
        _remove_quietly(temp)
        raise OSError(e.errno, e.strerror, path) from None
    except BaseException:
        _remove_quietly(temp)
        raise


def colours(n):
    """n distinguishable colours, the same for the same n."""
    cmap = plt.get_cmap("tab10" if n <= 10 else "tab20")
    return [cmap(i % cmap.N) for i in range(n)]


# Labels nearer than this (points) are stacked apart: about one line of 7-point text, and the width
# of a short label.
LABEL_LINE_PT = 9.0
LABEL_WIDTH_PT = 90.0


def annotate_apart(ax, points, labels, fontsize=7):
    """Labels each (x, y) point a little above and to the right, stacking upwards the labels that would
    print over one another (points that coincide, or nearly); a moved label gets a thin leader line.
    Call it after everything that sets the axes' limits has been drawn."""
    ax.autoscale_view()
    to_pt = 72.0 / ax.figure.dpi
    anchors = [(ax.transData.transform(p) * to_pt, p, label) for p, label in zip(points, labels)]
    placed = []
    for (x_pt, y_pt), point, label in sorted(anchors, key=lambda a: (a[0][1], a[0][0])):
        text_y = y_pt + 4.0
        while any(abs(px - x_pt) < LABEL_WIDTH_PT and abs(py - text_y) < LABEL_LINE_PT for px, py in placed):
            text_y += LABEL_LINE_PT / 3
        placed.append((x_pt, text_y))
        moved = text_y - y_pt > 4.0 + 1e-9
        ax.annotate(label, point, textcoords="offset points", xytext=(5, text_y - y_pt), fontsize=fontsize,
                    arrowprops={"arrowstyle": "-", "linewidth": 0.4, "color": "grey"} if moved else None)
