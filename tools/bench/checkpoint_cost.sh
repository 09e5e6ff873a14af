#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# What a checkpoint costs at 10^4, 10^5 and 10^6 TET10 elements (an elastic von Mises block on a
# wall, a few steps): checkpoint.h5's size per element, the time to write one (the run log's
# total over the run's checkpoints), the time to read one (the resume's log), and the share of a run's wall time that writing one every
# checkpoint_wall_interval (600 s by default) takes. The figures of docs/PERFORMANCE.md,
# "Checkpoints".
#   tools/bench/checkpoint_cost.sh [FEMDEM [OUT_DIR [ELEMENT_SIZE ...]]]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
femdem="${1:-$root/build/femdem}" out="${2:-out/checkpoint_cost}"
sizes=(0.083 0.0385 0.0179)  # box of 1 m: about 1e4, 1e5, 1e6 elements
[ $# -gt 2 ] && sizes=("${@:3}")
mkdir -p "$out"
scene="$out/block.toml"
cat >"$scene" <<'TOML'
title = "checkpoint cost: a plastic block on a wall"
[simulation]
end_time = 1.0  # set per size below: 12 steps
checkpoint_wall_interval = 0.0
[[materials]]
name = "steel"
model = "von_mises"
density = 7850.0
youngs_modulus = 210e9
poisson_ratio = 0.3
yield_stress = 250e6
[[bodies]]
name = "block"
material = "steel"
mesh = { generator = "box", size = [1.0, 1.0, 1.0], element_size = 0.1 }
position = [0.0, 0.0, 0.0]
velocity = [0.0, 0.0, -5.0]
[[walls]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
friction = 0.3
TOML
printf '%-9s %-10s %-12s %-9s %-13s %-11s %-10s %s\n' elements nodes checkpoint_MB B/element \
  write_s/ckpt read_s step_s share_at_600s
for h in "${sizes[@]}"; do
  dir="$out/h$h"
  # the stable step is about 0.3 h / 5900 m/s: 12 steps, a checkpoint every 4
  end=$(python3 -c "print(12 * 0.35 * $h / 5900)")
  every=$(python3 -c "print($end / 3)")
  sets=(--set "bodies.block.mesh.element_size=$h" --set "simulation.end_time=$end"
    --set "simulation.checkpoint_interval=$every" --set "simulation.output_interval=$end")
  "$femdem" run "$scene" --quiet --threads 2 --out "$dir" "${sets[@]}"
  longer=$(python3 -c "print(1.2 * $end)")
  cp "$dir/summary.json" "$dir/summary_run.json"
  "$femdem" resume "$dir" --quiet --threads 2 --set "simulation.end_time=$longer"
  python3 - "$dir" <<'PY'
import json, os, re, sys
d = sys.argv[1]
run = json.load(open(os.path.join(d, "summary_run.json")))
res = json.load(open(os.path.join(d, "summary.json")))
log = open(os.path.join(d, "run.log")).read()
n, t = re.findall(r"(\d+) checkpoints? written in ([0-9.e+-]+) s", log)[0]
write = float(t) / int(n)
size = os.path.getsize(os.path.join(d, "checkpoint.h5"))
read = float(re.findall(r"read in ([0-9.e+-]+) s", log)[0])
step = run["extra"]["loop_time_s"] / run["steps"]
e = run["elements"]
print(f"{e:<9d} {run['nodes']:<10d} {size / 1e6:<12.1f} {size / e:<9.0f} {write:<13.3f} "
      f"{read:<11.3f} {step:<10.4f} {100 * write / 600:.3f} %")
PY
done
