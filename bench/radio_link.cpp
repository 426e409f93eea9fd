// The radio link benchmark, latsim's side: the traffic of
// bench/radio_link_ns3.cpp on latsim's Wi-Fi model (models/radio).
//
// An access point sends a video stream to a headset: every 1/fps seconds all
// packets of one frame are queued at the AP at once; background stations
// send Poisson packets to the AP. VHT, one 80 MHz channel, a fixed MCS, BE
// EDCA, A-MPDU of up to 65535 bytes, BlockAck at 24 Mb/s, no losses but
// collisions. Prints, like the peer:
//   frames=N mean_ms=M p50_ms=... p99_ms=... max_ms=... incomplete=K
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "delivery_line.hpp"
#include "latsim/des/simulator.hpp"
#include "latsim/radio/bss.hpp"
#include "latsim/radio/traffic.hpp"

using namespace latsim;

namespace {

struct Options {
  double fps = 90, duration_s = 20, warmup_s = 1, bg_mbps = 0;
  long frame_bytes = 208333, packet_bytes = 1400, bg_stations = 0, bg_packet_bytes = 1500, seed = 1;
  int mcs = 9, width = 80, streams = 2;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const size_t eq = a.find('=');
    if (a.rfind("--", 0) != 0 || eq == std::string::npos) {
      std::fprintf(stderr, "usage: radio_link [--name=value]... (see bench/radio_link_ns3.cpp)\n");
      std::exit(2);
    }
    const std::string k = a.substr(2, eq - 2);
    const double v = std::atof(a.c_str() + eq + 1);
    if (k == "fps") o.fps = v;
    else if (k == "duration") o.duration_s = v;
    else if (k == "warmup") o.warmup_s = v;
    else if (k == "bg-mbps") o.bg_mbps = v;
    else if (k == "frame-bytes") o.frame_bytes = static_cast<long>(v);
    else if (k == "packet-bytes") o.packet_bytes = static_cast<long>(v);
    else if (k == "bg-stations") o.bg_stations = static_cast<long>(v);
    else if (k == "bg-packet-bytes") o.bg_packet_bytes = static_cast<long>(v);
    else if (k == "seed") o.seed = static_cast<long>(v);
    else if (k == "mcs") o.mcs = static_cast<int>(v);
    else if (k == "width") o.width = static_cast<int>(v);
    else if (k == "streams") o.streams = static_cast<int>(v);
    else {
      std::fprintf(stderr, "radio_link: unknown option --%s\n", k.c_str());
      std::exit(2);
    }
  }
  return o;
}

struct Frame {
  des::Time queued;
  long packets = 0;
  long arrived = 0;
  des::Time done = des::Time::ps(-1);
};

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  des::Simulator sim;
  const radio::PhyRate phy(radio::PhyParams{radio::Standard::vht, o.mcs, o.width, o.streams, 800, 24});
  radio::Bss bss(sim, phy, radio::MacParams{}, des::RandomStream(static_cast<uint64_t>(o.seed), "radio"));
  const radio::EdcaParams be = radio::EdcaParams::for_category("BE");
  const int ap = bss.add_station("ap", be);
  const int headset = bss.add_station("headset", be);
  std::vector<Frame> frames(static_cast<size_t>(o.duration_s * o.fps));
  bss.on_delivered([&](const radio::Packet& p, des::Time t) {
    if (p.to != headset) return;
    Frame& f = frames[static_cast<size_t>(p.tag)];
    if (++f.arrived == f.packets) f.done = t;
  });
  const des::Time start = des::Time::ms(600), end = start + des::Time::from_seconds(o.duration_s);
  std::vector<std::unique_ptr<radio::TrafficSource>> background;
  for (long i = 0; i < o.bg_stations && o.bg_mbps > 0; ++i) {
    const std::string name = "background" + std::to_string(i);
    const int st = bss.add_station(name, be);
    background.push_back(std::make_unique<radio::TrafficSource>(
        sim, bss,
        radio::TrafficParams{st, ap, o.bg_mbps * 1e6 / static_cast<double>(o.bg_stations), o.bg_packet_bytes,
                             radio::TrafficParams::Arrivals::poisson},
        des::RandomStream(static_cast<uint64_t>(o.seed), name)));
    background.back()->start(start, end);
  }
  const des::PeriodicSchedule frame_times(start, des::RationalSeconds{1000, static_cast<int64_t>(o.fps * 1000)});
  const des::KindId kind = sim.kind("bench.frame");
  for (size_t n = 0; n < frames.size(); ++n)
    sim.at(frame_times.at(static_cast<int64_t>(n)), kind, [&, n] {
      Frame& f = frames[n];
      f.queued = sim.now();
      f.packets = (o.frame_bytes + o.packet_bytes - 1) / o.packet_bytes;
      for (long i = 0; i < f.packets; ++i)
        bss.send(ap, headset, i + 1 < f.packets ? o.packet_bytes : o.frame_bytes - o.packet_bytes * (f.packets - 1),
                 static_cast<int64_t>(n));
    });
  sim.run_until(end + des::Time::s(1));

  std::vector<double> ms;
  long incomplete = 0;
  for (size_t n = 0; n < frames.size(); ++n) {
    if (static_cast<double>(n) / o.fps < o.warmup_s) continue;
    if (frames[n].done < des::Time::zero()) ++incomplete;
    else ms.push_back((frames[n].done - frames[n].queued).to_ms());
  }
  bench::print_delivery_line(std::move(ms), static_cast<unsigned long long>(incomplete));
  std::fprintf(stderr, "collisions=%lld ppdus=%lld retransmissions=%lld busy_s=%.4f\n",
               static_cast<long long>(bss.counts().collisions), static_cast<long long>(bss.counts().ppdus),
               static_cast<long long>(bss.counts().retransmissions), bss.counts().busy.to_seconds());
  return 0;
}
