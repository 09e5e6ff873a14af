// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Particle packings for compaction studies (`femdem pack`, scene section [[packings]]).
//
// A packing is a list of particles (centre, radius, orientation, shape name) placed without
// overlap in a container: a box [0, lx] x [0, ly] x [0, lz] or a cylinder (axis z, bottom face
// centred on the origin, open at the top while it is filled). Particles are either put on a
// lattice (simple, body-centred or face-centred cubic, touching each other and the walls) or
// dropped at random positions and settled under gravity by a small rigid-sphere DEM, so that
// the result is a dense, loose-random packing like a poured powder. Non-spherical particles
// (meshes from CAD) are settled by their bounding sphere and given a random orientation.
//
// The settling DEM (all in units of the largest diameter d and of g, so its parameters do not
// depend on the particle size): linear spring-dashpot normal contact (k_n = 2e4 m g / d for a
// particle of diameter d, restitution 0.2), a tangential spring (k_t = 2/7 k_n) capped by
// Coulomb friction, particle rotation, weak background drag, a cell list rebuilt every step,
// and semi-implicit Euler steps of 1/20 of the shortest contact duration. It runs serially in a
// fixed order, so a seed gives the same packing bits on the same platform. It stops when every
// particle is slower than 1e-3 sqrt(g d), then a few projection sweeps remove the remaining
// small spring overlaps (about 1e-3 d at the bottom of a deep bed), so that no two particles
// overlap by more than 1e-9 of their radii sum.
//
// File format (docs/OUTPUTS.md, "Packing files"): CSV with a commented header that holds the
// generator, the parameters (canonical TOML lines) and the result; the rows are
// `id,shape,x,y,z,radius,qw,qx,qy,qz`. The same parameters always write the same bytes.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "elements/tet10_mesh.hpp"

namespace femdem {

// What to generate. Strings keep the scene keys' spelling; check_packing_params() validates.
struct PackingParams {
  std::string container = "box";  // "box" | "cylinder"
  Vec3 size = Vec3::Zero();       // box: [lx, ly, lz] (m)
  double radius = 0.0;            // cylinder radius (m)
  double height = 0.0;            // cylinder height (m)
  // "random" (dropped and settled), "simple_cubic", "body_centred_cubic", "face_centred_cubic"
  std::string arrangement = "random";
  std::int64_t count = 0;  // random: required; lattice: 0 = as many as fit
  // "monodisperse" (diameter), "uniform" (diameter_min..diameter_max, uniform in diameter),
  // "lognormal" (ln d normal with standard deviation sigma, mean diameter diameter_mean before
  // clipping; clipped to [diameter_min, diameter_max] by redrawing)
  std::string distribution = "monodisperse";
  double diameter = 0.0;
  double diameter_min = 0.0, diameter_max = 0.0;  // lognormal: 0 = mean * exp(-+3 sigma)
  double diameter_mean = 0.0, sigma = 0.0;
  std::uint64_t seed = 1;
  std::string shape = "sphere";  // the name the scene's mesh is for; recorded per particle
  std::string orientation;       // "identity" | "random"; empty: identity for spheres
  double friction = 0.5;         // particle-particle and wall friction while settling
};

struct PackingParamError {
  std::string key;  // the parameter's name, as in the scene ("diameter_min")
  std::string message;
};

// The first problem with the parameters, if any (also checks that a particle fits).
std::optional<PackingParamError> check_packing_params(const PackingParams& p);

// Fills in what the parameters leave to defaults (orientation, lognormal clip bounds), so that
// two parameter sets that generate the same packing compare equal.
PackingParams resolve_packing_params(PackingParams p);

// The resolved parameters as TOML lines "key = value", only the keys that matter for them, in a
// fixed order, numbers in shortest round-trip form. Two parameter sets generate the same
// packing exactly when these texts are equal (the cache test of the scene reader).
std::string packing_params_text(const PackingParams& p);

struct PackedParticle {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // from the shape's frame
  std::string shape = "sphere";
};

struct PackingStats {
  double particle_volume = 0.0;     // sum of 4/3 pi r^3
  double bed_height = 0.0;          // highest particle top above the floor
  double packing_fraction = 0.0;    // particle volume / (container section * bed height)
  double container_fraction = 0.0;  // particle volume / container volume
  // Measured on a grid of points in the core of the bed, at least two largest diameters from
  // the walls, the floor and the bed's top: the bulk value, free of wall effects. NaN when the
  // bed is too small to have a core.
  double core_packing_fraction = 0.0;
  double min_gap = 0.0;  // smallest (distance - r_i - r_j) / (r_i + r_j); +inf for one particle
  // Settling (random only): simulated time in units sqrt(d / g), steps, largest particle speed
  // at the end in units sqrt(g d), and whether the rest criterion was met.
  double settle_time = 0.0;
  std::int64_t settle_steps = 0;
  double max_speed = 0.0;
  bool at_rest = true;
};

struct Packing {
  std::string generator;    // "femdem pack 0.1.0"; empty for a hand-written file
  std::string params_text;  // packing_params_text() of the parameters; empty if unknown
  std::vector<PackedParticle> particles;
  PackingStats stats;
};

// The first n diameters the parameters' size distribution draws (the generator's own stream).
std::vector<double> packing_diameters(const PackingParams& params, std::int64_t n);

// Generates the packing. Throws InputError (key = the parameter's name) for bad parameters or
// when the particles do not fit in the container.
Packing generate_packing(const PackingParams& params);

// Statistics of a list of particles in the container of `params` (settling fields untouched).
void measure_packing(const PackingParams& params, Packing& packing);

// The file's text, and atomic writing of it (throws std::runtime_error on I/O errors).
std::string packing_file_text(const Packing& packing);
void write_packing(const std::string& path, const Packing& packing);

// Reads a packing file. Only the column line and the rows are required (a hand-written file
// needs no header). Throws InputError naming the file, the line and the column (1-based).
Packing read_packing(const std::string& path);

// Distance from a mesh's node centroid to its farthest node: the radius of the bounding sphere
// that a shape is settled by (the packing's radius is this after scaling).
double bounding_radius(const Tet10Mesh& mesh, Vec3* centre = nullptr);

}  // namespace femdem
