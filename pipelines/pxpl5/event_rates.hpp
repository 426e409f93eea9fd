// What the two Pixel-Planes 5 pipelines declare to the event budget.
#pragma once

#include <vector>

#include "latsim/pipelines/event_rate.hpp"
#include "latsim/pxpl5/rc_engine.hpp"
#include "latsim/pxpl5/slats_engine.hpp"
#include "pxpl5/wiring.hpp"

namespace latsim::pipelines {

/// Slats: fields per second (at most one per refresh) times the events of
/// each field's ring messages and region copies, and the host's sends.
std::vector<EventRate> slats_event_rates(const pxpl5::SlatsParams& p, const Pxpl5Common& common,
                                         const sections::SharedParams& shared);

/// Rendering Control: frames per second (at most one per refresh) times the
/// events of each eye's region tokens, bin transfers and copies.
std::vector<EventRate> rc_event_rates(const pxpl5::RcParams& p, const Pxpl5Common& common,
                                      const sections::SharedParams& shared);

}  // namespace latsim::pipelines
