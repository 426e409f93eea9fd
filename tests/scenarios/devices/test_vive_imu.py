"""The HTC Vive headset's tracking chain in scenarios/devices/vive/base.json is
the real recording's (shared/data/imu/vive-hmd/, docs/devices.md, "The Vive's
IMU from a recording"): this test derives every value from the recording,
independently of latsim, and checks the profile holds it (to the digits the
profile gives).

- Reading rate: the device timecode counts at 48 MHz; a least-squares line
  of timecode against the unwrapped sequence number gives the period, and
  its difference from 1 ms the clock's rate error in ppm.
- Timestamp tick: one count of the 48 MHz timecode.
- Gyro noise density: the Allan deviation of each axis at averaging times
  of 10 to 100 ms lies on the white-noise line sigma(tau) = N / sqrt(tau);
  N is the mean of sigma(tau) sqrt(tau) over those times and axes. (The
  per-reading deviation is lower than N sqrt(1000 Hz): the part's low-pass
  filter correlates neighbouring readings.)
- Residual bias: the mean rate of each axis at rest after libsurvive's
  calibration; the profile's per-axis deviation is their root mean square.
- Range: the calibrated rate over the raw count (their deviations' ratio)
  is the gyro's scale; 2^15 counts of it are the range.
- Readings per report: 3, the Vive's IMU report layout (libsurvive,
  src/driver_vive.c, three samples per report); the sequence numbers are
  unique, so the host dedups the overlap.
- Report loss: reports come every reading (bursts of new readings a
  millisecond apart at the median); the share of 1 ms report slots in which
  no report reached the host.
- The host's delay beyond the poll: the delay of each burst's newest reading
  (host time minus device time, less its minimum) has mean 0.5 ms (the wait
  for a 1 kHz poll, uniform) plus the mean of an exponential delay.

Usage: test_vive_imu.py SOURCE_DIR
"""

import json
import math
import os
import sys

SOURCE_DIR = sys.argv[1]
RECORDING = os.path.join(SOURCE_DIR, "..", "shared", "data", "imu", "vive-hmd", "vive_hmd_imu_calibrated_I.txt")
PROFILE = os.path.join(SOURCE_DIR, "scenarios", "devices", "vive", "base.json")
TICK_HZ = 48_000_000
failures = []


def check(ok, message):
    print(("ok: " if ok else "FAILED: ") + message)
    if not ok:
        failures.append(message)


def rows():
    out = []
    for line in open(RECORDING, encoding="utf-8"):
        f = line.split()
        out.append((float(f[0]), int(f[4]), [float(x) for x in f[8:11]], int(f[-1])))
    return out


def main():
    if not os.path.exists(RECORDING):
        print("skipped: the recording is not in ../shared/data (it is not part of the repository)")
        return 0
    data = rows()
    # The first readings precede a jump of the device clock (the recording
    # starting): from the first run of consecutive timecodes on.
    start = next(i for i in range(1, len(data)) if (data[i][1] - data[i - 1][1]) % 2**32 > 10 * TICK_HZ // 1000) + 1
    data = data[start:]
    t = [0]
    seq = [0]
    for (h0, c0, g0, s0), (h1, c1, g1, s1) in zip(data, data[1:]):
        t.append(t[-1] + (c1 - c0) % 2**32)
        seq.append(seq[-1] + (s1 - s0) % 256)
    n = len(t)
    mean_s = sum(seq) / n
    mean_t = sum(t) / n
    slope = sum((s - mean_s) * (c - mean_t) for s, c in zip(seq, t)) / sum((s - mean_s) ** 2 for s in seq)
    period_ms = slope / TICK_HZ * 1e3
    rate_error_ppm = (1.0 / period_ms - 1.0) * 1e6  # positive: faster than 1 kHz

    # Allan deviation on consecutive readings (gaps ignored: white noise has no memory).
    densities = []
    for axis in range(3):
        g = [r[2][axis] for r in data]
        for m in (10, 20, 50, 100):
            blocks = [sum(g[i:i + m]) / m for i in range(0, len(g) - m + 1, m)]
            avar = sum((b1 - b0) ** 2 for b0, b1 in zip(blocks, blocks[1:])) / (2 * (len(blocks) - 1))
            densities.append(math.sqrt(avar) * math.sqrt(m / 1000.0))
    density_deg = sum(densities) / len(densities) * 180 / math.pi
    bias = [sum(r[2][a] for r in data) / len(data) * 180 / math.pi for a in range(3)]
    bias_rms = math.sqrt(sum(b * b for b in bias) / 3)

    # Bursts: readings the host received within 0.4 ms of each other came in one report.
    bursts = []
    for i, r in enumerate(data):
        if i == 0 or r[0] - data[i - 1][0] >= 0.0004:
            bursts.append([])
        bursts[-1].append(i)
    slots = seq[-1] - seq[0] + 1
    loss = 1.0 - len(bursts) / slots
    delays = [data[b[-1]][0] - t[b[-1]] / TICK_HZ for b in bursts]
    low = min(delays)
    extra_ms = (sum(d - low for d in delays) / len(delays)) * 1e3 - 0.5

    raw = [[float(x) for x in line.split()[8:11]] for line in open(RECORDING.replace("calibrated_I", "raw_i"),
                                                                     encoding="utf-8")]
    def sd(v):
        m = sum(v) / len(v)
        return math.sqrt(sum((x - m) ** 2 for x in v) / len(v))
    all_rows = rows()
    scale = sd([r[2][0] for r in all_rows]) / sd([r[0] for r in raw])  # rad/s per count
    range_deg = 32768 * scale * 180 / math.pi

    profile = json.load(open(PROFILE, encoding="utf-8"))
    imu = profile["tracker"]["imu"]
    check(round(rate_error_ppm) == profile["tracker"]["rate_error_ppm"],
          f"rate error {rate_error_ppm:.1f} ppm (period {period_ms:.6f} ms) against {profile['tracker']['rate_error_ppm']}")
    check(abs(imu["timestamp_tick_us"] - 1e6 / TICK_HZ) < 1e-4, f"timestamp tick {1e6 / TICK_HZ:.5f} us")
    check(abs(imu["gyro_noise_density_deg_s_rthz"] - density_deg) <= 0.00005,
          f"noise density {density_deg:.5f} deg/s/rtHz against {imu['gyro_noise_density_deg_s_rthz']}")
    check(abs(imu["gyro_bias_deg_s"] - bias_rms) <= 0.005,
          f"residual bias {bias_rms:.3f} deg/s rms (axes {', '.join(f'{b:.3f}' for b in bias)}) against {imu['gyro_bias_deg_s']}")
    check(imu["samples_per_report"] == 3, "three readings per report")
    check(abs(imu["range_deg_s"] - range_deg) <= 5, f"range {range_deg:.0f} deg/s against {imu['range_deg_s']}")
    check(abs(imu["report_loss_probability"] - loss) <= 0.005,
          f"report loss {loss:.3f} ({len(bursts)} reports in {slots} slots) against {imu['report_loss_probability']}")
    link = profile["transport"]
    check(link["os_jitter"] == "exponential" and abs(link["os_jitter_ms"] - extra_ms) <= 0.05,
          f"host delay beyond the poll {extra_ms:.2f} ms (exponential) against {link.get('os_jitter_ms')}")
    if failures:
        print(f"FAIL: {len(failures)} check(s)")
        return 1
    print("ok: the Vive profile's tracking chain is the recording's")
    return 0


if __name__ == "__main__":
    sys.exit(main())
