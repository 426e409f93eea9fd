#include "latsim/sections/shared.hpp"

#include <cmath>
#include <memory>

#include "latsim/renderer/obj_loader.hpp"

namespace latsim::sections {

using scenario::KeySpec;
using scenario::Section;

namespace {

// About twice as many triangles: far beyond any scene latsim draws, and still within memory.
constexpr double kMaxGalleryTiles = 2e6;

void gallery(Section& s, renderer::GalleryParams& g) {
  s.number("size_x_m", g.size_x_m, {.unit = "m", .min = 0.0, .above_min = true, .doc = "extent along x"});
  s.number("size_z_m", g.size_z_m, {.unit = "m", .min = 0.0, .above_min = true, .doc = "extent along z"});
  s.number("height_m", g.height_m, {.unit = "m", .min = 0.0, .above_min = true, .doc = "floor to ceiling"});
  s.integer("partition_count", g.partition_count, {.min = 0.0, .max = 64.0, .doc = "free-standing partitions"});
  s.integer("frames_per_wall", g.frames_per_wall, {.min = 0.0, .max = 64.0, .doc = "pictures on each wall and partition side"});
  s.number("tile_m", g.tile_m,
           {.unit = "m", .min = 0.0, .above_min = true,
            .doc = "tessellation step (a divisor of the region size keeps segments aligned with regions)"});
  // The scene is built in memory and cast by Embree: floor, ceiling and walls in tiles of tile_m.
  const double surface_m2 = 2.0 * (g.size_x_m * g.size_z_m + (g.size_x_m + g.size_z_m) * g.height_m);
  s.check("tile_m", surface_m2 / (g.tile_m * g.tile_m) <= kMaxGalleryTiles,
          "the gallery's floor, ceiling and walls would need more than 2e6 tiles of tile_m: make it smaller or the "
          "tiles larger");
}

void model_size(Section& s, renderer::SceneSpec& g, double default_m, const char* doc) {
  g.model_size_m = default_m;
  s.number("size_m", g.model_size_m, {.unit = "m", .min = 0.0, .max = 1e6, .above_min = true, .doc = doc});
}

void persistence(Section& s, display::PersistenceParams& p, const display::RasterParams& raster) {
  using Mode = display::PersistenceParams::Mode;
  const auto flash = [&p](Section& m) {
    m.duration("lit_ms", p.lit, {.unit = "ms", .min = 0.0, .above_min = true, .required = true, .doc = "how long each flash lasts"});
  };
  s.modes("type", "",
          {{"full", "sample and hold: a row stays lit until it is written again", [&p](Section&) { p.mode = Mode::full; }},
           {"rolling", "each row flashes for `lit_ms` once it has been written and has settled",
            [&p, flash](Section& m) {
              p.mode = Mode::rolling;
              flash(m);
            }},
           {"global", "the whole panel flashes for `lit_ms` once every row has been written and has settled",
            [&p, flash](Section& m) {
              p.mode = Mode::global;
              flash(m);
            }}},
          {.doc = "the illumination"});
  s.duration("response_ms", p.response, {.unit = "ms", .doc = "pixel response: the whole transition from the old value to the new"});
  using Rise = display::PersistenceParams::Rise;
  s.choice("rise", p.rise, {{"step", Rise::step}, {"linear", Rise::linear}, {"exponential", Rise::exponential}},
           {.doc = "how a camera sees the transition (latency figures do not depend on it): step: the new value "
                   "whenever lit; linear: over response_ms (OLED); exponential: 10 % to 90 % in response_ms (an "
                   "LCD's grey to grey), so that a camera's threshold on the light is crossed later"});
  // A row is written once per frame (two fields when interlaced).
  const double frame_ms = raster.field_period.to_seconds() * 1e3 * (raster.interlaced ? 2 : 1);
  s.check("lit_ms", p.mode == Mode::full || p.lit.to_ms() <= frame_ms + 1e-9,
          "a flash cannot last longer than the frame period (each row is written once a frame)");
}

void clock_noise(Section& s, display::ClockNoiseParams& p) {
  s.doc("The display oscillator's short-term instability (docs/display-clock.md): white jitter on every retrace and a "
        "rate that wanders as a random walk, drawn from the run's stream `display.clock_noise`.");
  double jitter_ns = static_cast<double>(p.jitter_rms.ticks()) / 1e3;
  s.number("jitter_ns_rms", jitter_ns,
           {.unit = "ns", .min = 0.0, .max = 1e6,
            .doc = "standard deviation of each retrace about the clock's time (cut at 4 standard deviations)"});
  p.jitter_rms = des::Time::ps(std::llround(jitter_ns * 1e3));
  s.number("wander_ppm_per_sqrt_s", p.wander_ppm_per_sqrt_s,
           {.unit = "ppm/√s", .min = 0.0, .max = 1e3,
            .doc = "random walk of the rate: after t seconds its deviation has standard deviation this × √t ppm"});
}

}  // namespace

void bind(Section& s, display::DisplayParams& p) {
  s.doc("One display per eye, synchronised; for interlaced displays `refresh_hz` is the field rate.");
  display::RasterParams& r = p.raster;
  s.rate("refresh_hz", r.field_period,
         {.unit = "Hz", .max = 1e4, .doc = "field rate (exact rational; \"60000/1001\" for NTSC's 59.94 Hz)"});
  s.flag("interlaced", r.interlaced, {.doc = "odd/even fields; a frame is two fields"});
  s.integer("width_px", r.width_px, {.unit = "px", .min = 1.0, .max = 16384.0, .doc = "active pixels per line"});
  s.integer("height_px", r.height_px, {.unit = "px", .min = 2.0, .max = 16384.0, .doc = "active lines (both fields together)"});
  s.check("height_px", !(r.interlaced && r.height_px % 2 != 0), "an interlaced display needs an even number of lines");
  s.integer("vblank_lines", r.vblank_lines, {.min = 0.0, .max = 100000.0, .doc = "blank line periods at the start of each field"});
  s.integer("hblank_px", r.hblank_px, {.unit = "px", .min = 0.0, .max = 100000.0, .doc = "blank pixel times per line"});
  s.integer("first_field_parity", r.first_field_parity, {.min = 0.0, .max = 1.0, .doc = "rows of field 0 (0: rows 0, 2, 4 …)"});
  s.number("hfov_deg", p.hfov_deg,
           {.unit = "deg", .min = 1.0, .max = 179.0, .doc = "horizontal field of view (probes, pixels of error, frames)"});
  s.choice("scanout", p.fidelity,
           {{"field", display::ScanoutFidelity::Field},
            {"line", display::ScanoutFidelity::Line},
            {"pixel", display::ScanoutFidelity::Pixel}},
           {.doc = "fidelity: latency sampled per field, per line (sees mid-field swaps) or per pixel (one event per "
                   "line, split where the image changes mid-line)"});
  clock(s, "", p.clock, "display (its first retrace)");
  s.optional_object("clock_noise", p.clock_noise, [](Section& o, display::ClockNoiseParams& v) { clock_noise(o, v); },
                    {.doc = "jitter and wander of the display clock (absent: a steady clock)"});
  s.integer("pixel_stride", p.pixel_stride,
            {.unit = "px", .min = 1.0, .max = 16384.0, .doc = "pixel fidelity: pixels per latency sample"});
  s.flag("pixel_events", p.pixel_events,
         {.doc = "pixel fidelity: one event per sample (the reference path) instead of one per line, split where "
                 "the image changes; the figures are the same"});
  s.optional_object("persistence", p.persistence, [&r](Section& o, display::PersistenceParams& v) { persistence(o, v, r); },
                    {.doc = "how long a written pixel stays lit (absent: lit at its scanout instant, as a CRT); "
                            "motion-to-photon latency is taken at the middle of the lit interval"});
}

void bind(Section& s, SceneParams& p) {
  s.doc(
      "`triangles` and `coverage` drive the generic render cost; Pixel-Planes 5 reads `triangles` and "
      "`regions_per_triangle`; frame capture and the address recalculation pipelines draw the geometry.");
  s.integer("triangles", p.triangles,
            {.min = 0.0, .max = 1099511627776.0, .doc = "triangles a frame draws (per eye)"});
  s.number("coverage", p.coverage, {.min = 0.0, .max = 1.0, .doc = "fraction of the screen the triangles cover"});
  s.number("regions_per_triangle", p.regions_per_triangle,
           {.min = 1.0, .max = 1024.0, .doc = "128 x 128 regions a triangle touches (typical 1.3; 20: the whole 640x480 screen)"});
  using Type = renderer::SceneSpec::Type;
  renderer::SceneSpec& g = p.geometry;
  s.modes("type", "gallery",
          {{"gallery", "a procedural art gallery with partitions and pictures",
            [&g](Section& m) {
              g.type = Type::Gallery;
              gallery(m, g.gallery);
            }},
           {"room", "a 6 x 2.7 x 8 m room with tiled walls and a dozen furniture boxes", [&g](Section&) { g.type = Type::Room; }},
           {"test_pattern", "coloured boxes at 2 to 9 m before a checkered backdrop, seen best from the origin looking down −z", [&g](Section&) { g.type = Type::TestPattern; }},
           {"mig", "the Mig of the Pixel-Planes 5 measurements: a jet of 417 triangles, nose towards −z, centred on the origin (docs/pxpl5.md)",
            [&g](Section& m) {
              g.type = Type::Mig;
              model_size(m, g, 1.0, "length, nose to tail");
            }},
           {"molecules", "the Molecules of the Pixel-Planes 5 measurements: 1,219 atoms (spheres) and a ribbon of 2,620 triangles in a ball centred on the origin (docs/pxpl5.md)",
            [&g](Section& m) {
              g.type = Type::Molecules;
              model_size(m, g, 1.0, "diameter of the ball the molecule fills");
            }},
           {"head", "the head of the Pixel-Planes 5 measurements: a range-scan grid of 59,592 triangles, facing +z, centred on the origin (docs/pxpl5.md)",
            [&g](Section& m) {
              g.type = Type::Head;
              model_size(m, g, 1.0, "height, neck to crown");
            }},
           {"obj", "a Wavefront OBJ mesh",
            [&g](Section& m) {
              g.type = Type::Obj;
              m.path("file", g.file, {.required = true, .doc = "the mesh, relative to the file that names it"});
              // Read and checked with the scenario: a bad mesh is this key's error, in validate as in run.
              m.guard("file", [&g] { g.mesh = std::make_shared<const renderer::Scene>(renderer::load_obj(g.file)); });
            }}},
          {.doc = "the geometry"});
}

}  // namespace latsim::sections
