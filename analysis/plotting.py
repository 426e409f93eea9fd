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


def save(fig, base_path):
    """Writes base_path.png and base_path.svg (each atomically) and closes the figure."""
    for ext, metadata in (("png", PNG_METADATA), ("svg", SVG_METADATA)):
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
