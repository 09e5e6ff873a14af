#!/usr/bin/env bash
# What a frame of a distributed run costs, and which way of writing it is faster on this machine
# (docs/PERFORMANCE.md, "Frames of a distributed run: gathered or parallel HDF5").
#   tools/bench/frame_costs.sh [FEMDEM] [OUTDIR]     (FEMDEM: build/femdem by default)
# 1. results.h5's frame layout written on 2 ranks both ways: gathered to rank 0 and written with
#    serial HDF5, or written by every rank with parallel HDF5 (build/tools/bench/frame_writers,
#    built where `tools/setup parallel-hdf5` installed HDF5 on Open MPI), 10^5 and 10^6
#    elements, the ranks' rows in runs as femdem deals a box, and in one block each.
# 2. femdem's own frames: the loop time of the box of tools/bench/timed_runs.py with 20 frames
#    after the first against 1, on 2 ranks of one thread and in one process of 2 threads; the
#    difference over 19 is one frame.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
femdem="${1:-$root/build/femdem}"
out="${2:-$root/out/frame_costs}"
writers="$root/build/tools/bench/frame_writers"
mpi=(mpirun -np 2 --oversubscribe --allow-run-as-root --bind-to none)
mkdir -p "$out"
if [ -x "$writers" ]; then
  for elements in 100000 1000000; do
    "${mpi[@]}" "$writers" --elements "$elements" --frames 8 --rounds 2 --dir "$out/writers"
    "${mpi[@]}" "$writers" --elements "$elements" --frames 8 --rounds 1 --blocks \
      --dir "$out/writers"
  done
else
  echo "frame_costs: $writers not built (tools/setup parallel-hdf5, then tools/build)" >&2
fi
for size in 1e5 1e6; do
  steps=100
  [ "$size" = 1e6 ] && steps=40
  for frames in 1 20; do
    echo "femdem, $size elements, $steps steps, $frames frame(s) after the first:"
    /usr/bin/python3 "$root/tools/bench/timed_runs.py" --femdem "$femdem" --sizes "$size" \
      --steps "$steps" --layouts 2x1,1x2 --frames "$frames" --out "$out/runs_$frames" | tail -2
    grep -h "rank 0's loop" "$out/runs_$frames"/n*_r2_t1/run.log || true
  done
done
