// Whole runs of the Pixel-Planes 5 pipelines: view-dependent loads near
// capacity, a torn field in a capture, the shipped room walks, the host read,
// the typical models of the published table.
#include <catch2/catch.hpp>

#include <png.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "latsim/run/runner.hpp"
#include "latsim/scenario/config.hpp"

using namespace latsim;

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("latsim_pxpl5_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// 150 triangles: a 4 x 2 checkered backdrop 8 m ahead (16) and 134 small
/// triangles 5 m ahead within 12 degrees of straight on. Facing it, all 150
/// are on screen, two more than a Slats field can take; turned 40 degrees
/// away, a handful.
fs::path write_scene(const fs::path& dir) {
  const fs::path file = dir / "cluster.obj";
  std::ofstream out(file);
  int v = 0;
  const auto tri = [&](double x0, double y0, double x1, double y1, double x2, double y2, double z, double shade) {
    out << "v " << x0 << ' ' << y0 << ' ' << z << ' ' << shade << ' ' << 0.5 * shade << " 0.2\n";
    out << "v " << x1 << ' ' << y1 << ' ' << z << ' ' << shade << ' ' << 0.5 * shade << " 0.2\n";
    out << "v " << x2 << ' ' << y2 << ' ' << z << ' ' << shade << ' ' << 0.5 * shade << " 0.2\n";
    v += 3;
    out << "f " << v - 2 << ' ' << v - 1 << ' ' << v << '\n';
  };
  out << "o backdrop\n";
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 2; ++j) {
      const double x = -4.0 + 2.0 * i, y = -1.0 + 2.6 * j, shade = (i + j) % 2 == 0 ? 0.9 : 0.4;
      tri(x, y, x + 2, y, x + 2, y + 2.6, -8, shade);
      tri(x, y, x + 2, y + 2.6, x, y + 2.6, -8, shade);
    }
  out << "o cluster\n";
  for (int k = 0; k < 134; ++k) {
    const double x = -1.0 + 0.15 * (k % 14), y = 0.6 + 0.2 * (k / 14);
    tri(x, y, x + 0.12, y, x, y + 0.15, -5, 0.3 + 0.005 * k);
  }
  return file;
}

Json slats_near_capacity(const fs::path& scene) {
  Json s = Json::parse(R"({
    "include": ")" LATSIM_SOURCE_DIR R"(/scenarios/pxpl5/slats_140.json",
    "duration_s": 2,
    "motion": {"type": "sinusoid", "position_m": [0, 1.6, 0], "yaw_amplitude_deg": 40, "yaw_frequency_hz": 0.5},
    "pipeline": {"workload": "view"}
  })");
  s["scene"] = {{"type", "obj"}, {"file", scene.string()}};
  return s;
}

/// Runs a scenario written next to its results (so that it may include shipped files).
Json run_into(const Json& scenario, const fs::path& dir, const std::string& name) {
  const fs::path file = dir / (name + ".json");
  std::ofstream(file) << scenario.dump(2);
  run::RunOptions options;
  options.out_dir = dir / name;
  return run::run_scenario(run::load_scenario(file, {}), options);
}

Json run_file(const std::string& file, const std::vector<std::string>& sets) {
  return run::run_scenario(run::load_scenario(LATSIM_SOURCE_DIR "/scenarios/" + file, sets),
                                 run::RunOptions{});
}

const Json& fig(const Json& summary, const char* name) { return summary.at("figures").at(name); }

/// An RGB image read with libpng's simplified interface.
struct Rgb {
  int width = 0, height = 0;
  std::vector<unsigned char> pixels;
  const unsigned char* at(int x, int row) const { return &pixels[(static_cast<std::size_t>(row) * width + x) * 3]; }
};

Rgb read_png(const fs::path& file) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_file(&image, file.c_str()) != 0);
  image.format = PNG_FORMAT_RGB;
  Rgb out;
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  out.pixels.resize(PNG_IMAGE_SIZE(image));
  REQUIRE(png_image_finish_read(&image, nullptr, out.pixels.data(), 0, nullptr) != 0);
  return out;
}

/// COPY intervals per field on one frame-buffer port, from timeline.csv.
std::map<int64_t, int> copies_per_field(const fs::path& timeline, const std::string& unit) {
  std::ifstream in(timeline);
  std::string line;
  std::getline(in, line);  // header: stage,frame,eye,unit,start_ms,end_ms
  std::map<int64_t, int> count;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string stage, frame, eye, u;
    std::getline(row, stage, ',');
    std::getline(row, frame, ',');
    std::getline(row, eye, ',');
    std::getline(row, u, ',');
    if (stage == "COPY" && u == unit) ++count[std::stoll(frame)];
  }
  return count;
}

}  // namespace

TEST_CASE("Slats at 150 triangles of a view-dependent scene misses some fields but not all", "[pxpl5][slats][view]") {
  const fs::path dir = fresh_dir("near");
  const Json r = run_into(slats_near_capacity(write_scene(dir)), dir, "run");
  CHECK(fig(r, "display_list_triangles") == 150);
  CHECK(fig(r, "triangles_on_screen")["max"].get<double>() == 150.0);
  CHECK(fig(r, "triangles_on_screen")["min"].get<double>() < 50.0);
  const int64_t missed = fig(r, "missed_fields"), complete = fig(r, "frames_completed");
  CAPTURE(missed, complete);
  CHECK(missed > 0);
  CHECK(complete > 0);
  CHECK(fig(r, "motion_to_photon_ms")["count"].get<int64_t>() > 0);
  CHECK(fig(r, "transform_to_retrace_fields")["max"].get<double>() == Approx(1.0).epsilon(1e-9));
  fs::remove_all(dir);
}

// The first field whose top regions come too late for the right eye (the
// later of the two ports; at 150 triangles only its last top slots are late),
// after a field of the same parity that was complete, is captured with that
// field: its late regions' rows of its parity show exactly the earlier
// field's pixels.
TEST_CASE("a torn Slats field shows the old region's pixels in a capture", "[pxpl5][slats][frames]") {
  const fs::path dir = fresh_dir("torn");
  Json s = slats_near_capacity(write_scene(dir));
  run_into(s, dir, "scan");
  const std::map<int64_t, int> copies = copies_per_field(dir / "scan" / "timeline.csv", "FB1");
  // A late top region is never copied (ten per eye when complete; lower ones always are).
  int64_t torn = -1;
  for (const auto& [field, n] : copies)
    if (field >= 10 && n < 10 && copies.count(field + 1) && copies.count(field - 2) && copies.at(field - 2) == 10) {
      torn = field;
      break;
    }
  REQUIRE(torn > 0);
  const int tops_copied = copies.at(torn) - 5;
  s["frames"] = {{"at_s", {(static_cast<double>(torn - 2) - 0.1) / 60.0, (static_cast<double>(torn) - 0.1) / 60.0}},
                 {"eye", 1},
                 {"threads", 1}};
  run_into(s, dir, "capture");
  const Rgb before = read_png(dir / "capture" / "frames" / "0000_displayed.png");
  const Rgb after = read_png(dir / "capture" / "frames" / "0001_displayed.png");
  const int parity = static_cast<int>(torn % 2);
  int64_t same = 0, changed = 0;
  for (int line = 0; line < 240; ++line) {
    const int row = 2 * line + parity;
    for (int x = 0; x < 640; ++x) {
      const bool late_region = line < 128 && x / 128 >= tops_copied;
      const bool equal = std::equal(before.at(x, row), before.at(x, row) + 3, after.at(x, row));
      if (late_region) {
        CHECK(equal);
        ++same;
      } else if (!equal) {
        ++changed;
      }
    }
  }
  CAPTURE(torn, tops_copied, same, changed);
  CHECK(same >= 128 * 128);
  CHECK(changed > 1000);  // elsewhere the head turned between the two fields
  fs::remove_all(dir);
}

TEST_CASE("the room walks report latency distributions and varying stages", "[pxpl5][scenario]") {
  const Json rc = run_file("pxpl5/rc_room_walk.json", {"/duration_s=4"});
  CHECK(fig(rc, "render_latency_fields")["stddev"].get<double>() > 0.3);
  CHECK(fig(rc, "stage_ms")["TRANSFORM"]["stddev"].get<double>() > 1.0);
  CHECK(fig(rc, "triangles_on_screen")["stddev"].get<double>() > 100.0);
  const Json slats = run_file("pxpl5/slats_room_walk.json", {"/duration_s=4"});
  CHECK(fig(slats, "missed_field_fraction").get<double>() > 0.0);
  CHECK(fig(slats, "missed_field_fraction").get<double>() < 0.5);
  CHECK(fig(slats, "motion_to_photon_ms")["stddev"].get<double>() > 0.0);
  CHECK(fig(slats, "stage_ms")["TRANSFORM"]["stddev"].get<double>() > 1.0);
}

TEST_CASE("reading the tracker late saves what late_read_saving_ms says", "[pxpl5][rc][host]") {
  const Json early = run_file("pxpl5/rc_room_walk.json", {"/duration_s=3"});
  const Json late = run_file("pxpl5/rc_room_walk.json", {"/duration_s=3", "/pipeline/host/read=\"late\""});
  const double saving = fig(early, "late_read_saving_ms")["mean"].get<double>();
  CHECK(saving > 16.0);
  CHECK(fig(late, "late_read_saving_ms")["max"].get<double>() == 0.0);
  // The same stages (loads differ a little with the newer poses), newer samples.
  const double tracker_early = fig(early, "tracker_to_render_ms")["mean"].get<double>();
  const double tracker_late = fig(late, "tracker_to_render_ms")["mean"].get<double>();
  CHECK(tracker_early - tracker_late == Approx(saving).epsilon(0.15));
  CHECK(fig(late, "motion_to_photon_ms")["mean"].get<double>() <
        fig(early, "motion_to_photon_ms")["mean"].get<double>() - 0.8 * saving);
}

// NTSC's true rate is 59.94 Hz: a field of 1000 / 59.94 = 16.6834 ms. Over a
// simulated minute (3597 fields) nothing drifts: Slats shows every field one
// field after its TRANSFORM, and its slack is the hand budget of
// docs/pxpl5.md with the longer field: 16.6834 - 0.3 (overhead) - 140 x 0.075
// (GP) - (0.0336 last message to R0 + 14 x 4 x 0.0046 render + 4 x 0.05
// finish) - 6 x 0.78 (top copy slots) = 0.7122 ms. RC stays COPY-bound: a
// stereo frame every second field.
TEST_CASE("Slats and RC at 59.94 Hz for a simulated minute", "[pxpl5][ntsc]") {
  const double field_ms = 1000.0 / 59.94;
  const std::vector<std::string> ntsc{"/display/refresh_hz=59.94", "/tracker/rate_hz=59.94", "/duration_s=60",
                                      "/output/timeline=false"};
  const Json slats = run_file("pxpl5/slats_140.json", ntsc);
  CHECK(fig(slats, "missed_fields") == 0);
  CHECK(fig(slats, "frames_completed").get<int64_t>() >= 3595);
  CHECK(fig(slats, "transform_to_retrace_fields")["min"].get<double>() == Approx(1.0).epsilon(1e-9));
  CHECK(fig(slats, "transform_to_retrace_fields")["max"].get<double>() == Approx(1.0).epsilon(1e-9));
  const double hand_slack_ms = field_ms - 0.3 - 140 * 0.075 - (14 * 48 / 20.0e3 + 14 * 4 * 0.0046 + 4 * 0.05) - 6 * 0.78;
  CHECK(fig(slats, "deadline_slack_ms")["min"].get<double>() == Approx(hand_slack_ms).margin(1e-4));
  CHECK(fig(slats, "deadline_slack_ms")["max"].get<double>() == Approx(hand_slack_ms).margin(1e-4));
  const Json rc = run_file("pxpl5/rc_min_latency.json", ntsc);
  CHECK(fig(rc, "frame_time_ms")["min"].get<double>() == Approx(2 * field_ms).margin(1e-4));
  CHECK(fig(rc, "frame_time_ms")["max"].get<double>() == Approx(2 * field_ms).margin(1e-4));
  CHECK(fig(rc, "frames_completed").get<int64_t>() >= 1797);
}

// The fly-through model viewer of SPEC.md section 4 on its three models,
// TRANSFORM start to the swap of the frame's first (left) eye against the
// published table. The two small models stay COPY-bound on the whole path
// (both eyes' TRANSFORMs and RENDERs fit in the two fields COPY takes), so
// both eyes give the minimum case's values by hand (tests/models/pxpl5/test_rc_per_eye.cpp):
// left 4 + (33.333 - 31.2 - 0.2) / 16.667 = 4.116 fields, right
// 4 - 15.6 / 16.667 = 3.064, the same every frame. Against the published
// means (Mig 4.61, Molecules 4.47) that is 11 % and 8 % low; against the
// published spreads (0.589, 0.502) nothing: a COPY-bound eye does not vary
// (docs/validation.md).
TEST_CASE("the Mig and Molecules of the fly-through are COPY-bound: the minimum case's latency", "[pxpl5][scenario][models]") {
  const double field_ms = 1000.0 / 60.0;
  const double left_hand = 4 + (2 * field_ms - 31.2 - 0.2) / field_ms, right_hand = 4 - 15.6 / field_ms;
  for (const auto& [file, published_mean, triangles, spheres] :
       {std::tuple{"pxpl5/rc_mig.json", 4.61, 417, 0}, std::tuple{"pxpl5/rc_molecules.json", 4.47, 2620, 1219}}) {
    CAPTURE(file);
    const Json r = run_file(file, {"/duration_s=20", "/output/timeline=false"});
    CHECK(fig(r, "display_list_triangles").get<int>() == triangles);
    if (spheres > 0) CHECK(fig(r, "display_list_spheres").get<int>() == spheres);
    CHECK(fig(r, "frame_time_ms")["max"].get<double>() == Approx(2 * field_ms).margin(1e-6));
    const Json& left = fig(r, "transform_to_swap_fields")["left"];
    const Json& right = fig(r, "transform_to_swap_fields")["right"];
    CHECK(left["mean"].get<double>() == Approx(left_hand).margin(0.01));
    CHECK(right["mean"].get<double>() == Approx(right_hand).margin(0.01));
    CHECK(left["stddev"].get<double>() < 0.1);
    CHECK(std::abs(left["mean"].get<double>() / published_mean - 1.0) < 0.2);
  }
}

// The head: 59,592 triangles, back faces culled. Its TRANSFORM follows what
// the path brings into view (from nothing to about 26,000 front faces); the
// published figures: 8.13 fields mean, 2.48 sd, far above the small models.
TEST_CASE("the head of the fly-through follows the view, far above the small models", "[pxpl5][scenario][models]") {
  const Json r = run_file("pxpl5/rc_head.json", {"/output/timeline=false"});
  CHECK(fig(r, "display_list_triangles").get<int>() == 59592);
  const Json& left = fig(r, "transform_to_swap_fields")["left"];
  const double mean = left["mean"].get<double>(), sd = left["stddev"].get<double>();
  CAPTURE(mean, sd);
  CHECK(std::abs(mean / 8.13 - 1.0) < 0.2);
  CHECK(sd > 2.48 / 2);
  CHECK(sd < 2.48 * 2);
  CHECK(mean > 4.116 + 2.0);
  // Never more than half the head faces the eye.
  CHECK(fig(r, "triangles_on_screen")["max"].get<double>() < 59592 / 2.0);
  CHECK(fig(r, "triangles_on_screen")["min"].get<double>() == 0.0);
}

// A viewer that blocks until the tracker has a newer sample, the tracker at
// 20 Hz on a direct link: sample k reaches the host 50 ms after sample k - 1,
// three fields, so once the first frame is out every frame waits for its
// sample and the minimum case swaps every three fields instead of every two.
TEST_CASE("a run whose host waits for the tracker is paced by it", "[pxpl5][scenario][host]") {
  const double field_ms = 1000.0 / 60.0;
  const std::vector<std::string> slow{"/tracker/rate_hz=20", "/duration_s=4", "/output/timeline=false"};
  std::vector<std::string> waiting = slow;
  waiting.push_back("/pipeline/host/wait_for_new_sample=true");
  const Json paced = run_file("pxpl5/rc_min_latency.json", waiting);
  CHECK(fig(paced, "frame_time_ms")["min"].get<double>() == Approx(3 * field_ms).margin(1e-6));
  CHECK(fig(paced, "frame_time_ms")["max"].get<double>() == Approx(3 * field_ms).margin(1e-6));
  const Json free_running = run_file("pxpl5/rc_min_latency.json", slow);
  CHECK(fig(free_running, "frame_time_ms")["max"].get<double>() == Approx(2 * field_ms).margin(1e-6));
}
