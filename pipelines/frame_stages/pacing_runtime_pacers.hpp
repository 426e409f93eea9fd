// The pacers of the runtimes (SteamVR, Oculus), next to Monado's in pacing_app.cpp.
#pragma once

#include <memory>

#include "frame_stages/pacing.hpp"

namespace latsim::pipelines::frame_stages {

/// SteamVR: WaitGetPoses returns at the next running start the application
/// can still make; throttled to a fraction of the rate when it cannot hold it.
std::unique_ptr<AppPacer> make_steamvr_pacer(const SteamVrParams& p);
/// Oculus PC and Quest: Phase Sync (a percentile of recent frame times
/// before the latch) and ASW (half rate, the other refreshes synthesised).
std::unique_ptr<AppPacer> make_oculus_pacer(const OculusParams& p);

}  // namespace latsim::pipelines::frame_stages
