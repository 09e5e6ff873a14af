#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# scenes/column_collapse.toml with one thing changed at a time, two runs at a time on one thread
# each, then tools/plot_collapse.py on each: the sensitivity tables of docs/VALIDATION.md,
# "Granular column collapse".
#   tools/bench/column_variants.sh [FEMDEM] [OUT_DIR] [SIZE]
# SIZE "small" (the default): the fast test's column (100 grains in a 10.5 mm tube; the options
#   of tests/scenes/test_column_collapse.cpp, modulus 0.1 MPa, lift 0.5 m/s) and the column
#   without rolling resistance (the scene's modulus, 1 MPa, to 0.41 s), which rolls out: the
#   reason the scene has it.
# SIZE "r7": the scene's column at 7 grain diameters of radius (573 grains in a 24.5 mm tube, the
#   same aspect ratio, the scene's modulus, the lift speed scaled with sqrt(R_i) to 0.130 m/s):
#   the modulus 4 times lower, the lift twice as fast, base friction 0.13 and 0.03.
# SIZE "r7soft": the r7 column at the modulus 4 times lower (0.25 MPa, within 3.3 % of the
#   scene's deposit: docs/VALIDATION.md), half the steps of r7: base friction 0.13 and 0.03 first
#   (about 80 min each on one core), then the lift twice as fast and the soft column itself, then
#   base friction 0.33 (the papers' middle value).
# SIZE "aspect": other aspect ratios at the modulus of r7soft, each lifted at the papers' Froude
#   number: a = 0.8 in the r7 tube (780 grains; the papers' 0.258 m/s at R_i 70.5 mm scaled with
#   sqrt(R_i) to 0.152 m/s), and a = 3 in tubes of 3 and 4 grain diameters (250 and 505 grains;
#   the tube clears the column in about 1.5 times its fall time sqrt(2 H_i / g), between the
#   papers' 2 at a = 0.8 and 0.86 at a = 8.94: 0.26 and 0.30 m/s), to 1.5 s; then the a = 3
#   column of 3 diameters on rough bases (the base's rolling resistance 0.3 and 0.5: a grain in
#   a pocket of a layer of glued grains of its size must lift its centre over its supports to
#   roll out, a lever of 0.29 of its radius over the saddle of two close-packed supports and
#   0.58 over one), and the column of 4 diameters on the base of 0.3.
# The modes small, r7, r7soft and aspect run on the smooth base (the grains' rolling resistance
#   0.1, as the scene was when they were measured); scale and rough_base on the coefficient base
#   (0.3), the scene's before it took the studded one; studded_base and studded_checks on that.
# SIZE "scale": the scale pair at a = 0.59 and E 0.25 MPa on the coefficient base: the r7soft column
#   (573 grains in a 24.5 mm tube) and the scene's 35 mm tube with 1,790 grains (the count that gives the
#   same a once settled at this modulus: the scene's 1,670 gave a = 0.565 at 1 MPa, and the
#   softer grains settle 2.5 % lower), the lift at the scene's 0.155 m/s (sqrt(R_i) scaling from
#   0.130 m/s), on 2 threads (about 1.2 h), then the r7 one on 1 thread.
# SIZE "rough_base": one base for every aspect ratio: the r7soft column (a = 0.59) and the a = 0.8
#   column of "aspect" on the base of rolling resistance 0.3 that meets eq. 61 at a = 3, then the
#   r7soft column on that base with base friction 0.13 (against 0.5: the issue's basal-friction
#   pair on the rough base), one thread each, about 1.5 h; then the r7soft column on that base
#   lifted twice as fast (0.26 m/s: the lift-speed check on the rough base).
# SIZE "studded_base": on the scene's base, the experiments' plane of glued beads made of geometry
#   (`walls.base.bumps`: hemispheres of the grains' mean diameter, touching, on a hexagonal
#   lattice; the plane lowered by their radius so their tops are at z = 0, where the packing
#   stands, and the tube with it), with the grains' own rolling resistance (0.1) on it: the r7soft
#   column with base friction 0.5 and 0.13 side by side (the issue's basal-friction pair), then
#   base friction 0.03 beside the a = 3 column of 3 grain diameters on it.
# SIZE "studded_checks": on that studded base, the checks measured on the coefficient base: the
#   a = 0.8 column of "aspect" (780 grains, lift 0.152 m/s, about 1.5 h) beside the r7soft column
#   of base friction 0.5 (studded_0.5 again, the reference) and then the same lifted twice as
#   fast (0.26 m/s: the lift-speed check).
# SIZE "studded_scale": the scale pair on the studded base: the scene's 35 mm tube with the
#   1,790 grains of "scale" (E 0.25 MPa, lift 0.155 m/s) on 2 threads (about 4 h: 0.1 s of the
#   collapse took 38 min on a shared machine, 2026-12-08, and the r7 column rests at 0.62 s), then the
#   r7soft column of studded_base (studded_0.5) again on 1 thread, with the same engine.
# ONLY (optional, a space-separated list): run only these names of the SIZE's list.
set -uo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
femdem="${1:-$root/build/femdem}" out="${2:-out/column_variants}" size="${3:-small}" only="${4:-}"
mkdir -p "$out" && out="$(cd "$out" && pwd)"
# The scene as shipped (its studded base) for the modes studded_base and studded_checks; the
# modes measured before it had that base run on a copy without its bumps, the plane and the tube
# back at z = 0: the smooth base (the grains' rolling resistance, 0.1: small, r7, r7soft,
# aspect) or the coefficient base (0.3: scale, rough_base), as the scene was when they were
# measured, so that their documented tables still reproduce.
scene="$root/scenes/column_collapse.toml"
flat_scene="$out/column_collapse_flat_base.toml"
grep -v '^bumps = ' "$scene" > "$flat_scene"
flat=(--set "walls.base.point=[0,0,0]" --set "tubes.tube.centre=[0,0,0]")
smooth=("${flat[@]}" --set walls.base.rolling_resistance=0.1)
coefficient=("${flat[@]}" --set walls.base.rolling_resistance=0.3)
lift() { echo "tubes.tube.velocity_history=[[0,0,0,0],[0.02,0,0,0],[0.022,0,0,$1]]"; }
run() {  # name, options... (on one thread; threads=N run ... for more)
  local name=$1 n=${threads:-1}; shift
  if [[ -n "$only" && " $only " != *" $name "* ]]; then return; fi
  OMP_NUM_THREADS=$n /usr/bin/time -f "$name: user %U s" "$femdem" run "$scene" \
    "${sized[@]}" "$@" --out "$out/$name" --force --threads "$n" --quiet --no-plot 2>&1 | tail -1
}
case "$size" in
  small)
    scene=$flat_scene
    sized=(--set packings.g.generate.radius=10.5e-3 --set packings.g.generate.count=100
      --set "packings.g.cache=$out/packing_100.csv" --set tubes.tube.radius=10.5e-3
      --set tubes.tube.height=40e-3 "${smooth[@]}")
    soft=(--set materials.glass.youngs_modulus=0.1e6 --set simulation.deformation_damping.frequency=1900)
    run base "${soft[@]}" --set "$(lift 0.5)" &
    run stiff --set materials.glass.youngs_modulus=0.25e6 \
      --set simulation.deformation_damping.frequency=3000 --set "$(lift 0.5)" &
    wait
    run slow_lift "${soft[@]}" --set "$(lift 0.25)" &
    run base_friction_0.13 "${soft[@]}" --set "$(lift 0.5)" --set walls.base.friction=0.13 &
    wait
    run base_friction_0.03 "${soft[@]}" --set "$(lift 0.5)" --set walls.base.friction=0.03 &
    run no_rolling_resistance --set "$(lift 0.5)" --set contact.rolling_resistance=0 \
      --set walls.base.rolling_resistance=0 \
      --set simulation.end_time=0.41 &
    wait
    names="base stiff slow_lift base_friction_0.13 base_friction_0.03 no_rolling_resistance" ;;
  r7)
    scene=$flat_scene
    sized=(--set packings.g.generate.radius=24.5e-3 --set packings.g.generate.count=573
      --set "packings.g.cache=$out/packing_573.csv" --set tubes.tube.radius=24.5e-3 "${smooth[@]}")
    # the packing first, once, so that the runs share it
    "$femdem" check "$scene" "${sized[@]}" > /dev/null
    run base --set "$(lift 0.130)" &
    run soft --set materials.glass.youngs_modulus=0.25e6 \
      --set simulation.deformation_damping.frequency=3000 --set "$(lift 0.130)" &
    wait
    run fast_lift --set "$(lift 0.260)" &
    run base_friction_0.13 --set "$(lift 0.130)" --set walls.base.friction=0.13 &
    wait
    run base_friction_0.03 --set "$(lift 0.130)" --set walls.base.friction=0.03 &
    wait
    names="base soft fast_lift base_friction_0.13 base_friction_0.03" ;;
  r7soft)
    scene=$flat_scene
    sized=(--set packings.g.generate.radius=24.5e-3 --set packings.g.generate.count=573
      --set "packings.g.cache=$out/packing_573.csv" --set tubes.tube.radius=24.5e-3
      --set materials.glass.youngs_modulus=0.25e6 --set simulation.deformation_damping.frequency=3000
      "${smooth[@]}")
    "$femdem" check "$scene" "${sized[@]}" > /dev/null
    run soft_friction_0.13 --set "$(lift 0.130)" --set walls.base.friction=0.13 &
    run soft_friction_0.03 --set "$(lift 0.130)" --set walls.base.friction=0.03 &
    wait
    run soft_fast_lift --set "$(lift 0.260)" &
    run soft --set "$(lift 0.130)" &
    wait
    run soft_friction_0.33 --set "$(lift 0.130)" --set walls.base.friction=0.33 &
    wait
    names="soft soft_fast_lift soft_friction_0.13 soft_friction_0.33 soft_friction_0.03" ;;
  aspect)
    scene=$flat_scene
    soft=(--set materials.glass.youngs_modulus=0.25e6 --set simulation.deformation_damping.frequency=3000
      --set simulation.end_time=1.5)
    column() {  # radius count
      echo --set packings.g.generate.radius=$1 --set packings.g.generate.count=$2 \
        --set "packings.g.cache=$out/packing_$2.csv" --set tubes.tube.radius=$1
    }
    sized=("${smooth[@]}")
    run a0.8_r7 "${soft[@]}" $(column 24.5e-3 780) --set "$(lift 0.152)" &
    (run a3_r3 "${soft[@]}" $(column 10.5e-3 250) --set "$(lift 0.26)"
      run a3_r4 "${soft[@]}" $(column 14e-3 505) --set "$(lift 0.30)"
      for mu_r in 0.5 0.3; do
        run a3_r3_rough_base_$mu_r "${soft[@]}" $(column 10.5e-3 250) --set "$(lift 0.26)" \
          --set walls.base.rolling_resistance=$mu_r
      done
      run a3_r4_rough_base_0.3 "${soft[@]}" $(column 14e-3 505) --set "$(lift 0.30)" \
        --set walls.base.rolling_resistance=0.3) &
    wait
    names="a0.8_r7 a3_r3 a3_r4 a3_r3_rough_base_0.5 a3_r3_rough_base_0.3 a3_r4_rough_base_0.3" ;;
  scale)
    scene=$flat_scene
    soft=(--set materials.glass.youngs_modulus=0.25e6 --set simulation.deformation_damping.frequency=3000)
    sized=(--set packings.g.generate.count=1790 --set "packings.g.cache=$out/packing_1790.csv"
      "${coefficient[@]}")
    "$femdem" check "$scene" "${sized[@]}" > /dev/null
    threads=2 run full "${soft[@]}"
    sized=(--set packings.g.generate.radius=24.5e-3 --set packings.g.generate.count=573
      --set "packings.g.cache=$out/packing_573.csv" --set tubes.tube.radius=24.5e-3
      "${coefficient[@]}")
    run r7 "${soft[@]}" --set "$(lift 0.130)"
    names="full r7" ;;
  rough_base)
    scene=$flat_scene
    soft=(--set materials.glass.youngs_modulus=0.25e6 --set simulation.deformation_damping.frequency=3000
      "${coefficient[@]}")
    sized=(--set packings.g.generate.radius=24.5e-3 --set tubes.tube.radius=24.5e-3)
    r7=(--set packings.g.generate.count=573 --set "packings.g.cache=$out/packing_573.csv")
    run a0.8_r7_rough_base_0.3 "${soft[@]}" --set packings.g.generate.count=780 \
      --set "packings.g.cache=$out/packing_780.csv" --set simulation.end_time=1.5 \
      --set "$(lift 0.152)" &
    (run soft_rough_base_0.3 "${soft[@]}" "${r7[@]}" --set "$(lift 0.130)"
      run soft_rough_base_0.3_friction_0.13 "${soft[@]}" "${r7[@]}" --set "$(lift 0.130)" \
        --set walls.base.friction=0.13) &
    wait
    run soft_rough_base_0.3_fast_lift "${soft[@]}" "${r7[@]}" --set "$(lift 0.260)"
    names="soft_rough_base_0.3 a0.8_r7_rough_base_0.3 soft_rough_base_0.3_friction_0.13
      soft_rough_base_0.3_fast_lift" ;;
  studded_base | studded_checks)
    # the scene's own base since commit c652e82 (these modes set it with --set before)
    soft=(--set materials.glass.youngs_modulus=0.25e6 --set simulation.deformation_damping.frequency=3000)
    sized=(--set packings.g.generate.radius=24.5e-3 --set tubes.tube.radius=24.5e-3)
    r7=(--set packings.g.generate.count=573 --set "packings.g.cache=$out/packing_573.csv")
    if [[ $size == studded_base ]]; then
      run studded_0.5 "${soft[@]}" "${r7[@]}" --set "$(lift 0.130)" &
      run studded_friction_0.13 "${soft[@]}" "${r7[@]}" --set "$(lift 0.130)" \
        --set walls.base.friction=0.13 &
      wait
      run studded_friction_0.03 "${soft[@]}" "${r7[@]}" --set "$(lift 0.130)" \
        --set walls.base.friction=0.03 &
      run a3_r3_studded "${soft[@]}" --set packings.g.generate.radius=10.5e-3 \
        --set tubes.tube.radius=10.5e-3 --set packings.g.generate.count=250 \
        --set "packings.g.cache=$out/packing_250.csv" --set simulation.end_time=1.5 \
        --set "$(lift 0.26)" &
      wait
      names="studded_0.5 studded_friction_0.13 studded_friction_0.03 a3_r3_studded"
    else
      run a0.8_r7_studded "${soft[@]}" --set packings.g.generate.count=780 \
        --set "packings.g.cache=$out/packing_780.csv" --set simulation.end_time=1.5 \
        --set "$(lift 0.152)" &
      (run studded_0.5 "${soft[@]}" "${r7[@]}" --set "$(lift 0.130)"
        run studded_fast_lift "${soft[@]}" "${r7[@]}" --set "$(lift 0.260)") &
      wait
      names="a0.8_r7_studded studded_0.5 studded_fast_lift"
    fi ;;
  studded_scale)
    soft=(--set materials.glass.youngs_modulus=0.25e6 --set simulation.deformation_damping.frequency=3000)
    sized=(--set packings.g.generate.count=1790 --set "packings.g.cache=$out/packing_1790.csv")
    "$femdem" check "$scene" "${sized[@]}" > /dev/null
    threads=2 run studded_full "${soft[@]}"
    sized=(--set packings.g.generate.radius=24.5e-3 --set tubes.tube.radius=24.5e-3
      --set packings.g.generate.count=573 --set "packings.g.cache=$out/packing_573.csv")
    run studded_0.5 "${soft[@]}" --set "$(lift 0.130)"
    names="studded_full studded_0.5" ;;
  *) echo "column_variants.sh: SIZE is small, r7, r7soft, aspect, scale, rough_base, studded_base, studded_checks or studded_scale, not '$size'" >&2; exit 2 ;;
esac
for name in $names; do
  if [[ -n "$only" && " $only " != *" $name "* ]]; then continue; fi
  echo "== $name"
  /usr/bin/python3 "$root/tools/plot_collapse.py" "$out/$name" --start 0.02 | sed -n 1,3p
done
