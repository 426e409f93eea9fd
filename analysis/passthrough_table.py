"""See-through headsets in `latsim report`: photon-to-photon latency beside
what the rig films, where the time goes, and the camera frames it costs
(docs/passthrough.md).

One table row per report row whose pipeline reports `photon_to_photon_ms`:
the computed photon-to-photon latency, the rig's frame counting and
trajectory shift (empty without /pipeline/rig), the six stages' means, their
sum and what photon-to-photon leaves of it, then camera frames shown, dropped
and repeated; every figure the mean over replications. The stages are taken
per camera frame at its first showing and add up to that showing's
photon-to-photon latency; photon-to-photon is taken per refresh, so a frame
shown again (repeated) is seen later than its stages say and the difference
is then positive.
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

import latsim_results as lr  # noqa: E402
import stage_table as st  # noqa: E402

# The passthrough pipeline's stages, in the order a camera frame goes through them.
STAGES = ["camera", "isp", "reprojection_queue", "reprojection", "display_wait", "scanout"]
P2P = "photon_to_photon_ms.mean"
RIG = [("rig, frame counting (ms)", "photon_to_photon_rig_ms.mean"),
       ("rig, trajectory shift (ms)", "photon_to_photon_rig_shift_ms.mean")]
COUNTS = [("shown", "camera_frames_shown"), ("dropped", "camera_frames_dropped"),
          ("repeated", "camera_frames_repeated")]


def passthrough_rows(coll):
    """The rows whose pipeline reports photon-to-photon latency."""
    return st.rows_with(coll, P2P)


def stage_sum(means):
    """The six stages' means added up, or None when a stage is missing."""
    return None if any(m is None for m in means) else sum(means)


def rows_of(coll):
    """(name, [cells]) per see-through row: photon-to-photon, rig, stages, their sum and its check, counts."""
    out = []
    for row in passthrough_rows(coll):
        p2p = row.mean(P2P)
        stages = [row.mean(f"{s}_ms.mean") for s in STAGES]
        total = stage_sum(stages)
        cells = [st.ms(p2p)] + [st.ms(row.mean(path)) for _, path in RIG]
        cells += [st.ms(m) for m in stages] + [st.ms(total), st.signed_ms(st.difference(p2p, total))]
        cells += [st.count(row.mean(path)) for _, path in COUNTS]
        out.append((lr.point_name(row, coll), cells))
    return out


def markdown(coll):
    """The report's passthrough section, or nothing when no row sees through."""
    header = (["row", "photon-to-photon (ms)"] + [label for label, _ in RIG] + [f"`{s}_ms`" for s in STAGES] +
              ["stages' sum (ms)", "photon-to-photon - sum (ms)"] + [f"camera frames {name}" for name, _ in COUNTS])
    intro = ("How late the real world is seen through the cameras (means over replications, ms): "
             "photon-to-photon latency at the filmed point, beside what the rig filming a moving object and its "
             "image measures (frame counting and trajectory shift). The six stages are taken per camera frame at "
             "its first showing and add up to its photon-to-photon latency: the sum check is zero when every "
             "camera frame is shown once, and positive by what repeated frames add, since photon-to-photon is "
             "taken per refresh (docs/passthrough.md).")
    return st.section("Passthrough stages", intro, header, rows_of(coll))
