"""Pose prediction in a report: registration error against latency, with and
without prediction, and the split by motion phase.

Reads only result files (through latsim_results). A row's predictor is the
resolved scenario's /host/prediction/type ("none" when the scenario has no
prediction); its pipeline is /pipeline/type.
"""

import os

import latsim_results as lr
import plotting
from plotting import plt

PHASES = ["still", "onset", "steady", "stop"]


def _prediction(row):
    scenario = row.first_summary().get("scenario", {}) if row.run_dirs else {}
    prediction = scenario.get("host", {}).get("prediction")
    return prediction if isinstance(prediction, dict) else None


def predictor_of(row):
    prediction = _prediction(row)
    return prediction.get("type", "none") if prediction else "none"


def predicting_rows(coll):
    """Rows whose scenario configures /host/prediction (type none included: the baseline)."""
    return [r for r in coll.rows if _prediction(r) is not None]


def has_prediction(coll):
    return bool(predicting_rows(coll))


def _fmt(value, digits=4):
    return "" if value is None else f"{value:.{digits}g}"


def _cell(text):
    """Text in a Markdown table cell."""
    return str(text).replace("|", "\\|")


def markdown(coll):
    """Two tables: the headline per row (a run, or a sweep point, named in its first column; several
    points can share a pipeline and predictor), and registration error by motion phase."""
    head = ["point", "pipeline", "predictor", "MTP mean (ms)", "horizon mean (ms)", "registration mean (arcmin)",
            "registration p99 (arcmin)", "prediction error mean (deg)", "prediction error p99 (deg)"]
    paths = ["motion_to_photon_ms.mean", "prediction_horizon_ms.mean", "registration_error_arcmin.mean",
             "registration_error_arcmin.p99", "prediction_error_deg.mean", "prediction_error_deg.p99"]
    rows = predicting_rows(coll)
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for row in rows:
        cells = [_cell(row.name), row.pipeline(), predictor_of(row)] + [_fmt(row.mean(p)) for p in paths]
        lines.append("| " + " | ".join(cells) + " |")
    phase_head = ["point", "pipeline", "predictor"] + [f"{p} (arcmin)" for p in PHASES] + ["onset / steady"]
    phase_lines = ["| " + " | ".join(phase_head) + " |", "|" + "---|" * len(phase_head)]
    any_phase = False
    for row in rows:
        means = [row.mean(f"registration_error_arcmin_{p}.mean") for p in PHASES]
        any_phase = any_phase or any(m is not None for m in means)
        onset, steady = means[1], means[2]
        ratio = onset / steady if onset is not None and steady else None
        phase_lines.append("| " + " | ".join([_cell(row.name), row.pipeline(), predictor_of(row)] + [_fmt(m) for m in means] +
                                             [_fmt(ratio, 3)]) + " |")
    md = ["## Pose prediction", "",
          "Registration error is measured against the true pose at each probe's photon time; the prediction "
          "error is the predicted head pose against the true pose at the instant it was predicted for "
          "(docs/prediction.md).", ""] + lines + [""]
    if any_phase:
        md += ["Registration error by motion phase (mean; onset and stop: within the window after the head's "
               "angular speed crosses the threshold; see docs/prediction.md).", ""] + phase_lines + [""]
    return md


def plot_registration_vs_latency(coll):
    """One marker per row at (mean motion-to-photon, mean registration error): colour by predictor, shape by
    pipeline; the markers are not joined."""
    rows = [r for r in predicting_rows(coll)
            if r.values("motion_to_photon_ms") and r.values("registration_error_arcmin")]
    if not rows:
        return None
    predictors = []
    for r in rows:
        if predictor_of(r) not in predictors:
            predictors.append(predictor_of(r))
    pipelines = []
    for r in rows:
        if r.pipeline() not in pipelines:
            pipelines.append(r.pipeline())
    markers = ["o", "s", "^", "D", "v", "P", "X", "*"]

    def marker_of(pipeline):
        # Hollow, and smaller for each further pipeline: two systems with the
        # same latency and error stay visible one inside the other.
        i = pipelines.index(pipeline)
        return {"marker": markers[i % len(markers)], "markersize": max(4, 12 - 2 * i), "fillstyle": "none"}

    fig, ax = plt.subplots(figsize=(8, 5))
    for predictor, colour in zip(predictors, plotting.colours(len(predictors))):
        # A scatter: the rows are separate designs, and a line through them (in plan order or any
        # other) would draw a trend that no design has.
        members = [r for r in rows if predictor_of(r) == predictor]
        ax.plot([], [], color=colour, marker="s", linestyle="none", label=predictor)
        for r in members:
            ax.plot([r.mean("motion_to_photon_ms")], [r.mean("registration_error_arcmin")], color=colour,
                    linestyle="none", **marker_of(r.pipeline()))
    for pipeline in pipelines:
        ax.plot([], [], color="grey", linestyle="none", label=pipeline, **marker_of(pipeline))
    ax.set_xlabel("mean motion-to-photon latency (ms)")
    ax.set_ylabel("mean registration error (arcmin)")
    ax.set_title("Registration error against latency, by predictor (colour) and pipeline (marker)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    base = "registration_vs_latency"
    plotting.save(fig, os.path.join(coll.directory, base))
    return base
