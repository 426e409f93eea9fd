"""Public camera measurements of headsets' latency, by the device labels of
scenarios/devices/devices_sweep.json: what the devices table sets beside each
profile (docs/validation.md gives the sources and what each rig did).

Each entry: (value ms, its uncertainty ms or None, what was measured, source key).
"""

# The community rig (github.com/Greendayle/VR-Motion-to-photon-latency-, 2024):
# a VRChat world whose test zone turns red when the right controller moves more
# than 1.1 x its largest change at rest from one frame to the next; a camera
# films the controller, flicked by hand, and the lenses; frames counted by hand.
COMMUNITY = "community-rig"
# Warburton et al., "Measuring motion-to-photon latency for sensorimotor
# experiments with virtual reality systems", Behavior Research Methods 2022:
# a controller moved from rest, Unity and SteamVR, latency at the start of the
# movement (as tabulated beside the community rig's in its delays_collab.ods).
WARBURTON = "warburton-2022"

PUBLISHED = {
    "Valve Index 120 Hz": [(43.8, 1.5, "controller flick, VRChat, Win10 SteamVR, 240 fps", COMMUNITY)],
    "Valve Index 144 Hz": [(35.3, 1.3, "controller flick, VRChat, Linux SteamVR, 240 fps", COMMUNITY),
                           (37.1, 1.6, "controller flick, VRChat, Win10 SteamVR, 240 fps", COMMUNITY),
                           (27.8, None, "controller movement onset, Unity, SteamVR", WARBURTON)],
    "Valve Index 144 Hz (Monado)": [(40.4, 1.2, "controller flick, VRChat, Linux Envision (Monado), 240 fps",
                                     COMMUNITY)],
    "HTC Vive 90 Hz": [(43.3, 2.0, "controller flick (Index controllers), VRChat, SteamVR, 120 fps", COMMUNITY),
                       (30.8, None, "controller movement onset, Unity, SteamVR", WARBURTON)],
    "HTC Vive Pro 2 90 Hz": [(41.7, 1.6, "controller flick (Index controllers), VRChat, SteamVR, 120 fps", COMMUNITY),
                             (37.5, 2.0, "the same, VRChat's PostLateUpdate", COMMUNITY),
                             (41.7, 2.4, "the same, a minimal OpenXR application", COMMUNITY)],
    "HTC Vive Pro 2 120 Hz": [(36.3, 1.9, "controller flick (Index controllers), VRChat, SteamVR, 120 fps", COMMUNITY),
                              (32.1, 1.8, "the same, VRChat's PostLateUpdate", COMMUNITY),
                              (26.2, 2.0, "the same, a minimal OpenXR application", COMMUNITY)],
    "Bigscreen Beyond 75 Hz": [(49.0, 1.0, "controller flick (Index controllers), VRChat, SteamVR, 481 fps", COMMUNITY),
                               (51.1, 1.3, "the same, Win10 SteamVR, 240 fps", COMMUNITY)],
    "Bigscreen Beyond 90 Hz": [(44.2, 0.8, "controller flick (Index controllers), VRChat, SteamVR, 481 fps", COMMUNITY),
                               (46.1, 1.3, "the same, Win10 SteamVR, 240 fps", COMMUNITY),
                               (49.5, 1.1, "the same, Linux SteamVR, 240 fps", COMMUNITY)],
    "PlayStation VR2 120 Hz": [(47.4, 2.7, "controller flick (Sense controllers), VRChat, SteamVR, 240 fps", COMMUNITY),
                               (40.1, 2.6, "the same with Index controllers", COMMUNITY)],
}

# The four the issue names as the profiles' targets: (label, value ms).
TARGETS = [("Valve Index 144 Hz", 35.3), ("HTC Vive 90 Hz", 43.3), ("HTC Vive Pro 2 90 Hz", 41.7),
           ("HTC Vive Pro 2 120 Hz", 36.3)]
