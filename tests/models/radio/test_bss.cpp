// The packet-level link on hand-derivable traffic: one exchange, an A-MPDU, a
// lost MPDU and its retransmission, a TXOP, and stations that always collide.
//
// Throughout: VHT MCS 9, 80 MHz, 2 streams, 800 ns GI (3120 bits per 4 us
// symbol, 44 us preamble, 2 BCC encoders: 12 tail bits), responses at
// 24 Mb/s (Ack 28 us, BlockAck 32 us), SIFS 16 us, slot 9 us, and
// contention windows of 0 so that every backoff is zero slots.
#include <catch2/catch.hpp>

#include <vector>

#include "latsim/des/simulator.hpp"
#include "latsim/radio/bss.hpp"

using latsim::des::RandomStream;
using latsim::des::Simulator;
using latsim::des::Time;
using namespace latsim::radio;

namespace {

struct Arrival {
  int64_t id;
  Time at;
};

struct Fixture {
  Simulator sim;
  Bss bss{sim, PhyRate(PhyParams{Standard::vht, 9, 80, 2, 800, 24}), MacParams{}, RandomStream(1, "radio")};
  std::vector<Arrival> arrivals;
  std::vector<std::pair<int64_t, LossReason>> losses;
  std::vector<Time> loss_times;
  Fixture() {
    bss.on_delivered([this](const Packet& p, Time t) { arrivals.push_back({p.id, t}); });
    bss.on_lost([this](const Packet& p, LossReason r) {
      losses.emplace_back(p.id, r);
      loss_times.push_back(sim.now());
    });
  }
};

constexpr EdcaParams kFixedBe{3, 0, 0, Time::zero()};

}  // namespace

TEST_CASE("one packet on an idle link: AIFS, the PPDU, received at its last symbol") {
  Fixture f;
  const int ap = f.bss.add_station("ap", kFixedBe);
  const int sta = f.bss.add_station("headset", kFixedBe);
  f.bss.send(ap, sta, 1000, 0);
  f.sim.run();
  // The medium counts as idle from 0 (a run starts with SIFS behind it), so
  // AIFS ends 3 slots later: sent at 27 us, with zero backoff slots.
  // MPDU: 1000 + 8 (LLC/SNAP) + 26 (QoS header) + 4 (FCS) = 1038 bytes, in a
  // 1042-byte subframe: 56 us (test_phy_rate). Received at 27 + 56 = 83 us.
  REQUIRE(f.arrivals.size() == 1);
  CHECK(f.arrivals[0].at == Time::us(83));
  CHECK(f.bss.counts().ppdus == 1);
  CHECK(f.bss.counts().busy == Time::us(56 + 28));
}

TEST_CASE("two packets aggregate, a lost MPDU is retransmitted after the BlockAck") {
  Fixture f;
  const int ap = f.bss.add_station("ap", kFixedBe);
  const int sta = f.bss.add_station("headset", kFixedBe);
  bool lost_once = false;
  f.bss.set_forced_loss([&](const Packet& p) {
    if (p.tag != 2 || lost_once) return false;
    lost_once = true;
    return true;
  });
  f.sim.at(Time::ms(1), f.sim.kind("test.send"), [&] {
    f.bss.send(ap, sta, 1000, 1);
    f.bss.send(ap, sta, 1000, 2);
  });
  f.sim.run();
  // At 1000 us on a medium idle since 0 the frame goes at the next slot
  // boundary after AIFS: 27 + 9 * (floor(973 / 9) + 1) = 1008 us.
  // Subframes 1044 (padded) + 1042 = 2086 bytes: 16 + 16688 + 12 bits -> 6
  // symbols, 68 us. MPDU 1 is received after 3 symbols (56 us): 1064 us.
  // MPDU 2 is lost; the BlockAck (it answers MPDU 1) ends at
  // 1008 + 68 + 16 + 32 = 1124 us; a new zero backoff; idle from SIFS after
  // it (1140 us), AIFS ends 1167 us: MPDU 2 again, alone, received 56 us
  // later at 1223 us.
  REQUIRE(f.arrivals.size() == 2);
  CHECK(f.arrivals[0].at == Time::us(1064));
  CHECK(f.arrivals[1].at == Time::us(1223));
  CHECK(f.bss.counts().retransmissions == 1);
  CHECK(f.bss.counts().ppdus == 2);
}

TEST_CASE("a TXOP limit lets a station send A-MPDU after A-MPDU, a SIFS apart") {
  Fixture f;
  EdcaParams vi{2, 0, 0, Time::us(3008)};
  const int ap = f.bss.add_station("ap", vi);
  const int sta = f.bss.add_station("headset", kFixedBe);
  for (int i = 0; i < 100; ++i) f.bss.send(ap, sta, 1400, i);
  f.sim.run();
  // 1400-byte packets: 1438-byte MPDUs, 1444-byte padded subframes; 45 fit
  // in 65535 bytes (44 * 1444 + 1442 = 64978; 46 would need 66422): 712 us.
  // AIFS of 2 slots from 0: the first PPDU at 18 us, its BlockAck ends at
  // 18 + 712 + 16 + 32 = 778 us, the second PPDU starts a SIFS later, 794 us,
  // with its first MPDU received after ceil((16 + 8 * 1442) / 3120) = 4
  // symbols (60 us): 854 us. The 46th packet (index 45) is that MPDU.
  REQUIRE(f.arrivals.size() == 100);
  CHECK(f.arrivals[44].at == Time::us(18 + 712));
  CHECK(f.arrivals[45].at == Time::us(854));
  // The third PPDU (10 packets) still fits in the TXOP: 794 + 712 + 48 = 1554 us.
  CHECK(f.bss.counts().ppdus == 3);
}

TEST_CASE("two stations whose backoffs always expire together collide until the retry limit") {
  Fixture f;
  const int a = f.bss.add_station("a", kFixedBe);
  const int b = f.bss.add_station("b", kFixedBe);
  f.bss.send(a, b, 1000, 0);
  f.bss.send(b, a, 1000, 0);
  f.sim.run();
  // Both go at 27 us, PPDUs end at 83 us, nobody answers: each times out at
  // 83 + 16 + 9 + 20 = 128 us, draws zero slots, is idle from 144 us and goes
  // again at 171 us: a collision every 144 us. The first transmission and 7
  // retries collide; the last times out at 27 + 7 * 144 + 101 = 1136 us.
  CHECK(f.arrivals.empty());
  CHECK(f.bss.counts().collisions == 8);
  REQUIRE(f.losses.size() == 2);
  CHECK(f.losses[0].second == LossReason::retry_limit);
  CHECK(f.loss_times[0] == Time::us(1136));
}

TEST_CASE("a full queue drops the newest packet, an old one expires") {
  MacParams mac;
  mac.queue_packets = 2;
  mac.queue_max_delay = Time::us(10);
  Simulator sim;
  Bss bss(sim, PhyRate(PhyParams{}), mac, RandomStream(1, "radio"));
  std::vector<LossReason> why;
  bss.on_lost([&](const Packet&, LossReason r) { why.push_back(r); });
  const int ap = bss.add_station("ap", kFixedBe);
  const int sta = bss.add_station("sta", kFixedBe);
  for (int i = 0; i < 3; ++i) bss.send(ap, sta, 100, i);
  sim.run();
  // The third packet finds the queue full; the first two have waited 27 us
  // (AIFS) when the station wins the medium: more than 10 us, both expire.
  REQUIRE(why.size() == 3);
  CHECK(why[0] == LossReason::queue_full);
  CHECK(why[1] == LossReason::expired);
}

TEST_CASE("a collision of unequal PPDUs ends for everyone whose backoff has run out meanwhile") {
  // a (1000 bytes, 56 us) and b (8000 bytes: 16 + 64336 + 12 bits -> 21
  // symbols, 128 us) both go at 18 us (AIFSN 2, CW 0) and collide; b's PPDU
  // ends at 146 us, its timeout at 146 + 16 + 9 + 20 = 191 us, when the
  // collision's end is handled; with the retry limit at 0 both frames are
  // discarded then. c, whose frame arrived during the collision (a zero
  // backoff drawn), may count from SIFS after the medium went quiet, 162
  // us: its AIFS ends at 180 us, an instant that has passed when the end is
  // handled. It transmits at 191 us (it was due already) instead of waiting
  // for an access that never comes: its 56 us PPDU is received at 247 us.
  MacParams mac;
  mac.retry_limit = 0;
  Simulator sim;
  Bss bss(sim, PhyRate(PhyParams{Standard::vht, 9, 80, 2, 800, 24}), mac, RandomStream(1, "radio"));
  std::vector<Time> lost, delivered;
  bss.on_lost([&](const Packet&, LossReason) { lost.push_back(sim.now()); });
  bss.on_delivered([&](const Packet&, Time t) { delivered.push_back(t); });
  const EdcaParams fixed{2, 0, 0, Time::zero()};
  const int a = bss.add_station("a", fixed);
  const int b = bss.add_station("b", fixed);
  const int c = bss.add_station("c", fixed);
  bss.send(a, c, 1000, 0);
  bss.send(b, c, 8000, 0);
  sim.at(Time::us(50), sim.kind("test.send"), [&] { bss.send(c, a, 1000, 0); });
  sim.run();
  CHECK(bss.counts().collisions == 1);
  REQUIRE(lost.size() == 2);
  CHECK(lost[0] == Time::us(191));
  REQUIRE(delivered.size() == 1);
  CHECK(delivered[0] == Time::us(247));
}
