// SPDX-License-Identifier: GPL-3.0-or-later
// Which way should a distributed run write its frames: every rank its own rows into one file
// with parallel HDF5 (MPI-IO, collective writes), or the ranks' rows gathered to rank 0, which
// writes them with serial HDF5 as one process does? This program times both on the frame
// layout of results.h5 (io/results/results_writer.hpp: /frames/displacement and velocity
// [frames, nodes, 3], stress [frames, elements, 9], von_mises, pressure and
// equivalent_plastic_strain [frames, elements], float64, chunks of one frame's rows up to 1 MiB,
// extended by one frame at a time, the file flushed after each frame).
//
//   mpirun -np 2 build/tools/bench/frame_writers --elements 1000000 --frames 10 --dir /tmp/fw
//   (--rounds N: the two writers alternated N times; --keep: the files stay, for h5diff)
//
// The rows each rank owns are those of a box of TET10 cut across its longest side, numbered as
// femdem numbers a box (x fastest): every rank owns one run of rows per (y, z) line of cells,
// so a rank's selection is many short runs, as in a real run; `--blocks` gives each rank one
// contiguous block instead (the best case for parallel HDF5).
//
// Gathered: one MPI_Gatherv of each field's owned rows to rank 0, which places them in the
// whole array and writes the frame in single-writer/multiple-reader mode (what keeps a killed
// run's frames readable: parallel HDF5 cannot open a file in that mode).
// Parallel: the file opened with the MPI-IO driver; each rank selects its runs in the frame's
// row of each dataset (a union of hyperslabs) and all write collectively.
// Prints, per writer, the seconds per frame (the slowest rank's, median of the frames after the
// first) and the bytes of one frame.
#include <hdf5.h>
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

namespace {

struct Field {
  const char* name;
  bool on_nodes;
  hsize_t comps;
};
constexpr Field kFields[] = {{"displacement", true, 3}, {"velocity", true, 3},
                             {"stress", false, 9},      {"von_mises", false, 1},
                             {"pressure", false, 1},    {"equivalent_plastic_strain", false, 1}};
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

void check(herr_t status, const char* what) {
  if (status < 0) {
    std::fprintf(stderr, "frame_writers: %s failed\n", what);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
}
hid_t checked(hid_t id, const char* what) {
  check(id < 0 ? -1 : 0, what);
  return id;
}

// A run of consecutive rows owned by one rank.
struct Run {
  hsize_t first, count;
};

// The box: cells nx x ny x nz, 6 TET10 a cell; nodes on the (2 nx + 1) x (2 ny + 1) x
// (2 nz + 1) lattice of a TET10 mesh; rows numbered x fastest. Rank r owns cells (and the
// lattice nodes) whose x index falls in its slab of x.
struct Box {
  long nx, ny, nz;
  long elements() const { return 6 * nx * ny * nz; }
  long nodes() const { return (2 * nx + 1) * (2 * ny + 1) * (2 * nz + 1); }
};

Box box_of(long elements) {
  // a box twice as long as it is wide, so that two ranks cut it across its length
  const double cells = static_cast<double>(elements) / 6.0;
  const long n = std::max(1L, std::lround(std::cbrt(cells / 2.0)));
  return {2 * n, n, n};
}

std::vector<Run> owned_runs(long lines, long per_line, int rank, int ranks, bool blocks,
                            long row_width) {
  // per line of `per_line` x positions, each `row_width` rows long (6 elements a cell, 1 node)
  std::vector<Run> runs;
  if (blocks) {
    const long total = lines * per_line * row_width;
    const long first = total * rank / ranks, last = total * (rank + 1) / ranks;
    runs.push_back({static_cast<hsize_t>(first), static_cast<hsize_t>(last - first)});
    return runs;
  }
  const long x0 = per_line * rank / ranks, x1 = per_line * (rank + 1) / ranks;
  for (long l = 0; l < lines; ++l)
    runs.push_back({static_cast<hsize_t>((l * per_line + x0) * row_width),
                    static_cast<hsize_t>((x1 - x0) * row_width)});
  return runs;
}

hsize_t rows_in(const std::vector<Run>& runs) {
  hsize_t n = 0;
  for (const Run& r : runs) n += r.count;
  return n;
}

struct Layout {
  hsize_t nodes, elements;
  std::vector<Run> node_runs, element_runs;
};

Layout layout_of(long elements, int rank, int ranks, bool blocks) {
  const Box b = box_of(elements);
  Layout l;
  l.nodes = static_cast<hsize_t>(b.nodes());
  l.elements = static_cast<hsize_t>(b.elements());
  l.node_runs = owned_runs((2 * b.ny + 1) * (2 * b.nz + 1), 2 * b.nx + 1, rank, ranks, blocks, 1);
  l.element_runs = owned_runs(b.ny * b.nz, b.nx, rank, ranks, blocks, 6);
  return l;
}

// The frame datasets, as results_writer.cpp makes them: [0, rows, comps], unlimited frames.
void create_frames(hid_t file, const Layout& l, bool parallel) {
  const hid_t group =
      checked(H5Gcreate2(file, "frames", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "H5Gcreate2");
  for (const Field& f : kFields) {
    const hsize_t rows = f.on_nodes ? l.nodes : l.elements;
    const hsize_t dims[3] = {0, rows, f.comps}, maxdims[3] = {H5S_UNLIMITED, rows, f.comps};
    const hsize_t chunk_rows =
        std::clamp<hsize_t>(kChunkBytes / (f.comps * sizeof(double)), 1, rows);
    const hsize_t chunk[3] = {1, chunk_rows, f.comps};
    const hid_t space = checked(H5Screate_simple(3, dims, maxdims), "H5Screate_simple");
    const hid_t dcpl = checked(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate");
    check(H5Pset_chunk(dcpl, 3, chunk), "H5Pset_chunk");
    check(H5Pset_fill_time(dcpl, H5D_FILL_TIME_NEVER), "H5Pset_fill_time");
    // (parallel HDF5 allocates a chunked dataset's space when it is extended, on every rank)
    if (parallel) check(H5Pset_alloc_time(dcpl, H5D_ALLOC_TIME_EARLY), "H5Pset_alloc_time");
    const hid_t d =
        checked(H5Dcreate2(group, f.name, H5T_IEEE_F64LE, space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
                "H5Dcreate2");
    H5Dclose(d);
    H5Pclose(dcpl);
    H5Sclose(space);
  }
  H5Gclose(group);
}

// One frame of one field into row `frame` of its dataset: `rows` whole rows from `data` (the
// rank's runs in order), selected in the file as `runs`.
void write_rows(hid_t file, const Field& f, hsize_t frame, hsize_t total_rows,
                const std::vector<Run>& runs, const double* data, hid_t dxpl) {
  const std::string path = std::string("frames/") + f.name;
  const hid_t d = checked(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "H5Dopen2");
  const hsize_t extent[3] = {frame + 1, total_rows, f.comps};
  check(H5Dset_extent(d, extent), "H5Dset_extent");
  const hid_t fspace = checked(H5Dget_space(d), "H5Dget_space");
  check(H5Sselect_none(fspace), "H5Sselect_none");
  for (const Run& r : runs) {
    if (r.count == 0) continue;
    const hsize_t start[3] = {frame, r.first, 0}, count[3] = {1, r.count, f.comps};
    check(H5Sselect_hyperslab(fspace, H5S_SELECT_OR, start, nullptr, count, nullptr),
          "H5Sselect_hyperslab");
  }
  const hsize_t n = rows_in(runs) * f.comps;
  const hsize_t mdims[1] = {std::max<hsize_t>(n, 1)};
  const hid_t mspace = checked(H5Screate_simple(1, mdims, nullptr), "H5Screate_simple");
  if (n == 0) H5Sselect_none(mspace);
  check(H5Dwrite(d, H5T_NATIVE_DOUBLE, mspace, fspace, dxpl, data), "H5Dwrite");
  H5Sclose(mspace);
  H5Sclose(fspace);
  H5Dclose(d);
}

double now() {
  return MPI_Wtime();
}

// The values a rank holds of one field: its rows in order, filled with something non-constant.
std::vector<double> owned_values(const std::vector<Run>& runs, hsize_t comps, int frame) {
  std::vector<double> v;
  v.reserve(rows_in(runs) * comps);
  for (const Run& r : runs)
    for (hsize_t i = 0; i < r.count; ++i)
      for (hsize_t c = 0; c < comps; ++c)
        v.push_back(1e-3 * static_cast<double>(r.first + i) + static_cast<double>(c) + frame);
  return v;
}

// The values of every field (kFields) a rank holds in `frame`.
std::vector<std::vector<double>> frame_values(const Layout& l, int frame) {
  std::vector<std::vector<double>> values;
  for (const Field& f : kFields)
    values.push_back(owned_values(f.on_nodes ? l.node_runs : l.element_runs, f.comps, frame));
  return values;
}

// The slowest rank's seconds since its `start` (a frame is written when every rank is done).
double slowest_since(double start) {
  double mine = now() - start, slowest = 0.0;
  MPI_Allreduce(&mine, &slowest, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return slowest;
}

// Gathered: each field's owned rows to rank 0 (MPI_Gatherv), placed into the whole frame there
// and written by rank 0 alone; the file in single-writer/multiple-reader mode.
std::vector<double> gathered(const Layout& l, const std::string& file_name, int frames) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  hid_t file = -1;
  if (rank == 0) {
    const hid_t fapl = checked(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate");
    check(H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST), "libver");
    file = checked(H5Fcreate(file_name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "H5Fcreate");
    H5Pclose(fapl);
    create_frames(file, l, false);
    check(H5Fstart_swmr_write(file), "H5Fstart_swmr_write");
  }
  // each rank's runs, once, to rank 0 (as a distributed run's partition is known to rank 0)
  auto runs_of_all = [&](const std::vector<Run>& mine) {
    const int n = static_cast<int>(mine.size() * 2);
    std::vector<int> counts(ranks), displs(ranks);
    MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    int total = 0;
    for (int r = 0; r < ranks; ++r) displs[r] = total, total += counts[r];
    std::vector<unsigned long long> all(static_cast<std::size_t>(std::max(total, 1)));
    std::vector<unsigned long long> flat;
    for (const Run& r : mine) flat.push_back(r.first), flat.push_back(r.count);
    MPI_Gatherv(flat.data(), n, MPI_UNSIGNED_LONG_LONG, all.data(), counts.data(), displs.data(),
                MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
    std::vector<std::vector<Run>> per(ranks);
    for (int r = 0; r < ranks && rank == 0; ++r)
      for (int k = displs[r]; k < displs[r] + counts[r]; k += 2)
        per[r].push_back({all[k], all[k + 1]});
    return per;
  };
  const auto node_runs = runs_of_all(l.node_runs);
  const auto element_runs = runs_of_all(l.element_runs);
  std::vector<double> seconds;
  std::vector<double> whole, received;
  for (int frame = 0; frame < frames; ++frame) {
    const std::vector<std::vector<double>> values = frame_values(l, frame);
    MPI_Barrier(MPI_COMM_WORLD);
    const double start = now();
    for (std::size_t k = 0; k < std::size(kFields); ++k) {
      const Field& f = kFields[k];
      const auto& per = f.on_nodes ? node_runs : element_runs;
      const hsize_t total_rows = f.on_nodes ? l.nodes : l.elements;
      const int n = static_cast<int>(values[k].size());
      std::vector<int> counts(ranks), displs(ranks);
      MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
      int sum = 0;
      for (int r = 0; r < ranks; ++r) displs[r] = sum, sum += counts[r];
      received.resize(rank == 0 ? static_cast<std::size_t>(sum) : 1);
      MPI_Gatherv(values[k].data(), n, MPI_DOUBLE, received.data(), counts.data(), displs.data(),
                  MPI_DOUBLE, 0, MPI_COMM_WORLD);
      if (rank != 0) continue;
      whole.resize(total_rows * f.comps);
      for (int r = 0; r < ranks; ++r) {
        const double* src = received.data() + displs[r];
        for (const Run& run : per[r]) {
          std::memcpy(whole.data() + run.first * f.comps, src,
                      run.count * f.comps * sizeof(double));
          src += run.count * f.comps;
        }
      }
      write_rows(file, f, static_cast<hsize_t>(frame), total_rows, {Run{0, total_rows}},
                 whole.data(), H5P_DEFAULT);
    }
    if (rank == 0) check(H5Fflush(file, H5F_SCOPE_LOCAL), "H5Fflush");
    seconds.push_back(slowest_since(start));
  }
  if (rank == 0) H5Fclose(file);
  return seconds;
}

// Parallel: one file opened by every rank with the MPI-IO driver, collective writes of each
// rank's runs.
std::vector<double> parallel(const Layout& l, const std::string& file_name, int frames) {
  const hid_t fapl = checked(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate");
  check(H5Pset_fapl_mpio(fapl, MPI_COMM_WORLD, MPI_INFO_NULL), "H5Pset_fapl_mpio");
  check(H5Pset_libver_bounds(fapl, H5F_LIBVER_LATEST, H5F_LIBVER_LATEST), "libver");
  const hid_t file =
      checked(H5Fcreate(file_name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "H5Fcreate");
  H5Pclose(fapl);
  create_frames(file, l, true);
  const hid_t dxpl = checked(H5Pcreate(H5P_DATASET_XFER), "H5Pcreate");
  check(H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE), "H5Pset_dxpl_mpio");
  std::vector<double> seconds;
  for (int frame = 0; frame < frames; ++frame) {
    const std::vector<std::vector<double>> values = frame_values(l, frame);
    MPI_Barrier(MPI_COMM_WORLD);
    const double start = now();
    for (std::size_t k = 0; k < std::size(kFields); ++k) {
      const Field& f = kFields[k];
      write_rows(file, f, static_cast<hsize_t>(frame), f.on_nodes ? l.nodes : l.elements,
                 f.on_nodes ? l.node_runs : l.element_runs, values[k].data(), dxpl);
    }
    check(H5Fflush(file, H5F_SCOPE_GLOBAL), "H5Fflush");
    seconds.push_back(slowest_since(start));
  }
  H5Pclose(dxpl);
  H5Fclose(file);
  return seconds;
}

double median_after_first(std::vector<double> s) {
  if (s.size() > 1) s.erase(s.begin());
  std::sort(s.begin(), s.end());
  return s[s.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  long elements = 100000;
  int frames = 10, rounds = 2;
  bool blocks = false, keep = false;
  std::string dir = "frame_writers_tmp";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* name) {
      if (i + 1 >= argc) {
        if (rank == 0) std::fprintf(stderr, "frame_writers: %s needs a value\n", name);
        MPI_Abort(MPI_COMM_WORLD, 2);
      }
      return std::string(argv[++i]);
    };
    if (a == "--elements")
      elements = std::stol(value("--elements"));
    else if (a == "--frames")
      frames = std::stoi(value("--frames"));
    else if (a == "--rounds")
      rounds = std::stoi(value("--rounds"));
    else if (a == "--dir")
      dir = value("--dir");
    else if (a == "--blocks")
      blocks = true;
    else if (a == "--keep")
      keep = true;
    else {
      if (rank == 0)
        std::fprintf(stderr,
                     "frame_writers: unknown option %s (--elements N --frames N "
                     "--rounds N --dir D --blocks --keep)\n",
                     a.c_str());
      MPI_Abort(MPI_COMM_WORLD, 2);
    }
  }
  if (rank == 0) std::filesystem::create_directories(dir);
  MPI_Barrier(MPI_COMM_WORLD);
  const Layout l = layout_of(elements, rank, ranks, blocks);
  double frame_bytes = 0.0;
  for (const Field& f : kFields)
    frame_bytes += 8.0 * static_cast<double>((f.on_nodes ? l.nodes : l.elements) * f.comps);
  if (rank == 0)
    std::printf(
        "%d ranks, %llu elements, %llu nodes, %s; one frame %.1f MB; %d frames a "
        "writer and round\n",
        ranks, static_cast<unsigned long long>(l.elements),
        static_cast<unsigned long long>(l.nodes),
        blocks ? "one block of rows a rank" : "runs of rows per line of cells", frame_bytes / 1e6,
        frames);
  for (int round = 0; round < rounds; ++round) {
    // alternated, so that the machine's drift touches both alike
    const double g = median_after_first(gathered(l, dir + "/gathered.h5", frames));
    const double p = median_after_first(parallel(l, dir + "/parallel.h5", frames));
    if (rank == 0)
      std::printf(
          "round %d: gathered %.4f s a frame (%.0f MB/s), parallel %.4f s a frame "
          "(%.0f MB/s), parallel / gathered %.2f\n",
          round + 1, g, frame_bytes / g / 1e6, p, frame_bytes / p / 1e6, p / g);
  }
  // (--keep: both files stay, to compare: h5diff DIR/gathered.h5 DIR/parallel.h5)
  if (rank == 0 && !keep) std::filesystem::remove_all(dir);
  MPI_Finalize();
  return 0;
}
