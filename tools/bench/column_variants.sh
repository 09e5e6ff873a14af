#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# scenes/column_collapse.toml at the fast test's size (100 grains in a 10.5 mm tube; the
# options of tests/scenes/test_column_collapse.cpp) with one thing changed at a time, two runs
# at a time on one thread each, then tools/plot_collapse.py on each: the sensitivity table of
# docs/VALIDATION.md, "Granular column collapse". And the column without rolling resistance
# (the scene's modulus, 1 MPa, to 0.41 s), which rolls out: the reason the scene has it.
#   tools/bench/column_variants.sh [FEMDEM] [OUT_DIR]
set -uo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
femdem="${1:-$root/build/femdem}" out="${2:-out/column_variants}"
mkdir -p "$out"
small=(--set packings.g.generate.radius=10.5e-3 --set packings.g.generate.count=100
  --set "packings.g.cache=$out/packing_100.csv" --set tubes.tube.radius=10.5e-3
  --set tubes.tube.height=40e-3)
lift() { echo "tubes.tube.velocity_history=[[0,0,0,0],[0.02,0,0,0],[0.022,0,0,$1]]"; }
soft=(--set materials.glass.youngs_modulus=0.1e6 --set simulation.deformation_damping.frequency=1900)
run() {  # name, options...
  local name=$1; shift
  OMP_NUM_THREADS=1 /usr/bin/time -f "$name: user %U s" "$femdem" run "$root/scenes/column_collapse.toml" \
    "${small[@]}" "$@" --out "$out/$name" --force --threads 1 --quiet --no-plot 2>&1 | tail -1
}
run base "${soft[@]}" --set "$(lift 0.5)" &
run stiff --set materials.glass.youngs_modulus=0.25e6 \
  --set simulation.deformation_damping.frequency=3000 --set "$(lift 0.5)" &
wait
run slow_lift "${soft[@]}" --set "$(lift 0.25)" &
run base_friction_0.13 "${soft[@]}" --set "$(lift 0.5)" --set walls.base.friction=0.13 &
wait
run base_friction_0.03 "${soft[@]}" --set "$(lift 0.5)" --set walls.base.friction=0.03 &
run no_rolling_resistance --set "$(lift 0.5)" --set contact.rolling_resistance=0 \
  --set simulation.end_time=0.41 &
wait
for name in base stiff slow_lift base_friction_0.13 base_friction_0.03 no_rolling_resistance; do
  echo "== $name"
  /usr/bin/python3 "$root/tools/plot_collapse.py" "$out/$name" --start 0.02 | sed -n 1,3p
done
