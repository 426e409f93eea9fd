// How fast a capture loads: writes a PresentMon capture of N rows in the
// current column set (the 32 columns of PresentMon 2, two processes
// interleaved, 1 % NA), then reads two columns of one process with
// read_capture and reports the time, the rate and the peak memory.
//
//   build/capture_load_bench [rows=1000000] [file=/tmp/latsim_capture_bench.csv]
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "latsim/capture/capture.hpp"

namespace {

constexpr const char* kHeader =
    "Application,ProcessID,SwapChainAddress,PresentRuntime,SyncInterval,PresentFlags,AllowsTearing,PresentMode,"
    "FrameType,TimeInQPC,MsBetweenSimulationStart,MsBetweenPresents,MsBetweenDisplayChange,MsInPresentAPI,"
    "MsRenderPresentLatency,MsUntilDisplayed,MsPCLatency,CPUStartQPC,MsBetweenAppStart,MsCPUBusy,MsCPUWait,"
    "MsGPULatency,MsGPUTime,MsGPUBusy,MsGPUWait,MsVideoBusy,MsAnimationError,AnimationTime,MsFlipDelay,"
    "MsAllInputToPhotonLatency,MsClickToPhotonLatency,MsInstrumentedLatency\n";

double cpu_s() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) * 1e-6;
}

double peak_rss_mb() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_maxrss) / 1024.0;
}

// Deterministic values in the ranges of a real capture (a 60 Hz game).
void write_capture(const std::filesystem::path& file, long rows) {
  std::ofstream out(file, std::ios::binary);
  out << "\xEF\xBB\xBF" << kHeader;
  char line[512];
  unsigned x = 12345;
  for (long i = 0; i < rows; ++i) {
    x = x * 1103515245u + 12345u;
    const double cpu = 4.0 + (x >> 16) % 8000 / 1000.0, gpu = 6.0 + (x >> 8) % 9000 / 1000.0;
    const bool game = i % 4 != 3;
    const char* displayed = i % 100 == 50 ? "NA" : "16.6667";
    std::snprintf(line, sizeof line,
                  "%s,%d,0x224B280A1C0,DXGI,1,0,0,Hardware: Independent Flip,Application,%ld,NA,16.6667,16.6667,"
                  "0.0893,0.0673,%s,NA,%ld,16.3893,%.4f,0.0893,0.8529,15.5144,%.4f,1.2,0.0000,NA,332.7030,NA,NA,NA,NA\n",
                  game ? "game.exe" : "dwm.exe", game ? 4242 : 1268, 2076674276L + i * 166667L, displayed,
                  2076511276L + i * 166667L, cpu, gpu);
    out << line;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const long rows = argc > 1 ? std::atol(argv[1]) : 1000000;
  const std::filesystem::path file = argc > 2 ? argv[2] : "/tmp/latsim_capture_bench.csv";
  write_capture(file, rows);
  const double rss_before = peak_rss_mb();
  const double cpu_before = cpu_s();
  const auto start = std::chrono::steady_clock::now();
  const latsim::capture::Capture c =
      latsim::capture::read_capture(file, {{"MsCPUBusy", "MsGPUBusy"}, {"game.exe", std::nullopt}});
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double busy_s = cpu_s() - cpu_before;
  const double mib = static_cast<double>(std::filesystem::file_size(file)) / (1 << 20);
  std::printf("rows %ld, file %.1f MiB, kept %lld rows x 2 columns: %.3f s (CPU %.3f s), %.2f M rows/s, %.0f MiB/s, "
              "peak RSS %.1f MB (%.1f MB before reading)\n",
              rows, mib, static_cast<long long>(c.rows_selected), wall_s, busy_s, static_cast<double>(rows) / wall_s / 1e6,
              mib / wall_s, peak_rss_mb(), rss_before);
  std::filesystem::remove(file);
  return 0;
}
