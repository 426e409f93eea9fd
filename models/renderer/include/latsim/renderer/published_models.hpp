// Stand-ins for the three models of the Pixel-Planes 5 latency measurements
// (SPEC.md section 4), with exactly the published primitive counts.
#pragma once

#include "latsim/renderer/scene.hpp"

namespace latsim::renderer {

/// The published primitive counts of the fly-through model viewer's models.
inline constexpr int kMigTriangles = 417;
inline constexpr int kMoleculesTriangles = 2620;
inline constexpr int kMoleculesSpheres = 1219;
inline constexpr int kHeadTriangles = 59592;

/// A jet fighter of 417 triangles, `length_m` long along z (nose towards -z),
/// centred on the origin: a 12-sided lofted fuselage of 14 segments (336),
/// nose cone and exhaust cap (12 each), two wings (10 each), two tailplanes
/// (8 each), a fin (10) and a canopy (11). Throws for length_m <= 0.
Scene make_mig(double length_m);

/// A globular molecule of 1219 atoms (spheres of radius 0.025 to 0.035 x
/// size_m, strung 0.02 to 0.06 x size_m off the backbone) round a backbone
/// that coils through a ball of diameter size_m centred on the origin, traced
/// by a ribbon 0.024 x size_m wide of 1310 quads (2620 triangles). Deterministic.
Scene make_molecules(double size_m);

/// A head of 59,592 triangles, `height_m` from the neck to the crown, centred
/// on the origin and facing +z: the cylindrical grid of a range scan, 191
/// columns round and 156 rows up, two triangles per cell, open at the neck
/// and at a small hole on the crown.
Scene make_head(double height_m);

}  // namespace latsim::renderer
