#!/usr/bin/env bash
# The Taylor bar as the paper sets it up (scenes/taylor_bar.toml: no mass scaling), with the
# element-and-contact bound, with the assembled stable-step estimate at safety 0.5 and with the
# defaults (0.8 of it), as in docs/PERFORMANCE.md ("Stable step"): steps, loop time, final length
# and bounding-box base radius (tools/taylor_profile.py OUT gives the mean rim radius).
#   tools/bench/stable_step_taylor.sh [OUT_DIR]        (default out/stable_step_taylor)
# CalculiX's fixed increment on the same meshes: tools/bench/calculix_taylor.py --h H --increment-only
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
femdem="${FEMDEM:-$root/build/femdem}"
out="${1:-$root/out/stable_step_taylor}"
run() {  # name, threads, extra --set options
  local name=$1 threads=$2
  shift 2
  "$femdem" run "$root/scenes/taylor_bar.toml" --set simulation.mass_scaling_time_step=0 "$@" \
    --threads "$threads" --no-plot --quiet --out "$out/$name"
  /usr/bin/python3 - "$out/$name/summary.json" "$name" <<'PY'
import json, sys
s = json.load(open(sys.argv[1])); b = s["bodies"]["rod"]; e = s["extra"]
print(f"{sys.argv[2]:>24}: {s['steps']:>7} steps, loop {e['loop_time_s']:.1f} s, "
      f"length {1e3 * b['bbox_max'][2]:.4f} mm, base radius {1e3 * (b['bbox_max'][0] - b['bbox_min'][0]) / 2:.4f} mm, "
      f"energy error {100 * s['energy']['balance_error']:.3f} %, last stable step {e['stable_time_step']:.3e} s "
      f"(bound {e['stable_time_step_bound']:.3e} s)")
PY
}
run h1.6_element 1 --set bodies.rod.mesh.element_size=1.6e-3 --set simulation.stable_step=element
run h1.6_assembled_safety0.5 1 --set bodies.rod.mesh.element_size=1.6e-3 \
  --set simulation.time_step_safety=0.5
run h1.6_defaults 1 --set bodies.rod.mesh.element_size=1.6e-3
run h1.1_assembled_safety0.5 1 --set bodies.rod.mesh.element_size=1.1e-3 \
  --set simulation.time_step_safety=0.5
run h1.1_defaults 1 --set bodies.rod.mesh.element_size=1.1e-3
run h0.8_defaults 2
