#include "arp/region_report.hpp"

#include <sstream>

#include "latsim/arp/memory_frames.hpp"
#include "latsim/results/run_files.hpp"

namespace latsim::pipelines {
namespace {

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(digits);
  s << v;
  return s.str();
}

struct MemoryRow {
  double rate_hz = 0.0;
  double segments = 0.0;
};

MemoryRow row_of(const RegionRun& run, int memory, des::Time duration) {
  const arp::MemoryRenderCounts& c = run.system().memories().counts(memory);
  const double renders = static_cast<double>(c.renders);
  return {renders / duration.to_seconds(), c.renders > 0 ? static_cast<double>(c.object_segments) / renders : 0.0};
}

double render_load(const RegionRun& run, des::Time duration) {
  int64_t segments = 0;
  for (int m = 0; m < run.system().model().memory_count(); ++m) segments += run.system().memories().counts(m).object_segments;
  return static_cast<double>(segments) / duration.to_seconds();
}

int64_t skipped(const RegionRun& run) {
  int64_t n = 0;
  for (int m = 0; m < run.system().model().memory_count(); ++m) n += run.system().memories().queue().skipped(m);
  return n;
}

// The head of a memories table: a rate and a segments column per run.
void memories_header(std::ostringstream& md, const std::vector<const RegionRun*>& runs) {
  md << "| memory |";
  for (const RegionRun* run : runs) md << " update rate, " << run->label() << " (Hz) |";
  for (const RegionRun* run : runs) md << " segments per update, " << run->label() << " |";
  md << "\n|---|";
  for (size_t i = 0; i < 2 * runs.size(); ++i) md << "---|";
  md << "\n";
}

}  // namespace

std::string memories_markdown(const std::vector<const RegionRun*>& runs, des::Time duration, des::Time window) {
  std::ostringstream md;
  memories_header(md, runs);
  for (int m = 0; m < runs[0]->system().model().memory_count(); ++m) {
    md << "| " << m << " |";
    for (const RegionRun* run : runs) md << " " << fixed(row_of(*run, m, duration).rate_hz, 2) << " |";
    for (const RegionRun* run : runs) md << " " << fixed(row_of(*run, m, duration).segments, 1) << " |";
    md << "\n";
  }
  md << "\nSegments are object segments (an object's part within one region), counted alike with and without "
        "segmentation.\n\n| run | render load (segments/s) | renderer utilisation | renders skipped | tear gap max "
        "(px) | tear gap p99 (px) | stretch max (px) | stretch p99 (px) |\n|---|---|---|---|---|---|---|---|\n";
  for (const RegionRun* run : runs) {
    const stats::Distribution& tears = run->tear_gap_px();
    const stats::Distribution& stretch = run->stretch_px();
    md << "| " << run->label() << " | " << fixed(render_load(*run, duration), 0) << " | "
       << fixed(run->system().memories().queue().utilisation(duration), 3) << " | " << skipped(*run) << " | "
       << fixed(tears.summary().max, 3) << " | " << fixed(tears.quantile(0.99), 3) << " | "
       << (run->warping() ? fixed(stretch.summary().max, 3) : "—") << " | "
       << (run->warping() ? fixed(stretch.quantile(0.99), 3) : "—") << " |\n";
  }
  if (!runs[0]->has_window()) return md.str();
  md << "\nOver the position window (" << fixed(window.to_seconds(), 3)
     << " s): per update, object segments and, in brackets, segments or whole objects drawn (each once).\n\n";
  memories_header(md, runs);
  for (int m = 0; m < runs[0]->system().model().memory_count(); ++m) {
    md << "| " << m << " |";
    for (const RegionRun* run : runs) md << " " << fixed(run->window_row(m, window).rate_hz, 2) << " |";
    for (const RegionRun* run : runs) {
      const RegionRun::WindowRow row = run->window_row(m, window);
      md << " " << fixed(row.segments, 1) << " (" << fixed(row.drawn, 1) << ") |";
    }
    md << "\n";
  }
  return md.str();
}

std::string memories_csv(const std::vector<const RegionRun*>& runs, des::Time duration) {
  std::ostringstream csv;
  csv << "run,memory,update_rate_hz,segments_per_update,render_load,renderer_utilisation,renders_skipped,"
         "tear_gap_max_px,tear_gap_p99_px,stretch_max_px,stretch_p99_px\n";
  for (const RegionRun* run : runs) {
    const stats::Distribution& tears = run->tear_gap_px();
    const stats::Distribution& stretch = run->stretch_px();
    for (int m = 0; m < run->system().model().memory_count(); ++m) {
      const MemoryRow row = row_of(*run, m, duration);
      csv << '"' << run->label() << "\"," << m << ',' << fixed(row.rate_hz, 3) << ',' << fixed(row.segments, 2) << ','
          << fixed(render_load(*run, duration), 1) << ',' << fixed(run->system().memories().queue().utilisation(duration), 4)
          << ',' << skipped(*run) << ',' << fixed(tears.summary().max, 4) << ',' << fixed(tears.quantile(0.99), 4)
          << ',' << (run->warping() ? fixed(stretch.summary().max, 4) : "") << ','
          << (run->warping() ? fixed(stretch.quantile(0.99), 4) : "") << '\n';
    }
  }
  return csv.str();
}

RegionFrames::RegionFrames(const renderer::Camera& camera, const glm::dquat& head, const FrameOptions& options,
                           results::RunFiles& files)
    : camera_(camera), head_(head), options_(options), files_(files) {}

renderer::Frame RegionFrames::composite(const RegionRun& run, std::vector<renderer::CubeMap>* cubes_out) {
  const arp::RegionPrioritySystem& system = run.system();
  std::vector<const arp::MemoryImage*> shown;
  for (int m = 0; m < system.model().memory_count(); ++m) shown.push_back(system.memories().shown(m));
  const arp::MemoryRenderer renderer(system.model().scene(), options_.face_px, options_.background, options_.threads);
  std::vector<renderer::CubeMap> cubes = renderer.render(system.model(), shown);
  std::vector<const renderer::CubeMap*> all;
  for (const auto& c : cubes) all.push_back(&c);
  renderer::Frame frame = arp::view_through_cubes(all, camera_, head_, options_.background);
  if (cubes_out) *cubes_out = std::move(cubes);
  return frame;
}

void RegionFrames::write_memories(const std::string& stem, const RegionRun& run) {
  std::vector<renderer::CubeMap> cubes;
  const renderer::Frame all = composite(run, &cubes);
  for (size_t m = 0; m < cubes.size(); ++m) {
    const renderer::CubeMap* one[] = {&cubes[m]};
    const renderer::Frame f = arp::view_through_cubes(one, camera_, head_, options_.background);
    files_.write_png(stem + "_memory" + std::to_string(m) + ".png", f.colour);
  }
  files_.write_png(stem + "_composite.png", all.colour);
}

std::array<int, 2> RegionFrames::widest_tear(const RegionRun& run, const arp::ScreenProjection& screen) const {
  std::array<int, 2> best{screen.width_px() / 2, screen.height_px() / 2};
  double worst = -1.0;
  const arp::RegionPriorityModel& model = run.system().model();
  const arp::ShownRegions shown = run.system().shown();
  for (const arp::SharedVertex& s : model.scene().shared_vertices) {
    const int ma = shown.memory_of_segment[s.segment_a];
    const int mb = shown.memory_of_segment[s.segment_b];
    if (ma == mb || ma < 0 || mb < 0) continue;
    glm::dvec2 pa;
    glm::dvec2 pb;
    if (!screen.project(head_, model.drawn_direction(ma, s.position_m, *shown.views[static_cast<size_t>(ma)]), pa)) continue;
    if (!screen.project(head_, model.drawn_direction(mb, s.position_m, *shown.views[static_cast<size_t>(mb)]), pb)) continue;
    const double gap = glm::length(pa - pb);
    if (gap > worst) {
      worst = gap;
      best = {static_cast<int>(pa.x), static_cast<int>(pa.y)};
    }
  }
  return best;
}

void RegionFrames::write_tear_close_ups(const std::string& stem, const RegionRun& torn, const RegionRun& warped,
                                        const arp::ScreenProjection& screen) {
  const auto at = widest_tear(torn, screen);
  for (const RegionRun* run : {&torn, &warped}) {
    const renderer::Frame f = composite(*run, nullptr);
    const std::string tag = run->warping() ? "_warped" : "_torn";
    files_.write_png(stem + tag + ".png", f.colour);
    files_.write_png(stem + tag + "_closeup.png", arp::close_up(f.colour, at[0], at[1], 24, 8));
  }
}

}  // namespace latsim::pipelines
