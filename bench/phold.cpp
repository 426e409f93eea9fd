// PHOLD on the latsim kernel, a peer of the programs in ../shared/bench.
//
// N logical processes (LPs) start with K events each; every event counts
// itself on its LP, draws a destination LP and a delay, and schedules one new
// event there unless it would fall at or after the end time. The draws, their
// order and the integer ticks are those of the peers, so for the same flags
// every peer commits the same events with the same per-LP counts; `events=`
// on stdout and `check=` on stderr must match theirs exactly.
//
// Each event is a callback scheduled with Simulator::at() and run by
// Simulator::run(), i.e. the full public kernel path: kind accounting,
// fingerprint, cancellable ids and the type-erased callback slab included.
//
// Run: build/phold --lps 1024 --epl 16 --end 1000 [--seed S] [--mean M]
//      [--lookahead L] [--queue quaternary|binary]
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "latsim/des/simulator.hpp"
#include "py_random.hpp"

namespace {

using latsim::bench::PyRandom;
using latsim::des::KindId;
using latsim::des::QueueKind;
using latsim::des::Simulator;
using latsim::des::Time;

// Model time unit in ticks (ps): shared with the peers.
constexpr double kTicksPerUnit = 1e9;

uint64_t to_ticks(double units) { return static_cast<uint64_t>(units * kTicksPerUnit + 0.5); }

// The peers' command-line parameters, plus the choice of pending-event set.
struct Options {
  uint32_t lps = 1024;
  uint32_t epl = 16;
  double end = 1000.0;
  uint64_t seed = 1;
  double mean = 1.0;
  double lookahead = 0.1;
  QueueKind queue = QueueKind::quaternary_heap;
};

[[noreturn]] void usage(const char* prog, int status) {
  std::fprintf(stderr,
               "usage: %s [--lps N] [--epl K] [--end T] [--seed S] [--mean M] [--lookahead L] "
               "[--queue quaternary|binary]\n",
               prog);
  std::exit(status);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    std::string flag = argv[i];
    if (flag == "-h" || flag == "--help") usage(argv[0], 0);
    std::string value;
    if (const auto eq = flag.find('='); eq != std::string::npos) {
      value = flag.substr(eq + 1);
      flag.resize(eq);
    } else if (i + 1 < argc) {
      value = argv[++i];
    } else {
      usage(argv[0], 2);
    }
    try {
      if (flag == "--lps") o.lps = static_cast<uint32_t>(std::stoul(value));
      else if (flag == "--epl") o.epl = static_cast<uint32_t>(std::stoul(value));
      else if (flag == "--end") o.end = std::stod(value);
      else if (flag == "--seed") o.seed = std::stoull(value);
      else if (flag == "--mean") o.mean = std::stod(value);
      else if (flag == "--lookahead") o.lookahead = std::stod(value);
      else if (flag == "--queue" && value == "quaternary") o.queue = QueueKind::quaternary_heap;
      else if (flag == "--queue" && value == "binary") o.queue = QueueKind::binary_heap;
      else usage(argv[0], 2);
    } catch (const std::exception&) {
      std::fprintf(stderr, "bad value '%s' for %s\n", value.c_str(), flag.c_str());
      std::exit(2);
    }
  }
  if (o.lps == 0 || o.end < 0 || o.mean < 0 || o.lookahead < 0) {
    std::fprintf(stderr, "invalid parameters: need lps > 0 and end, mean, lookahead >= 0\n");
    std::exit(2);
  }
  return o;
}

// The PHOLD model: per-LP counters and the one random stream.
class Phold {
 public:
  Phold(Simulator& sim, const Options& o)
      : sim_(sim), kind_(sim.kind("phold.event")), rng_(o.seed), lps_(o.lps), mean_(o.mean),
        lookahead_(o.lookahead), end_ticks_(to_ticks(o.end)), counts_(o.lps, 0) {}

  // Draw order is fixed across peers: destination first, then delay.
  uint32_t draw_destination() { return static_cast<uint32_t>(rng_.random() * static_cast<double>(lps_)); }
  uint64_t draw_delay_ticks() {
    const double exponential = -std::log(1.0 - rng_.random());
    return to_ticks(lookahead_ + mean_ * exponential);
  }

  void schedule(uint64_t when_ticks, uint32_t lp) {
    if (when_ticks >= end_ticks_) return;
    sim_.at(Time::ps(static_cast<int64_t>(when_ticks)), kind_, [this, lp] { on_event(lp); });
  }

  void on_event(uint32_t lp) {
    ++counts_[lp];
    const uint32_t dest = draw_destination();
    const uint64_t delay = draw_delay_ticks();
    schedule(static_cast<uint64_t>(sim_.now().ticks()) + delay, dest);
  }

  // FNV-1a over the 64-bit per-LP counts, as the peers compute `check=`.
  uint64_t checksum() const {
    uint64_t h = 1469598103934665603ull;
    for (const uint64_t c : counts_) {
      h ^= c;
      h *= 1099511628211ull;
    }
    return h;
  }

 private:
  Simulator& sim_;
  KindId kind_;
  PyRandom rng_;
  uint32_t lps_;
  double mean_;
  double lookahead_;
  uint64_t end_ticks_;
  std::vector<uint64_t> counts_;
};

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  Simulator sim(o.queue);
  Phold model(sim, o);
  const std::size_t population = static_cast<std::size_t>(o.lps) * o.epl;
  sim.reserve(population + 1);

  // Initial events: LP-major, one delay draw each; drawn before the clock starts.
  std::vector<uint64_t> first(population);
  for (uint64_t& t : first) t = model.draw_delay_ticks();

  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < population; ++i) model.schedule(first[i], static_cast<uint32_t>(i / o.epl));
  sim.run();
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const uint64_t events = sim.events_executed();
  std::printf("events=%llu wall_s=%.6f events_per_s=%.1f\n", static_cast<unsigned long long>(events), wall_s,
              wall_s > 0 ? static_cast<double>(events) / wall_s : 0.0);
  std::fflush(stdout);
  std::fprintf(stderr, "phold_latsim queue=%s lps=%u epl=%u end=%g seed=%llu mean=%g lookahead=%g check=%016llx\n",
               o.queue == QueueKind::binary_heap ? "binary" : "quaternary", o.lps, o.epl, o.end,
               static_cast<unsigned long long>(o.seed), o.mean, o.lookahead,
               static_cast<unsigned long long>(model.checksum()));
  return 0;
}
