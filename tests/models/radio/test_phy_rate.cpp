// PHY rates and PPDU airtime against the 802.11 tables, derived by hand.
#include <catch2/catch.hpp>

#include "latsim/radio/phy_rate.hpp"

using latsim::des::Time;
using namespace latsim::radio;

TEST_CASE("VHT data rates are N_SD x N_BPSCS x N_SS x R per symbol") {
  // 80 MHz: 234 data subcarriers; MCS 9 is 256-QAM (8 bits) at rate 5/6.
  // Two streams: 234 * 8 * 2 * 5/6 = 3120 bits per 4 us symbol = 780 Mb/s,
  // and per 3.6 us with the short guard interval = 866.7 Mb/s (the familiar
  // "AC1200" figure for a 2x2 80 MHz link).
  PhyRate lgi(PhyParams{Standard::vht, 9, 80, 2, 800, 24});
  CHECK(lgi.bits_per_symbol() == 3120);
  CHECK(lgi.data_rate_bps() == Approx(780e6));
  PhyRate sgi(PhyParams{Standard::vht, 9, 80, 2, 400, 24});
  CHECK(sgi.data_rate_bps() == Approx(866.667e6).epsilon(1e-5));
  // 20 MHz MCS 0, one stream: 52 * 1 * 1/2 = 26 bits / 4 us = 6.5 Mb/s.
  CHECK(PhyRate(PhyParams{Standard::vht, 0, 20, 1, 800, 24}).data_rate_bps() == Approx(6.5e6));
}

TEST_CASE("VHT MCS 9 at 20 MHz on one stream does not exist, HE rounds N_DBPS down") {
  // 52 * 8 * 5/6 = 346.67: not whole, so the standard leaves it out.
  CHECK_THROWS_WITH(PhyRate(PhyParams{Standard::vht, 9, 20, 1, 800, 24}), Catch::Contains("not defined"));
  // HE 80 MHz (980 data subcarriers) MCS 11 (1024-QAM, 5/6), 2 streams:
  // floor(980 * 10 * 2 * 5/6) = 16333 bits per 13.6 us = 1201 Mb/s (Wi-Fi 6 "AX1800" 5 GHz half).
  PhyRate he(PhyParams{Standard::he, 11, 80, 2, 800, 24});
  CHECK(he.bits_per_symbol() == 16333);
  CHECK(he.data_rate_bps() == Approx(1200.96e6).epsilon(1e-5));
  CHECK_THROWS_WITH(PhyRate(PhyParams{Standard::vht, 10, 80, 2, 800, 24}), Catch::Contains("MCS 0 to 9"));
  CHECK_THROWS(PhyRate(PhyParams{Standard::he, 5, 80, 2, 400, 24}));
  CHECK_THROWS(PhyRate(PhyParams{Standard::vht, 5, 30, 2, 800, 24}));
}

TEST_CASE("PPDU airtime: preamble, then whole symbols of service, data and tail bits") {
  PhyRate phy(PhyParams{Standard::vht, 9, 80, 2, 800, 24});
  // VHT SU preamble with 2 streams: 8 + 8 + 4 (legacy) + 8 (VHT-SIG-A) + 4 (VHT-STF)
  // + 2 * 4 (VHT-LTFs) + 4 (VHT-SIG-B) = 44 us.
  CHECK(phy.preamble() == Time::us(44));
  // 1042 bytes: 16 + 8336 + 2 encoders * 6 tail = 8364 bits -> 3 symbols -> 44 + 12 = 56 us.
  CHECK(phy.ppdu_duration(1042) == Time::us(56));
  // 64978 bytes: 16 + 519824 + 12 = 519852 bits -> 167 symbols -> 44 + 668 = 712 us.
  CHECK(phy.ppdu_duration(64978) == Time::us(712));
  // The receiver has the first 1042 bytes once symbol ceil((16 + 8336) / 3120) = 3 ends.
  CHECK(phy.bytes_received_after(1042) == Time::us(56));
  // HE, 2 streams: 36 + 2 * 8 (2x HE-LTF with 1.6 us GI) = 52 us of preamble.
  CHECK(PhyRate(PhyParams{Standard::he, 11, 80, 2, 800, 24}).preamble() == Time::us(52));
}

TEST_CASE("legacy control responses: 20 us, then 4 us symbols of 4 x rate bits") {
  // BlockAck (32 bytes) at 24 Mb/s: 16 + 256 + 6 = 278 bits / 96 -> 3 symbols: 32 us.
  CHECK(PhyRate::legacy_duration(32, 24) == Time::us(32));
  // Ack (14 bytes) at 24 Mb/s: 134 bits -> 2 symbols: 28 us; at 6 Mb/s: 134 / 24 -> 6: 44 us.
  CHECK(PhyRate::legacy_duration(14, 24) == Time::us(28));
  CHECK(PhyRate::legacy_duration(14, 6) == Time::us(44));
  CHECK_THROWS_WITH(PhyRate(PhyParams{Standard::vht, 9, 80, 2, 800, 25}), Catch::Contains("control_rate_mbps"));
}
