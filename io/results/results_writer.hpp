// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// results.h5 + results.xdmf: the mesh once, then one frame per call of write_frame().
//
// Layout of results.h5 (HDF5 1.10 format, written in SWMR mode; format_version 2):
//   /                      attributes: complete (int32: 0 while running or if the run was killed
//                          or closed with close(false), 1 after close(true)), format
//                          ("femdem-results"), format_version (int32, 2), femdem_version,
//                          scene_digest, units ("SI: m, s, kg, Pa, N, J"), node_order (the TET10
//                          node order of /mesh/connectivity, in words)
//   /mesh/coordinates      [nodes, 3]      float64, reference coordinates
//   /mesh/connectivity     [elements, 10]  int32, TET10 in VTK / XDMF Tetrahedron_10 order
//   /mesh/node_body        [nodes]         int32
//   /mesh/element_body     [elements]      int32
//   /mesh/body_names       [bodies]        fixed-length UTF-8 strings, index = body id
//   /frames/time           [frames]        float64 (chunks of 1024)
//   /frames/displacement   [frames, nodes, 3]     float64 (or float32, see Options)
//   /frames/velocity       [frames, nodes, 3]
//   /frames/stress         [frames, elements, 9]  Cauchy stress as a full row-major 3x3 tensor
//                                                 (xx xy xz yx yy yz zx zy zz)
//   /frames/von_mises      [frames, elements]
//   /frames/pressure       [frames, elements]
//   /frames/equivalent_plastic_strain [frames, elements]
//   /walls/names           [walls]         fixed-length UTF-8 strings (only when there are walls)
//   /walls/normal          [walls, 3]      float64, unit normals (towards the bodies)
//   /walls/patch           [walls, 4, 3]   float64, the rectangle drawn for each wall at t = 0
//                                          (io/results/wall_patch.hpp)
//   /walls/displacement    [frames, walls, 3]  float64, each wall's translation since t = 0
//   /walls/force           [frames, walls, 3]  float64, the force the bodies exert on it, N
//   /frame_views/NNNNNN/<field>  one frame of each field above as a dataset of its own
//                          ([nodes, 3], [elements, 9], [elements]): HDF5 virtual datasets onto
//                          row NNNNNN of /frames/<field>, no data of their own
// Every /frames dataset but time carries an attribute `unit`. Frame datasets are chunked
// [1, up to ~1 MiB of one frame, components] with an unlimited first dimension, so one frame is
// a contiguous set of whole chunks.
//
// Why the views: XDMF readers that cannot take a HyperSlab of a larger dataset (meshio's
// TimeSeriesReader; ParaView's Xdmf3 readers lose such fields) read a frame as one whole dataset.
// SWMR mode allows no new objects once it has started, so the views are made when the file is
// created (or reopened to resume), for the frames the run expects (ResultsOptions); a frame past
// them is named in results.xdmf by a HyperSlab, which ParaView's legacy XDMF reader reads.
//
// Crash consistency: the file is written in HDF5's single-writer/multiple-reader mode, whose
// ordered metadata flushes keep the file valid at every moment. Each frame is written, flushed,
// then /frames/time is extended and flushed: len(/frames/time) is the number of complete
// frames. results.xdmf is then replaced atomically (temp + rename) and names only complete
// frames. After a kill, open results.h5 with H5F_ACC_SWMR_READ (h5py: swmr=True), or clear the
// writer's mark first with `h5clear -s results.h5` (HDF5 tools) for readers that do not use
// SWMR, e.g. ParaView and meshio.
//
// results.xdmf: a Temporal Collection of Uniform grids; every grid uses the reference
// coordinates as geometry and the frame's views as attributes. The deformed shape is shown by
// ParaView's "Warp By Vector" filter on `displacement` (scale factor 1). Stress is declared as
// a 9-component "Tensor" because XDMF readers disagree on the component order of "Tensor6".
//
// walls.xdmf (only when there are walls; ParaView opens it beside results.xdmf): the same
// frames, each wall a quadrilateral where it is at that time (no warp needed), with the cell
// fields `wall` (index) and `force`. Its numbers are inline XML, so it reads anywhere.
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "elements/tet10_mesh.hpp"

namespace femdem {

struct ResultsWall {
  std::string name;
  Vec3 normal = Vec3(0, 0, 1);
  std::array<Vec3, 4> patch{};  // corners at t = 0 (io/results/wall_patch.hpp)
};

struct ResultsMesh {
  std::span<const double> coordinates;         // 3 per node, reference
  std::span<const Tet10> connectivity;         // per element
  std::span<const std::int32_t> node_body;     // per node
  std::span<const std::int32_t> element_body;  // per element
  std::span<const std::string> body_names;     // per body
  std::span<const ResultsWall> walls = {};     // per rigid wall
};

struct FrameFields {
  std::span<const double> displacement;               // 3 per node
  std::span<const double> velocity;                   // 3 per node
  std::span<const double> stress;                     // 6 per element: xx yy zz xy yz xz
  std::span<const double> von_mises;                  // 1 per element
  std::span<const double> pressure;                   // 1 per element
  std::span<const double> equivalent_plastic_strain;  // 1 per element
  std::span<const double> wall_displacement = {};     // 3 per wall
  std::span<const double> wall_force = {};            // 3 per wall
  // the optional fields (ResultsOptions::optional_fields; engine/output_fields.hpp), needed only
  // when chosen
  std::span<const double> log_strain = {};        // 6 per element: xx yy zz xy yz xz
  std::span<const double> nodal_stress = {};      // 6 per node
  std::span<const double> contact_force = {};     // 3 per node
  std::span<const double> contact_pressure = {};  // 1 per node
  std::span<const double> body_velocity = {};     // 3 per node
};

struct ResultsOptions {
  bool single_precision = false;  // store frame fields as float32 (half the size)
  std::string scene_digest = {};  // root attribute scene_digest (io/scene/scene_digest.hpp)
  // The frames the run expects to write (its schedule's count): /frame_views are made for this
  // many (at most kMaxFrameViews). 0: none (every frame is named by a HyperSlab).
  std::int64_t expected_frames = 0;
  // Optional fields written besides the default ones: any of "log_strain", "nodal_stress",
  // "contact_force", "contact_pressure", "body_velocity" (each a /frames dataset, named so), and
  // "node_body" (/mesh/node_body named in results.xdmf as a node field).
  std::vector<std::string> optional_fields = {};
};

// The most frames /frame_views are made for (6 small objects each, made before the run starts:
// see docs/PERFORMANCE.md for their cost).
inline constexpr std::int64_t kMaxFrameViews = 20000;

// The scene_digest attribute of `folder`/results.h5 ("" when the file or the attribute is
// missing): which scene the results belong to, what femdem resume checks a checkpoint against.
std::string results_scene_digest(const std::filesystem::path& folder);

class ResultsWriter {
 public:
  // Creates `folder` if needed, replaces results.xdmf (by one with no frames) and results.h5,
  // and writes the mesh. Throws std::invalid_argument for inconsistent sizes and
  // std::runtime_error for I/O errors (naming the file).
  ResultsWriter(const std::filesystem::path& folder, const ResultsMesh& mesh,
                ResultsOptions options = {});
  // Continues the results of an interrupted run in `folder` (femdem resume): keeps their first
  // `frames` frames (those written before the checkpoint the run resumes from), drops any after
  // them, marks the file incomplete again and appends from there. Throws std::runtime_error
  // naming the file when it is missing, holds another mesh or fewer frames.
  struct ContinueFrom {
    std::int64_t frames = 0;
  };
  ResultsWriter(const std::filesystem::path& folder, const ResultsMesh& mesh, ContinueFrom from,
                ResultsOptions options = {});
  // Closes as close(false) if still open; never throws.
  ~ResultsWriter();
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  // Appends one frame (sizes checked against the mesh), flushes it to the file and rewrites
  // results.xdmf. Throws std::invalid_argument / std::runtime_error; after a runtime_error the
  // frames written before stay valid.
  void write_frame(double time, const FrameFields& fields);

  // Closes the file; `complete` sets the root attribute complete = 1 (a finished run).
  // Idempotent; later write_frame calls throw std::logic_error.
  void close(bool complete);

  std::int64_t frame_count() const;
  bool is_open() const;
  std::filesystem::path h5_path() const;
  std::filesystem::path xdmf_path() const;
  std::filesystem::path walls_xdmf_path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace femdem
