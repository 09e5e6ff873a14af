#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The armour layer as one process of 2 threads against 2 MPI ranks of 1 thread
# (docs/PERFORMANCE.md, "Distributed runs"), in two segments resumed from the same checkpoint:
# 0.6 -> 0.7 s (first impacts) and 1.2 -> 1.3 s (the layer forming), two rounds, alternated.
# Prints each run's wall and user time and run.log's lines on steps, rank 0's loop and the
# contact nodes received from other ranks; checks that both layouts write the same history.csv.
#   tools/bench/armour_layouts.sh BINARY OUTDIR
set -euo pipefail
bin=$(realpath "$1")
out=$2
scene=$(dirname "$(realpath "$0")")/../../scenes/armour_layer.toml
mkdir -p "$out"
cd "$out"
mpi="mpirun -np 2 --allow-run-as-root -x OMP_NUM_THREADS=1"
# the starting states: 0.6 s in one process, 1.2 s on 2 ranks from there
rm -rf start_0.6 start_1.2
OMP_NUM_THREADS=2 "$bin" run "$scene" --quiet --threads 2 --out start_0.6 --set simulation.end_time=0.6
cp -r start_0.6 start_1.2
$mpi "$bin" resume start_1.2 --quiet --threads 1 --set simulation.end_time=1.2
for segment in "0.6 0.7" "1.2 1.3"; do
  set -- $segment
  for round in 1 2; do
    for layout in 1x2 2x1; do
      d=from_$1_${layout}_$round
      rm -rf "$d"
      cp -r "start_$1" "$d"
      if [ "$layout" = 1x2 ]; then
        /usr/bin/time -f "%e s wall %U s user" "$bin" resume "$d" --quiet --threads 2 \
          --set simulation.end_time=$2 > "$d.out" 2>&1
      else
        /usr/bin/time -f "%e s wall %U s user" $mpi "$bin" resume "$d" --quiet --threads 1 \
          --set simulation.end_time=$2 > "$d.out" 2>&1
      fi
      echo "$1 -> $2 s, $layout, round $round: $(tail -1 "$d.out")"
      tail -3 "$d/run.log" | grep "done:\|rank 0's loop\|contact nodes" || true
    done
    cmp "from_$1_1x2_$round/history.csv" "from_$1_2x1_$round/history.csv" &&
      echo "  the same history.csv"
  done
done
