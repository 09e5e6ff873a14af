#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The contact-bound scenes over a window of each, with two femdem binaries one after the other,
# one thread each: user CPU time (immune to a loaded machine's descheduling), steps, candidate
# and touching pairs per step, and whether the two histories are the same bits. The figures of
# docs/PERFORMANCE.md, "Contact throughput (issue 18)".
#   tools/bench/contact_runs.sh OLD_FEMDEM NEW_FEMDEM [OUT_DIR [SCENE:END_TIME[:SET] ...]]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
old="$1" new="$2" out="${3:-out/contact_runs}"
# scene:end_time[:extra --set]
scenes=("powder_compaction:1.5e-5" "compaction_64_spheres:6e-4:packings.p.mesh.cells_per_radius=1"
  "sphere_impact_pair:2e-4" "closed_die_cube:2e-4")
[ $# -gt 3 ] && scenes=("${@:4}")  # or the scenes given after OUT_DIR
for scene in "${scenes[@]}"; do
  IFS=: read -r name end extra <<<"$scene"
  sets=(--set simulation.end_time="$end")
  [ -n "$extra" ] && sets+=(--set "$extra")
  for which in old new; do
    bin=$old
    [ "$which" = new ] && bin=$new
    dir="$out/$which/$name"
    /usr/bin/time -f "$name $which user %U s wall %e s" "$bin" run "$root/scenes/$name.toml" \
      --threads 1 --quiet --no-plot --out "$dir" "${sets[@]}" 2>&1 | tail -1
    python3 -c "import json,sys; s=json.load(open(sys.argv[1])); e=s['extra']; n=s['steps']; \
print('  steps', n, 'candidate pairs/step %.0f' % (e.get('contact_pair_evaluations', 0) / n), \
'touching/step %.0f' % (e.get('contact_touching_pair_evaluations', 0) / n), \
'energy balance %.2e' % s['energy']['balance_error'])" "$dir/summary.json"
  done
  if cmp -s "$out/old/$name/history.csv" "$out/new/$name/history.csv"; then
    echo "  $name: histories identical"
  else
    echo "  $name: histories differ"
  fi
done
