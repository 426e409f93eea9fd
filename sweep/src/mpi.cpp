#include "latsim/sweep/mpi.hpp"

#include <iostream>

#ifdef LATSIM_HAVE_MPI

#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <thread>
#include <vector>

#include "latsim/run/exit_codes.hpp"
#include "latsim/sweep/cost.hpp"
#include "latsim/sweep/progress_line.hpp"
#include "latsim/sweep/tables.hpp"

namespace latsim::sweep {

using run::kExitBadInput;
using run::kExitFailure;
using run::kExitOk;

namespace {

using Json = nlohmann::json;

constexpr int kToRankZero = 1;
constexpr int kToRank = 2;
// Runs a rank holds at once (running and next), so that it never waits for
// rank 0 to poll between two runs.
constexpr size_t kRunsInHand = 2;

// Waits by sleeping between polls: Open MPI's blocking calls spin on a core
// that the runs of this or another rank need.
class Backoff {
 public:
  void sleep() {
    std::this_thread::sleep_for(delay_);
    delay_ = std::min(delay_ * 2, std::chrono::microseconds(1000));
  }
  void reset() { delay_ = std::chrono::microseconds(20); }

 private:
  std::chrono::microseconds delay_{20};
};

struct Message {
  int source = 0;
  Json body;
};

/// Sends without waiting for the receiver: Open MPI's MPI_Send may spin until
/// the message is taken, which a rank busy with a run does only between runs.
class Outbox {
 public:
  Outbox() = default;
  Outbox(const Outbox&) = delete;
  Outbox& operator=(const Outbox&) = delete;
  ~Outbox() { flush(); }

  void post(int rank, int tag, const Json& body) {
    auto text = std::make_unique<std::string>(body.dump());
    MPI_Request request;
    MPI_Isend(text->data(), static_cast<int>(text->size()), MPI_CHAR, rank, tag, MPI_COMM_WORLD, &request);
    pending_.push_back({std::move(text), request});
  }
  /// Lets go of the messages delivered so far.
  void progress() {
    std::erase_if(pending_, [](Pending& p) {
      int done = 0;
      MPI_Test(&p.request, &done, MPI_STATUS_IGNORE);
      return done != 0;
    });
  }
  /// Waits until every message is delivered.
  void flush();

 private:
  struct Pending {
    std::unique_ptr<std::string> text;  ///< must outlive the send
    MPI_Request request;
  };
  std::vector<Pending> pending_;
};

std::optional<Message> try_receive(int source, int tag) {
  int arrived = 0;
  MPI_Status status;
  MPI_Iprobe(source, tag, MPI_COMM_WORLD, &arrived, &status);
  if (!arrived) return std::nullopt;
  int size = 0;
  MPI_Get_count(&status, MPI_CHAR, &size);
  std::string text(static_cast<size_t>(size), '\0');
  MPI_Recv(text.data(), size, MPI_CHAR, status.MPI_SOURCE, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return Message{status.MPI_SOURCE, Json::parse(text)};
}

Message receive(int source, int tag) {
  Backoff backoff;
  while (true) {
    if (auto message = try_receive(source, tag)) return std::move(*message);
    backoff.sleep();
  }
}

void Outbox::flush() {
  Backoff backoff;
  for (progress(); !pending_.empty(); progress()) backoff.sleep();
}

// MPI_Finalize synchronises the ranks and spins while it waits; wait for the
// others here first, politely.
void quiet_barrier() {
  MPI_Request request;
  MPI_Ibarrier(MPI_COMM_WORLD, &request);
  Backoff backoff;
  for (int done = 0; MPI_Test(&request, &done, MPI_STATUS_IGNORE), !done;) backoff.sleep();
}

/// MPI from initialisation to finalisation.
class MpiSession {
 public:
  explicit MpiSession(const std::atomic<bool>* stop) : stop_(stop) {
    int provided = 0;
    // Only the main thread of each rank calls MPI; run threads never do.
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  ~MpiSession() {
    // Stopped: mpiexec is ending the job, and finalising would wait for it
    // (every rank hung there until its stop watchdog ended it, 800 ms on).
    if (stop_ && stop_->load()) return;
    quiet_barrier();
    MPI_Finalize();
  }
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  const std::atomic<bool>* stop_;
  int rank_ = 0, size_ = 1;
};

bool stop_requested(const SweepRequest& request) { return request.stop && request.stop->load(); }

// Every rank but 0: run what rank 0 hands out until it says stop. Once a stop
// is requested, the runs in hand are dropped (rank 0 is told, so that it does
// not wait for them) and the rank waits only for rank 0's word.
int serve(const SweepRequest& request, const std::function<int(bool)>& on_stop) {
  Outbox outbox;
  outbox.post(0, kToRankZero, {{"ready", true}});
  std::optional<SweepWorkspace> work;  // created with the first run: bad input writes nothing
  std::deque<RunTask> inbox;
  bool stopped = false;
  auto take = [&](const Message& m) {
    if (m.body.contains("stop")) stopped = true;
    else inbox.push_back(RunTask::from_json(m.body.at("run")));
  };
  while (true) {
    outbox.progress();
    while (auto m = try_receive(0, kToRank)) take(*m);
    if (stop_requested(request) && !inbox.empty()) {
      outbox.post(0, kToRankZero, {{"dropped", inbox.size()}});
      inbox.clear();
    }
    if (inbox.empty()) {
      // The outbox delivers the last report before it goes.
      if (stopped) return stop_requested(request) ? on_stop(false) : kExitOk;
      take(receive(0, kToRank));
      continue;
    }
    const RunTask task = std::move(inbox.front());
    inbox.pop_front();
    if (!work) work.emplace(request);
    const size_t removed_before = work->executor.temporaries_removed();
    const RunAttempt attempt = work->executor.execute(task, 0);
    outbox.post(0, kToRankZero, {{"index", task.index}, {"attempt", attempt.to_json()},
                                 {"temporaries", work->executor.temporaries_removed() - removed_before}});
  }
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Tells every other rank there is nothing to do (after its first message, so none is left unreceived).
void stop_all(int size) {
  Outbox outbox;
  for (int rank = 1; rank < size; ++rank) {
    (void)receive(rank, kToRankZero);
    outbox.post(rank, kToRank, {{"stop", true}});
  }
}

/// Rank 0's hand-out of runs, in the order given: its own run threads take
/// from the same queue as the messages it sends to the other ranks.
class Dispatcher {
 public:
  Dispatcher(const SweepPlan& plan, KeepPolicy keep, std::vector<size_t> order, SweepWorkspace& work,
             unsigned threads, int ranks, const std::atomic<bool>* stop)
      : stop_(stop),
        plan_(plan), keep_(std::move(keep)), order_(std::move(order)), work_(work), threads_(threads), ranks_(ranks),
        attempts_(order_.size()), in_hand_(static_cast<size_t>(ranks), 0), stopped_(static_cast<size_t>(ranks), false) {
    for (size_t p = 0; p < order_.size(); ++p) position_of_[order_[p]] = p;
    stopped_[0] = true;  // rank 0's share is taken by its threads
  }

  /// Runs every run; the attempts come back in the order given.
  std::vector<RunAttempt> run(ProgressLine& progress) {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads_; ++t)
      pool.emplace_back([&, t] {
        while (const auto p = next()) {
          attempts_[*p] = work_.executor.execute(task(*p), t);
          progress.advance();
        }
        ++threads_done_;
      });
    Backoff backoff;
    while (!everyone_done()) {
      outbox_.progress();
      if (const auto message = try_receive(MPI_ANY_SOURCE, kToRankZero)) {
        answer(*message, progress);
        backoff.reset();
      } else {
        backoff.sleep();
      }
    }
    for (auto& thread : pool) thread.join();
    outbox_.flush();
    return std::move(attempts_);
  }
  size_t remote_temporaries() const { return remote_temporaries_; }

 private:
  std::optional<size_t> next() {
    if (stop_ && stop_->load()) return std::nullopt;  // stopping: nothing more is handed out or started
    const size_t p = next_.fetch_add(1);
    if (p < order_.size()) return p;
    return std::nullopt;
  }
  RunTask task(size_t position) const { return RunTask::of(plan_, plan_.runs()[order_[position]], keep_); }

  // A rank reported a run (or that it is ready): record it, and top its hand up or tell it to stop.
  void answer(const Message& message, ProgressLine& progress) {
    const auto r = static_cast<size_t>(message.source);
    if (message.body.contains("index")) {
      attempts_[position_of_.at(message.body["index"].get<size_t>())] = RunAttempt::from_json(message.body["attempt"]);
      remote_temporaries_ += message.body.value("temporaries", size_t{0});
      --in_hand_[r];
      progress.advance();
    }
    if (message.body.contains("dropped")) in_hand_[r] -= message.body["dropped"].get<size_t>();
    while (!stopped_[r] && in_hand_[r] < kRunsInHand) {
      if (const auto p = next()) {
        outbox_.post(message.source, kToRank, {{"run", task(*p).to_json()}});
        ++in_hand_[r];
      } else {
        outbox_.post(message.source, kToRank, {{"stop", true}});
        stopped_[r] = true;
      }
    }
  }

  bool everyone_done() const {
    for (size_t r = 1; r < static_cast<size_t>(ranks_); ++r)
      if (!stopped_[r] || in_hand_[r] > 0) return false;
    return threads_done_ == threads_;
  }

  const std::atomic<bool>* stop_;
  const SweepPlan& plan_;
  KeepPolicy keep_;
  std::vector<size_t> order_;
  SweepWorkspace& work_;
  unsigned threads_;
  int ranks_;
  std::vector<RunAttempt> attempts_;
  std::map<size_t, size_t> position_of_;  ///< plan index -> position in order_
  std::vector<size_t> in_hand_;           ///< per rank: runs sent and not yet reported
  std::vector<bool> stopped_;
  std::atomic<size_t> next_{0};
  std::atomic<unsigned> threads_done_{0};
  size_t remote_temporaries_ = 0;
  Outbox outbox_;
};

// Rank 0: check the plan, hand the runs out, write the tables.
int lead(SweepRequest request, int size, const std::function<int(bool)>& on_stop) {
  const auto start = std::chrono::steady_clock::now();
  const auto plan = load_plan(request);
  if (!plan || !settle_keep(request, *plan)) {
    stop_all(size);
    return stop_requested(request) ? on_stop(true) : kExitBadInput;
  }
  PhaseTimes phases;
  phases.plan_s = seconds_since(start);
  std::vector<size_t> all(plan->runs().size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  const PointCheck check = check_points(*plan, all, request.jobs, request.max_events, request.stop);
  if (check.stopped) {
    stop_all(size);
    return on_stop(true);
  }
  phases.check_s = check.wall_s;
  phases.points = check.points;
  if (check.problem) {
    std::cerr << request.sweep_file << ": " << *check.problem << "\n";
    stop_all(size);
    return kExitBadInput;
  }

  SweepWorkspace work(request);
  write_file_if_changed(work.store.out_dir() / "plan.json", plan->to_json().dump(2) + "\n");
  SweepTally tally;
  std::vector<size_t> pending;
  const std::set<std::string> finished = work.store.finished_runs();
  for (size_t i : all) {
    if (finished.count(plan->runs()[i].run_id)) ++tally.resumed;
    else pending.push_back(i);
  }
  pending = longest_first(pending, check.cost_of_run);
  const auto runs_start = std::chrono::steady_clock::now();
  ProgressLine progress("sweep", plan->runs().size(), tally.resumed);
  Dispatcher dispatcher(*plan, request.keep, pending, work, request.jobs, size, request.stop);
  const auto attempts = dispatcher.run(progress);
  progress.finish();
  // Stopped: what finished is in the store and the claims, for the same command to resume; no tables.
  if (stop_requested(request)) return on_stop(true);
  phases.runs_s = seconds_since(runs_start);
  tally.add(*plan, pending, attempts);

  size_t temporaries = work.executor.temporaries_removed() + dispatcher.remote_temporaries();
  const auto tables_start = std::chrono::steady_clock::now();
  // Every rank is done: rank 0 may use its whole node for the tables.
  const size_t gathered = write_tables(*plan, work.store, available_cpus(), temporaries);
  phases.tables_s = seconds_since(tables_start);
  std::printf("sweep: %zu runs %s on %d MPI rank(s) x %u thread(s) in %.2f s -> %s\n", plan->runs().size(),
              tally.counts().c_str(), size, request.jobs, seconds_since(start),
              (work.store.out_dir() / "results.csv").c_str());
  tally.print_notes(temporaries);
  if (request.timings) phases.print(tally.times, request.jobs);
  return tally.failures.empty() && gathered == plan->runs().size() ? kExitOk : kExitFailure;
}

}  // namespace

int sweep_mpi(const SweepRequest& request, const std::function<int(bool lead)>& stopped) {
  MpiSession mpi(request.stop);
  try {
    return mpi.rank() == 0 ? lead(request, mpi.size(), stopped) : serve(request, stopped);
  } catch (const std::exception& e) {
    // The other ranks would wait for this one for ever.
    std::cerr << "sweep: MPI rank " << mpi.rank() << ": " << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, kExitFailure);
    return kExitFailure;
  }
}

}  // namespace latsim::sweep

#else

namespace latsim::sweep {

int sweep_mpi(const SweepRequest&, const std::function<int(bool)>&) {
  std::cerr << "latsim sweep: --mpi: this latsim was built without MPI (install libopenmpi-dev and configure with "
               "-DLATSIM_MPI=ON)\n";
  return 2;
}

}  // namespace latsim::sweep

#endif
