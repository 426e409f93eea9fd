#include "latsim/results/presentmon_log.hpp"

#include <limits>
#include <string_view>

#include "cursor_text.hpp"
#include "latsim/results/csv_text.hpp"

namespace latsim::results {

namespace {

using cursor::put;
using cursor::put_fixed;
using cursor::put_int;

constexpr int64_t kPsPerMs = 1'000'000'000;
constexpr int64_t kPsPerS = 1'000'000'000'000;
// Rows gather in memory and go to the file this many bytes at a time.
constexpr size_t kBatchBytes = size_t{60} << 10;
// The longest a row's cells after the application name and the present mode
// can be: 17 numbers of at most 20 digits, a sign, a point and 12 decimals
// each, the fixed text.
constexpr size_t kRowBytes = 17 * 40 + 128;

void put_ms(char*& p, des::Time t) {
  *p++ = ',';
  put_fixed<kPsPerMs, 9>(p, t.ticks());
}

void put_s(char*& p, des::Time t) {
  *p++ = ',';
  put_fixed<kPsPerS, 12>(p, t.ticks());
}

void put_na(char*& p) { put(p, ",NA"); }

// The PresentMode cell with the comma before it (NA when the pipeline models none).
std::string mode_cell(const std::string& mode) {
  std::string cell(1, ',');
  cell.append(mode.empty() ? std::string("NA") : csv_field(mode));
  return cell;
}

}  // namespace

const std::vector<std::string>& PresentMonLog::columns() {
  static const std::vector<std::string> cols{
      "Application",      "ProcessID",  "SwapChainAddress",       "PresentRuntime",
      "SyncInterval",     "AllowsTearing", "FrameType",           "TimeInSeconds",
      "MsBetweenPresents", "MsBetweenDisplayChange", "MsRenderPresentLatency", "MsUntilDisplayed",
      "CPUStartTimeInSeconds", "MsCPUBusy", "MsGPULatency",       "MsGPUTime",
      "MsGPUBusy",        "MsGPUWait",  "FrameId",                "PresentMode",
      "MsInPresentAPI",   "MsCPUWait",  "MsBetweenAppStart",      "MsUntilScanout"};
  return cols;
}

PresentMonLog::Pending& PresentMonLog::pending(int64_t frame) {
  while (base_ + static_cast<int64_t>(pending_.size()) <= frame) pending_.emplace_back();
  return pending_[static_cast<size_t>(frame - base_)];
}

void PresentMonLog::completed(const FrameTimes& f, RunFiles& files) {
  if (f.frame < base_) return;
  pending(f.frame).times = f;
  // Frames that are never shown are final once complete.
  flush(files, presents_.shown ? newest_shown_ : std::numeric_limits<int64_t>::max());
}

void PresentMonLog::shown(int64_t frame, des::Time photon, RunFiles& files) {
  if (frame < base_) return;
  Pending& p = pending(frame);
  // Both eyes, and strips, are images of one frame: the earliest photon is its first.
  if (!p.photon || photon < *p.photon) p.photon = photon;
  if (frame > newest_shown_) newest_shown_ = frame;
  flush(files, newest_shown_);
}

// Writes the complete rows in order below `below_frame`: no image of theirs
// can be lit for the first time any more.
void PresentMonLog::flipped(int64_t frame, des::Time t) {
  if (frame < base_) return;
  Pending& p = pending(frame);
  if (!p.flip || t < *p.flip) p.flip = t;
}

void PresentMonLog::flush(RunFiles& files, int64_t below_frame) {
  while (!pending_.empty() && base_ < below_frame && pending_.front().times) {
    write_row(*pending_.front().times, pending_.front(), files);
    pending_.pop_front();
    ++base_;
  }
}

void PresentMonLog::finish(RunFiles& files) {
  // The last frame shown is final too; frames never completed have no row.
  const int64_t last = presents_.shown ? newest_shown_ : std::numeric_limits<int64_t>::max();
  while (!pending_.empty() && base_ <= last) {
    if (pending_.front().times) write_row(*pending_.front().times, pending_.front(), files);
    pending_.pop_front();
    ++base_;
  }
  if (!file_.is_open()) return;
  file_.write(batch_);
  batch_.clear();
  files.commit(file_, "presentmon.csv");
}

void PresentMonLog::write_row(const FrameTimes& f, const Pending& pend, RunFiles& files) {
  const std::optional<des::Time>& photon = pend.photon;
  if (!file_.is_open()) {
    file_ = files.stream("presentmon.csv");
    for (const std::string& c : columns()) batch_ += (batch_.empty() ? "" : ",") + c;
    batch_ += '\n';
    // The cells every row begins with.
    prefix_ = csv_field(application_) + ",0,0x0,latsim," + std::to_string(presents_.sync_interval) +
              (presents_.allows_tearing ? ",1" : ",0") + ",Application";
    mode_cell_ = mode_cell(presents_.present_mode);
  }
  const size_t at = batch_.size();
  batch_.resize(at + prefix_.size() + mode_cell_.size() + kRowBytes);
  char* const begin = batch_.data() + at;
  char* p = begin;
  put(p, prefix_);
  put_s(p, f.present);
  if (last_present_) put_ms(p, f.present - *last_present_);
  else put_na(p);
  if (photon && last_photon_) put_ms(p, *photon - *last_photon_);
  else put_na(p);
  put_ms(p, f.gpu_end - f.present);
  if (photon) put_ms(p, *photon - f.present);
  else put_na(p);
  if (f.has_cpu) {
    put_s(p, f.cpu_start);
    put_ms(p, f.cpu_busy);
    put_ms(p, f.gpu_start - f.cpu_start);
  } else {
    put(p, ",NA,NA,NA");
  }
  put_ms(p, f.gpu_end - f.gpu_start);
  put_ms(p, f.gpu_busy);
  put_ms(p, (f.gpu_end - f.gpu_start) - f.gpu_busy);
  *p++ = ',';
  put_int(p, f.frame);
  put(p, mode_cell_);
  if (f.in_present) {
    put_ms(p, *f.in_present);
    put_ms(p, *f.in_present);
    if (f.has_cpu) put_ms(p, f.cpu_busy + *f.in_present);
    else put_na(p);
  } else {
    put(p, ",NA,NA,NA");
  }
  // Where the pipeline says when the frame's scanout began: PresentMon's display time.
  if (photon && pend.flip) put_ms(p, *pend.flip - f.present);
  else put_na(p);
  *p++ = '\n';
  batch_.resize(at + static_cast<size_t>(p - begin));
  if (batch_.size() >= kBatchBytes) {
    file_.write(batch_);
    batch_.clear();
  }
  last_present_ = f.present;
  if (photon) last_photon_ = photon;
  ++rows_;
}

}  // namespace latsim::results
