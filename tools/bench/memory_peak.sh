#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The peak resident size of `femdem run` (GNU time's %M, 2 threads, 3 us of a von Mises block or
# ball on a wall) against the estimate femdem makes before building the model
# (engine/memory_estimate.hpp): the table of docs/PERFORMANCE.md, "Memory".
#   tools/bench/memory_peak.sh [FEMDEM [OUT_DIR]]
set -euo pipefail
femdem="${1:-$(cd "$(dirname "$0")/../.." && pwd)/build/femdem}" out="${2:-out/memory_peak}"
mkdir -p "$out"
for shape in block ball; do
  if [ "$shape" = block ]; then
    mesh='{ generator = "box", size = [1.0, 1.0, 1.0], element_size = 0.1 }' position='[0.0, 0.0, 0.0]'
  else
    mesh='{ generator = "sphere", radius = 0.5, element_size = 0.05 }' position='[0.0, 0.0, 0.5]'
  fi
  cat >"$out/$shape.toml" <<TOML
title = "memory: a $shape on a wall"
[simulation]
end_time = 3e-6
output_interval = 3e-6
checkpoint_wall_interval = 0.0
[[materials]]
name = "steel"
model = "von_mises"
density = 7850.0
youngs_modulus = 210e9
poisson_ratio = 0.3
yield_stress = 250e6
[[bodies]]
name = "body"
material = "steel"
mesh = $mesh
position = $position
velocity = [0.0, 0.0, -5.0]
[[walls]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
TOML
done
printf '%-6s %-8s %-9s %-9s %-10s %-11s %s\n' mesh h nodes elements rss_MB estimate_MB ratio
for run in block:0.083 block:0.0385 block:0.0179 ball:0.04 ball:0.02; do
  IFS=: read -r shape h <<<"$run"
  rss=$(/usr/bin/time -f "%M" "$femdem" run "$out/$shape.toml" --quiet --force --threads 2 \
    --out "$out/run" --set "bodies.body.mesh.element_size=$h" 2>&1 >/dev/null | tail -1)
  python3 - "$out/run/summary.json" "$rss" "$shape" "$h" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
n, e, rss = s["nodes"], s["elements"], float(sys.argv[2]) * 1024 / 1e6
est = (30e6 + 3700 * e + 500 * n) / 1e6  # engine/memory_estimate.hpp
print(f"{sys.argv[3]:<6} {sys.argv[4]:<8} {n:<9d} {e:<9d} {rss:<10.0f} {est:<11.0f} {est / rss:.2f}")
PY
done
