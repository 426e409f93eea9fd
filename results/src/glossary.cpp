#include "latsim/results/glossary.hpp"

#include <algorithm>
#include <array>

namespace latsim::results {

namespace {

constexpr std::array kGlossary = {
    GlossaryEntry{"motion_to_photon_ms",
                  "per lit span: photon time minus the measurement time of the older of the samples whose orientation "
                  "and position it was computed from"},
    GlossaryEntry{"rotation_latency_ms", "per lit span: photon time minus the measurement time of the orientation used"},
    GlossaryEntry{"translation_latency_ms", "per lit span: photon time minus the measurement time of the position used"},
    GlossaryEntry{"render_latency_ms",
                  "per image: photon time of the first span that shows it minus the start of the stage that first "
                  "used its tracking data"},
    GlossaryEntry{"render_latency_fields", "render_latency_ms in field periods"},
    GlossaryEntry{"image_age_ms",
                  "per field and eye: motion_to_photon_ms of the field's first active line (the age of the pose the "
                  "shown image was computed from, as the field starts to light up)"},
    GlossaryEntry{"pixel_age_ms",
                  "per sampled pixel and refresh: photon time minus the measurement time of the sample the pixel was "
                  "computed from"},
    GlossaryEntry{"display_ms", "per lit span: photon time minus the photon time of its field's first active line"},
    GlossaryEntry{"tracker_to_host_ms",
                  "per record carried: the instant the host application can see it minus its measurement time"},
    GlossaryEntry{"tracker_to_render_ms",
                  "per image: the start of the stage that first used its tracking data minus the sample's measurement "
                  "time"},
    GlossaryEntry{"line_wait_ms", "per record sent on a serial line: the time it waited in the line's buffer"},
    GlossaryEntry{"registration_error_arcmin",
                  "per lit world point: the angle between where it is drawn and where it should appear given the head "
                  "pose at its photon time"},
    GlossaryEntry{"registration_error_px", "registration_error_arcmin in display pixels at the image centre"},
    GlossaryEntry{"prediction_horizon_ms",
                  "per prediction: the instant the pose was predicted for minus the measurement time of its sample"},
    GlossaryEntry{"prediction_error_deg",
                  "per prediction: the angle between the predicted head orientation and the true one at the instant "
                  "predicted for"},
    GlossaryEntry{"prediction_error_mm",
                  "per prediction: the distance between the predicted head position and the true one at the instant "
                  "predicted for"},
    GlossaryEntry{"frame_rate_hz", "distinct images first shown per second on one eye's display"},
    GlossaryEntry{"missed_refreshes",
                  "refreshes (one eye) that showed no new image although the pipeline had one due by then"},
    GlossaryEntry{"fields", "refreshes (retraces) the display made"},
    GlossaryEntry{"tracker_samples", "samples the tracker measured"},
    GlossaryEntry{"records_dropped", "records pushed out of a full link buffer before they were sent"},
    GlossaryEntry{"line_utilisation",
                  "records offered times the time each holds the line, over the run: above 1 the line cannot keep up"},
    GlossaryEntry{"interrupt_utilisation",
                  "records offered times the interrupt handlers' time per record, over the run: above 1 the host cannot "
                  "keep up"},
};

// Figures split by motion phase (/motion_phases) into <name>_<phase>.
constexpr std::array<std::string_view, 2> kSplit = {"registration_error_arcmin", "prediction_error_deg"};
constexpr std::array<std::string_view, 4> kPhases = {"still", "onset", "steady", "stop"};

constexpr std::array<std::string_view, 3> kCounters = {"images_shown", "fields", "unlit_spans"};

}  // namespace

std::span<const GlossaryEntry> glossary() { return kGlossary; }

std::span<const std::string_view> recorder_counters() { return kCounters; }

std::span<const std::string_view> phase_split_figures() { return kSplit; }

std::span<const std::string_view> motion_phase_suffixes() { return kPhases; }

bool is_glossary_figure(std::string_view name) {
  const std::string_view head = name.substr(0, name.find('.'));
  if (std::any_of(kGlossary.begin(), kGlossary.end(), [&](const GlossaryEntry& e) { return e.name == head; }))
    return true;
  // A motion-phase part of a split figure is the recorder's too.
  for (std::string_view base : kSplit)
    for (std::string_view phase : kPhases)
      if (head.size() == base.size() + 1 + phase.size() && head.starts_with(base) && head[base.size()] == '_' &&
          head.ends_with(phase))
        return true;
  return false;
}

}  // namespace latsim::results
