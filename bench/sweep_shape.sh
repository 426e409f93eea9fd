# The sweep shape of BENCHMARKS.md's sweep measurements, for the scripts
# beside this file to source: scenarios/hmd_60hz_serial_poll.json cut to 1
# simulated second, display refresh 50..95 Hz (10 values) x host poll
# interval 1..20 ms (20 values) x REPLICATIONS (10: the 2,000-run shape).
#
#   write_sweep_shape FILE REPLICATIONS [JITTER_MS]
#
# JITTER_MS (default 0) jitters the tracker's sample times, which takes the
# double-buffering analytic figure away (it needs exact sample times).
write_sweep_shape() {
  local file=$1 replications=$2 jitter=${3:-0}
  local root
  root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
  local overrides='"/duration_s": 1'
  [ "$jitter" = 0 ] || overrides="$overrides, \"/tracker/jitter_ms\": $jitter"
  cat > "$file" <<JSON
{
  "description": "refresh x poll interval, 1 s runs of the polled serial HMD, $replications replications",
  "base": "$root/scenarios/hmd_60hz_serial_poll.json",
  "overrides": {$overrides},
  "axes": [
    {"pointer": "/display/refresh_hz", "range": {"from": 50, "to": 95, "step": 5}},
    {"pointer": "/transport/poll_interval_ms", "range": {"from": 1, "to": 20, "step": 1}}
  ],
  "replications": $replications,
  "seed": 1
}
JSON
}
