// SPDX-License-Identifier: GPL-3.0-or-later
// armour_units: writes closed triangle surfaces (binary STL, OBJ or OFF) of concrete armour units
// from their published proportions, for the CAD-import path of femdem scenes.
//
//   armour_units tetrapod -o tetrapod.stl [--size H | --mass KG] [--scale F] [shape options]
//
// Shapes and the proportions used (see scenes/meshes/README.md and docs/SCENES.md):
//  - tetrapod (Danel, Sogreah, 1950s). Size = unit height H, resting on three legs. Proportions
//    from the tetrapod specification drawing of the Shore Protection Manual (CERC 1984, vol. II,
//    ch. 7) and Hudson (1974, WES MP H-74-2): leg tip diameter A = 0.302 H, leg length from the
//    centre to the tip face F = 0.644 H, the leg diameter D = 0.470 H at C = 0.477 H from the tip,
//    the truncated cone continued to the centre; volume 0.280 H^3 (how this reading of the drawing
//    was checked: scenes/meshes/README.md). We take A, D and C as given and derive F from H so
//    that the height is exactly H: F = 3/4 (H - A sqrt(2)/3) = 0.643 H.
//  - dolos (Merrifield, East London, 1963). Size = overall length C (the unit fits a C x C x C
//    box). A straight shank of regular octagonal section, across-flats r C (waist ratio r,
//    0.32-0.34 as published), with a fluke of length C at each end, at right angles to the shank
//    and to each other. The flukes are octagonal too, of width r C where they meet the shank,
//    tapering linearly from the shank's faces to a tip width t C. t is not fixed by r alone; the
//    default t = 0.18 is chosen so that r = 0.32 gives the published volume of about 0.16 C^3
//    (SPM 1984).
//  - cube (plain concrete cube). Size = edge length.
//  - vcross (the idealised cruciform "V-Cross" of Xiang et al. 2009 and the thesis, section 6.3.1).
//    Two square-section bars (arm width a = 1.26 m) crossing at mid-length in one plane, one bar
//    vertical (the "main body", the impact leg at the bottom), one horizontal. Size = span S (the
//    length of each bar). The notes give only a and the mass (~30 t at 2340 kg/m3, so 12.82 m3);
//    V = 2 a^2 S - a^3 then gives S = (V + a^3) / (2 a^2) = 4.67 m.
//
// The tetrapod and the dolos are unions of convex pieces (frustums with N facets, octagonal
// prisms). Each piece is built as an exact convex hull and the pieces are united with CGAL's
// corefinement in the exact-constructions kernel, so the union itself is exact; edges shorter
// than --min-edge are then collapsed. The cube and the V-Cross are written directly. The result
// is rounded to the single-precision coordinates that STL stores, put in a canonical order and
// checked in that rounded form: closed, every edge shared by exactly two faces in opposite
// directions, manifold vertices, one component, no degenerate face, no self-intersection,
// positive volume. A surface that fails is not written (exit 1).
//
// Placement: z is up; the unit rests with its lowest point on z = 0 and its vertical axis on
// x = y = 0 (tetrapod: one leg up, three down, one lower leg towards +x; dolos: shank along x,
// fluke at x < 0 along y, fluke at x > 0 along z; vcross: main body along z, cross bar along x).
//
// Exit codes: 0 written, 2 bad option, 1 geometry check or write failed.

#include <CLI/CLI.hpp>

#include "tools/armour_units/unit_shapes.hpp"
#include "tools/armour_units/unit_surface.hpp"

namespace {

using namespace armour_units;

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

struct Defaults {
  double size;  // m
  const char* size_meaning;
};

const std::map<std::string, Defaults> kShapes{
    {"tetrapod", {2.0, "unit height H"}},
    {"dolos", {2.5, "overall length C"}},
    {"cube", {1.4, "edge length"}},
    {"vcross", {4.67, "span S of each bar"}},
};

}  // namespace

int main(int argc, char** argv) {
  // CGAL's default random generator is seeded from the clock and the hull construction draws
  // from it; a fixed seed makes the output the same file on every run (the shipped meshes are
  // compared against fresh output in the tests).
  CGAL::get_default_random() = CGAL::Random(0);
  CLI::App app{
      "Write a closed triangle surface of a concrete armour unit (tetrapod, dolos, cube, vcross)\n"
      "from its published proportions. Lengths in metres; z up, resting on z = 0."};
  std::string shape, output;
  double size = 0, mass = 0, density = 2340, scale = 1, arm = 1.26, min_edge = 0.005;
  TetrapodParams tp;
  DolosParams dp;
  std::map<std::string, std::vector<CLI::Option*>> shape_options;  // options of one shape only
  app.add_option("shape", shape, "tetrapod | dolos | cube | vcross")->required();
  app.add_option("-o,--output", output, "output file: .stl (binary), .obj or .off")->required();
  auto* size_opt = app.add_option(
      "--size", size,
      "characteristic size in m: tetrapod height H (default 2.0), dolos length C (2.5), cube edge "
      "(1.4), vcross span S (4.67)");
  auto* mass_opt = app.add_option("--mass", mass, "size the unit to this mass in kg instead");
  mass_opt->excludes(size_opt);
  app.add_option("--density", density, "density in kg/m3 for --mass and the report")
      ->capture_default_str();
  app.add_option("--scale", scale, "multiply every length by this (e.g. a model scale)")
      ->capture_default_str();
  shape_options["tetrapod"].push_back(
      app.add_option("--tip-diameter", tp.tip_diameter, "tetrapod leg tip diameter A / H")
          ->capture_default_str());
  shape_options["tetrapod"].push_back(
      app.add_option("--mid-diameter", tp.mid_diameter,
                     "tetrapod leg diameter D / H at --mid-from-tip")
          ->capture_default_str());
  shape_options["tetrapod"].push_back(
      app.add_option("--mid-from-tip", tp.mid_from_tip, "tetrapod distance C / H of D from the tip")
          ->capture_default_str());
  shape_options["tetrapod"].push_back(
      app.add_option(
             "--leg-phases", tp.phases,
             "tetrapod: turn of each leg's facets (top, then the three lower legs), in facets")
          ->expected(4)
          ->capture_default_str());
  shape_options["tetrapod"].push_back(
      app.add_option("--facets", tp.facets, "tetrapod: sides of each leg's cone")
          ->capture_default_str());
  shape_options["dolos"].push_back(
      app.add_option("--waist", dp.waist, "dolos waist ratio r (shank width / C)")
          ->capture_default_str());
  shape_options["dolos"].push_back(
      app.add_option("--fluke-tip", dp.fluke_tip, "dolos fluke tip width / C")
          ->capture_default_str());
  app.add_option("--min-edge", min_edge,
                 "collapse edges shorter than this fraction of the size (0: keep the exact union)")
      ->capture_default_str();
  shape_options["vcross"].push_back(
      app.add_option("--arm", arm, "vcross arm width a in m at the default span (scales with size)")
          ->capture_default_str());
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "error: " << e.what() << "\nRun with --help for the options.\n";
    return kExitBadInput;
  }

  try {
    const auto it = kShapes.find(shape);
    if (it == kShapes.end())
      throw BadOption("unknown shape '" + shape + "' (tetrapod, dolos, cube, vcross)");
    for (const auto& [owner, options] : shape_options)
      for (const CLI::Option* o : options)
        if (owner != shape && !o->empty())
          throw BadOption(o->get_name() + " applies to " + owner + " only, not to " + shape);
    auto positive = [](double v, const char* what) {
      if (!(std::isfinite(v) && v > 0)) throw BadOption(std::string(what) + " must be > 0");
    };
    positive(density, "--density");
    positive(scale, "--scale");
    if (!size_opt->empty()) positive(size, "--size");
    if (!mass_opt->empty()) positive(mass, "--mass");
    const std::string ext = std::filesystem::path(output).extension().string();
    if (ext != ".stl" && ext != ".obj" && ext != ".off")
      throw BadOption("output '" + output + "' must end in .stl, .obj or .off");

    ExactMesh mesh;
    std::string params;
    const double default_size = it->second.size;
    if (shape == "tetrapod") {
      if (!(tp.tip_diameter > 0 && tp.tip_diameter < tp.mid_diameter && tp.mid_diameter < 1 &&
            tp.mid_from_tip > 0 && tp.mid_from_tip < 1))
        throw BadOption(
            "tetrapod needs 0 < --tip-diameter < --mid-diameter < 1, 0 < --mid-from-tip < 1");
      if (tp.facets < 8 || tp.facets > 256 || tp.facets % 2 != 0)
        throw BadOption("--facets must be an even number from 8 to 256");
      if (tetrapod_leg_length(tp) <= tp.mid_from_tip)
        throw BadOption("tetrapod --mid-from-tip must be shorter than the leg");
      mesh = tetrapod(tp);
      params = "A/H=" + std::to_string(tp.tip_diameter) +
               " D/H=" + std::to_string(tp.mid_diameter) +
               " C/H=" + std::to_string(tp.mid_from_tip) + " N=" + std::to_string(tp.facets);
    } else if (shape == "dolos") {
      if (!(dp.waist >= 0.2 && dp.waist <= 0.5))
        throw BadOption("--waist must be in [0.2, 0.5] (published dolosse: 0.32 to 0.42)");
      if (!(dp.fluke_tip > 0 && dp.fluke_tip <= dp.waist))
        throw BadOption("--fluke-tip must be in (0, --waist]");
      mesh = dolos(dp);
      params = "r=" + std::to_string(dp.waist) + " t=" + std::to_string(dp.fluke_tip);
    } else if (shape == "cube") {
      mesh = cube();
    } else {
      positive(arm, "--arm");
      if (!(arm < 0.5 * default_size))
        throw BadOption("--arm must be less than half the default span (4.67 m)");
      mesh = vcross(arm / default_size);
      params = "a/S=" + std::to_string(arm / default_size);
    }

    if (!(min_edge >= 0 && min_edge <= 0.05)) throw BadOption("--min-edge must be in [0, 0.05]");
    const InexactMesh clean = to_inexact_without_short_edges(mesh, min_edge);

    // Size: given, or from the mass through the unit-size volume (the shape is exact up to
    // scaling, so the volume scales with the cube of the size).
    double length = size_opt->empty() ? default_size : size;
    if (!mass_opt->empty()) {
      const double unit_volume = signed_volume(round_to_float(clean, 1.0));
      length = std::cbrt(mass / density / unit_volume);
    }
    length *= scale;
    Surface surface = round_to_float(clean, length);
    canonicalize(surface);
    check_solid(surface);

    const std::string title = shape + " size=" + std::to_string(length) + "m " + params;
    if (ext == ".stl")
      write_stl(surface, output, title);
    else
      write_obj_or_off(surface, output, ext == ".off", title);

    std::array<float, 3> lo = surface.points.front(), hi = lo;
    for (const auto& p : surface.points)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    const double volume = signed_volume(surface);
    std::printf("shape      %s (%s %.6g m) %s\n", shape.c_str(), it->second.size_meaning, length,
                params.c_str());
    std::printf("file       %s\n", output.c_str());
    std::printf("triangles  %zu\nvertices   %zu\n", surface.triangles.size(),
                surface.points.size());
    std::printf("volume     %.6g m3 (%.6g size^3)\n", volume, volume / std::pow(length, 3));
    std::printf("mass       %.6g kg at %g kg/m3\n", volume * density, density);
    double min_edge = HUGE_VAL;
    for (const auto& t : surface.triangles)
      for (int k = 0; k < 3; ++k) {
        const auto &a = surface.points[t[k]], &b = surface.points[t[(k + 1) % 3]];
        min_edge = std::min(
            min_edge, std::hypot(double(a[0]) - b[0], double(a[1]) - b[1], double(a[2]) - b[2]));
      }
    std::printf("min edge   %.3g m\n", min_edge);
    std::printf("bbox       [%.6g, %.6g] x [%.6g, %.6g] x [%.6g, %.6g] m\n", lo[0], hi[0], lo[1],
                hi[1], lo[2], hi[2]);
    std::printf("checks     closed, oriented, manifold, one component, no self-intersection\n");
    return kExitOk;
  } catch (const BadOption& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return kExitFailure;
  }
}
