#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Whole runs of the same scenes with two femdem binaries, one after the other, one thread each:
# user CPU time (immune to a loaded machine's descheduling), steps, elements and the run's
# element-update rate. The figures of docs/PERFORMANCE.md, "SIMD element update (issue 16)".
#   tools/bench/old_vs_new_runs.sh OLD_FEMDEM NEW_FEMDEM [OUT_DIR]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
old="$1" new="$2" out="${3:-out/old_vs_new}"
for scene in sphere_impact:1.2e-3 taylor_bar:80e-6 armour_layer:0.5; do
  name=${scene%%:*} end=${scene##*:}
  for which in old new; do
    bin=$old
    [ "$which" = new ] && bin=$new
    dir="$out/$which/$name"
    /usr/bin/time -f "$name $which user %U s wall %e s" "$bin" run "$root/scenes/$name.toml" \
      --threads 1 --quiet --no-plot --out "$dir" --set simulation.end_time="$end" 2>&1 | tail -1
    python3 -c "import json,sys; s=json.load(open(sys.argv[1])); e=s['extra']; \
print('  steps', s['steps'], 'elements', s['elements'], 'element updates/s', e['element_updates_per_s'])" \
      "$dir/summary.json"
  done
done
