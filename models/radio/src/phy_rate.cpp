#include "latsim/radio/phy_rate.hpp"

#include <array>
#include <cstdio>
#include <stdexcept>

namespace latsim::radio {

namespace {

struct Modulation {
  int bits_per_subcarrier;  // N_BPSCS
  int rate_num;             // code rate R = num / den
  int rate_den;
};

// IEEE 802.11-2020 Table 21-29ff (VHT) and 802.11ax-2021 Table 27-55ff (HE):
// MCS 0-9 are shared, 10 and 11 (1024-QAM) are HE only.
constexpr std::array<Modulation, 12> kMcs = {{{1, 1, 2},
                                             {2, 1, 2},
                                             {2, 3, 4},
                                             {4, 1, 2},
                                             {4, 3, 4},
                                             {6, 2, 3},
                                             {6, 3, 4},
                                             {6, 5, 6},
                                             {8, 3, 4},
                                             {8, 5, 6},
                                             {10, 3, 4},
                                             {10, 5, 6}}};

// Data subcarriers of a full-band channel: VHT (Table 21-6) and HE (the
// full-bandwidth RU of Table 27-7).
int data_subcarriers(Standard s, int width_mhz) {
  switch (width_mhz) {
    case 20: return s == Standard::vht ? 52 : 234;
    case 40: return s == Standard::vht ? 108 : 468;
    case 80: return s == Standard::vht ? 234 : 980;
    case 160: return s == Standard::vht ? 468 : 1960;
    default: throw std::invalid_argument("channel_width_mhz: must be 20, 40, 80 or 160");
  }
}

// Training fields for n streams: VHT-LTFs and HE-LTFs (1, 2, 4, 4, 6, 6, 8, 8).
int long_training_fields(int streams) {
  if (streams <= 2) return streams;
  if (streams <= 4) return 4;
  if (streams <= 6) return 6;
  return 8;
}

}  // namespace

PhyRate::PhyRate(PhyParams params) : p_(params) {
  const bool vht = p_.standard == Standard::vht;
  if (p_.mcs < 0 || p_.mcs > (vht ? 9 : 11))
    throw std::invalid_argument(vht ? "mcs: VHT (802.11ac) has MCS 0 to 9" : "mcs: HE (802.11ax) has MCS 0 to 11");
  if (p_.spatial_streams < 1 || p_.spatial_streams > 8) throw std::invalid_argument("spatial_streams: 1 to 8");
  const int gi = p_.guard_interval_ns;
  if (vht ? (gi != 800 && gi != 400) : (gi != 800 && gi != 1600 && gi != 3200))
    throw std::invalid_argument(vht ? "guard_interval_ns: VHT has 800 or 400 ns"
                                    : "guard_interval_ns: HE has 800, 1600 or 3200 ns");
  const Modulation m = kMcs[static_cast<size_t>(p_.mcs)];
  const int64_t coded = static_cast<int64_t>(data_subcarriers(p_.standard, p_.channel_width_mhz)) *
                        m.bits_per_subcarrier * p_.spatial_streams * m.rate_num;
  // VHT leaves out the combinations whose N_DBPS is not whole; HE rounds it
  // down (802.11ax-2021 27.5: N_DBPS = floor(N_CBPS · R)).
  if (vht && coded % m.rate_den != 0)
    throw std::invalid_argument("mcs: MCS " + std::to_string(p_.mcs) + " is not defined for " +
                                std::to_string(p_.channel_width_mhz) + " MHz with " +
                                std::to_string(p_.spatial_streams) + " streams (data bits per symbol not whole)");
  n_dbps_ = coded / m.rate_den;
  symbol_ = des::Time::ns((vht ? 3200 : 12800) + gi);
  const int ltf = long_training_fields(p_.spatial_streams);
  // VHT SU: L-STF 8, L-LTF 8, L-SIG 4, VHT-SIG-A 8, VHT-STF 4, VHT-LTFs 4 each, VHT-SIG-B 4.
  // HE SU: L-STF 8, L-LTF 8, L-SIG 4, RL-SIG 4, HE-SIG-A 8, HE-STF 4, HE-LTFs 8 each
  // (2x HE-LTF of 6.4 µs with a 1.6 µs guard interval).
  preamble_ = vht ? des::Time::us(36 + 4 * ltf) : des::Time::us(36 + 8 * ltf);
  if (vht) {
    // One BCC encoder per 600 Mb/s of the short-GI rate (the N_ES of the VHT MCS tables).
    const int64_t sgi_rate_bps = n_dbps_ * 1'000'000'000 / 3600;
    n_es_ = static_cast<int>((sgi_rate_bps + 599'999'999) / 600'000'000);
    if (n_es_ < 1) n_es_ = 1;
  }
  const std::array<int, 8> legacy = {6, 9, 12, 18, 24, 36, 48, 54};
  bool ok = false;
  for (int r : legacy) ok = ok || r == p_.control_rate_mbps;
  if (!ok) throw std::invalid_argument("control_rate_mbps: a legacy OFDM rate (6, 9, 12, 18, 24, 36, 48 or 54)");
}

double PhyRate::data_rate_bps() const { return static_cast<double>(n_dbps_) / symbol_.to_seconds(); }

int64_t PhyRate::data_symbols(int64_t bytes) const {
  const int64_t bits = 16 + 8 * bytes + 6 * static_cast<int64_t>(n_es_);
  return (bits + n_dbps_ - 1) / n_dbps_;
}

des::Time PhyRate::ppdu_duration(int64_t psdu_bytes) const { return preamble_ + symbol_ * data_symbols(psdu_bytes); }

des::Time PhyRate::bytes_received_after(int64_t bytes) const {
  // The symbol holding the last bit of the first `bytes` (after 16 service bits).
  const int64_t bits = 16 + 8 * bytes;
  return preamble_ + symbol_ * ((bits + n_dbps_ - 1) / n_dbps_);
}

des::Time PhyRate::legacy_duration(int64_t bytes, int rate_mbps) {
  const int64_t per_symbol = 4 * static_cast<int64_t>(rate_mbps);
  const int64_t symbols = (16 + 8 * bytes + 6 + per_symbol - 1) / per_symbol;
  return des::Time::us(20 + 4 * symbols);
}

std::string PhyRate::describe() const {
  char text[96];
  std::snprintf(text, sizeof text, "%s MCS %d, %d MHz, %d stream%s, %.1f Mb/s",
                p_.standard == Standard::vht ? "VHT" : "HE", p_.mcs, p_.channel_width_mhz, p_.spatial_streams,
                p_.spatial_streams == 1 ? "" : "s", data_rate_bps() / 1e6);
  return text;
}

}  // namespace latsim::radio
