#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Two femdem binaries on 2 MPI ranks of one thread each, resumed from the same checkpoint over
# the same window, alternated for a number of rounds: wall and user time of each, rank 0's
# stepping time and the contact figures of run.log, and whether both wrote the same history.csv.
# The start state is made once with NEW: one process of 2 threads to T0, then 2 ranks to T1
# (so that the ranks' bodies are dealt as a 2-rank run deals them). docs/PERFORMANCE.md,
# "Distributed runs".
#   tools/bench/rank_binaries.sh OLD_FEMDEM NEW_FEMDEM OUT_DIR SCENE T0 T1 T2 [ROUNDS [--set ...]]
set -euo pipefail
old=$(realpath "$1") new=$(realpath "$2") out=$3 scene=$(realpath "$4") t0=$5 t1=$6 t2=$7
rounds=${8:-2}
sets=("${@:9}")
mkdir -p "$out"
cd "$out"
mpi=(mpirun -np 2 --allow-run-as-root -x OMP_NUM_THREADS=1)
if [ ! -f start/checkpoint.h5 ]; then
  rm -rf start
  OMP_NUM_THREADS=2 "$new" run "$scene" --quiet --no-plot --threads 2 --out start \
    --set simulation.end_time="$t0" "${sets[@]}"
  "${mpi[@]}" "$new" resume start --quiet --threads 1 --set simulation.end_time="$t1"
fi
for round in $(seq 1 "$rounds"); do
  for which in old new; do
    bin=$old
    [ "$which" = new ] && bin=$new
    d=${which}_$round
    rm -rf "$d"
    cp -r start "$d"
    /usr/bin/time -f "%e s wall %U s user" "${mpi[@]}" "$bin" resume "$d" --quiet --threads 1 \
      --set simulation.end_time="$t2" > "$d.out" 2>&1
    echo "$t1 -> $t2 s, $which, round $round: $(tail -1 "$d.out")"
    # (the lines this resume added to run.log)
    tail -n +$(($(wc -l <start/run.log) + 1)) "$d/run.log" |
      grep "rank 0's loop\|contact nodes\|contact pairs evaluated" | sed 's/^/  /' || true
  done
  cmp "old_$round/history.csv" "new_$round/history.csv" && echo "  the same history.csv"
done
