"""Streamed headsets in `latsim report`: the stages as ALVR's statistics name
them, the streaming tool's own total latency beside what the camera measures,
and the frames the stream cost (docs/streaming.md).

One table row per report row whose pipeline reports `reported_total_ms`:
motion-to-photon (the camera), the tool's total and the difference, each
stage's mean, then frames dropped, late and re-projected; every figure the
mean over replications. The eight stages add up to the tool's total, as in
ALVR, where the network time is what the total leaves.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import latsim_results as lr  # noqa: E402
import stage_table as st  # noqa: E402

# ALVR's stage names (alvr/server_core/src/statistics.rs), in the order a frame goes through them.
STAGES = ["game", "server_compositor", "encoder", "network", "decoder", "decoder_queue", "client_compositor",
          "vsync_queue"]
TOTAL = "reported_total_ms.mean"
CAMERA = "motion_to_photon_ms.mean"
COUNTS = [("dropped", "frames_dropped"), ("late", "frames_late"), ("re-projected", "frames_rewarped")]


def streaming_rows(coll):
    """The rows whose pipeline reports the tool's total latency."""
    return st.rows_with(coll, TOTAL)


def rows_of(coll):
    """(name, [cells]) per streamed row: camera, tool's total, difference, stages, counts."""
    out = []
    for row in streaming_rows(coll):
        camera, total = row.mean(CAMERA), row.mean(TOTAL)
        cells = [st.ms(camera), st.ms(total), st.signed_ms(st.difference(camera, total))]
        cells += [st.ms(row.mean(f"{s}_ms.mean")) for s in STAGES]
        cells += [st.count(row.mean(path)) for _, path in COUNTS]
        out.append((lr.point_name(row, coll), cells))
    return out


def markdown(coll):
    """The report's streaming section, or nothing when no row streams."""
    header = (["row", "camera MTP (ms)", "tool's total (ms)", "camera - tool (ms)"] +
              [f"`{s}` (ms)" for s in STAGES] + [f"frames {name}" for name, _ in COUNTS])
    intro = ("The stages as ALVR's statistics name them (means over replications, ms); the tool's total is "
             "computed as ALVR computes it, from the pose report's sending to the display time the runtime "
             "predicts for the refresh that shows the frame, and the eight stages add up to it (the network "
             "time is what the total leaves). Beside it, the camera's motion-to-photon latency "
             "(docs/streaming.md).")
    return st.section("Streaming stages", intro, header, rows_of(coll))
