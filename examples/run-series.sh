#!/usr/bin/env bash
# Run a series of the paper's scenes, each in its own directory, with its figure and outcomes.
#
#   examples/run-series.sh SERIES [PRESET] [-- extra lmp arguments, e.g. -sf omp -pk omp 4]
#
#   expts    Expts 1-3 at the standard rate (paper Figs. 3-5)
#   fig6     Expts 1-3 at the 5x lower rate of Fig. 6 (0.01 m/s instead of 0.05 m/s)
#   fig7     Expt 1 geometry with a 65 degree fault and salt 1000, 500, 250 m (paper Fig. 7;
#            the cover keeps its 1750 m)
#   seeds    Expt 1 with three more packing seeds (what is robust, what is one packing's)
#   study    quick Expt 1 changing one assumption at a time (docs/scenes.md)
#   contact  the paper's kind of salt (-var saltlaw contact, docs/scenes.md): expts, fig7 and
#            fig6 with disc-contact salt instead of the default Newtonian SPH salt
#   fv       the frictional-viscous salt (-var saltmodel paper, docs/scenes.md): Expts 1-3 at
#            both of Fig. 6's rates and fig7
#   eta100   Expts 1-3 with salt 100x more viscous than the paper states (5e10 Pa s, S x100 to
#            keep the Reynolds number): the Newtonian salt as strong as the paper's kind of salt
#            is under the scenes' overburden (docs/scenes.md), at both of Fig. 6's rates
#   syntectonic  Expt 1 with sedimentation that keeps filling the hanging-wall low (every 50 m
#            of slip, fill to the initial top of the section: examples/scene/sediment.in)
#            beside the plain Expt 1 (docs/beyond.md)
#   sections the sections beyond the paper's (examples/sections, docs/sections.md): three domino
#            basement faults, salt pinching out over a basement step on an extending margin, a
#            salt pillow under a two-unit cover
#   wedge    loading by a prograding wedge (examples/wedge.in): the front migrates 3 km at
#            0.317 m/s (10 km/Myr natural), filling behind it to 400 m above the initial top
#   3d       beyond the paper, in 3D (docs/3d.md): Expt 1 as a slab of spheres 250 m deep,
#            periodic along strike (expt1_3d), and a basement fault whose throw dies out along
#            strike: whole at z = 0, none from z = 1000 m on, between smooth end walls 1500 m
#            apart (fault_tip_3d); sections, outcomes and the cover's map view by examples/post3d.sh
#   gallery  everything docs/gallery.md shows: at quick expts, fig7, eta100, contact, seeds and fig6;
#            at medium Expt 1, Expt 3 and fig7
# PRESET: full (default: the paper's resolution), medium, quick, tiny.  Every run goes to the
# paper's 1000 m at the paper's physics (examples/scene/params.in).
# Output: out/SERIES_PRESET/NAME/ with the frames, log, figures/NAME.png, outcomes/outcomes.md,
# wall.txt and cmd.txt (the run's lmp command); OUT=DIR puts them under DIR instead of out/.
# SALTMODEL=paper runs any series with the paper's salt (-var saltmodel paper) into
# out/SERIES_PRESET_paper/.  A finished run (its 'done' file) is skipped; an interrupted one resumes from the newer of its
# restart files that matches its checksum (the older one if the newer is damaged); every segment
# of a run reads the scene files it started with (its copy in scene-files/).  LMP (default build/lmp) and
# MPIRUN (e.g. "mpirun -np 8") choose how lmp runs; ONLY="NAME ..." runs only those runs of
# the series (e.g. to split a series between cores: one run-series.sh per core, each with its
# own ONLY list).  DECKS=1 runs the paper's scenes from examples/expt*.in instead of their section
# descriptions (the same runs).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
series=${1:?usage: examples/run-series.sh expts|fig6|fig7|seeds|study|contact|fv|eta100|syntectonic|wedge|sections|gallery [full|medium|quick|tiny] [-- lmp args]}
preset=${2:-full}
shift $(( $# >= 2 ? 2 : 1 ))
[ "${1:-}" = "--" ] && shift
lmp=${LMP:-$root/build/lmp}
py=${SALTDEM_PYTHON:-/usr/bin/python3}
case $preset in full|medium|quick|tiny) ;;
  *) echo "run-series: preset '$preset' must be full, medium, quick or tiny" >&2; exit 2 ;;
esac

# name deck rate(m/s) [lmp -var arguments]
expts=("expt1 expt1 0.05" "expt2 expt2 0.05" "expt3 expt3 0.05")
fig6=("expt1_slow expt1 0.01" "expt2_slow expt2 0.01" "expt3_slow expt3 0.01")
fig7=("fig7_salt1000 expt1 0.05 -var dip 65 -var salt 1000"
      "fig7_salt500 expt1 0.05 -var dip 65 -var salt 500"
      "fig7_salt250 expt1 0.05 -var dip 65 -var salt 250")
seeds=("expt1_seed2 expt1 0.05 -var seed 2" "expt1_seed3 expt1 0.05 -var seed 3"
       "expt1_seed4 expt1 0.05 -var seed 4")
study=("base expt1 0.05" "endwall_smooth expt1 0.05 -var endwall smooth"
       "endwall_bonded expt1 0.05 -var endwall bonded" "rightwall_fixed expt1 0.05 -var rightwall fixed"
       "eta10x expt1 0.05 -var eta 5e9 -var S 40" "eta100x expt1 0.05 -var eta 5e10 -var S 400"
       "eta1000x expt1 0.05 -var eta 5e11 -var S 4000"
       "salt_contact expt1 0.05 -var saltlaw contact -var csalt_cal 0.5"
       "frame_damping expt1 0.05 -var eta 5e6 -var damping 5e4"
       "frame_damping_all expt1 0.05 -var eta 5e6 -var damping 5e4 -var damping_group all")
cs="-var saltlaw contact"
contact=("expt1_contact expt1 0.05 $cs" "expt3_contact expt3 0.05 $cs" "expt2_contact expt2 0.05 $cs"
         "fig7_salt1000_contact expt1 0.05 -var dip 65 -var salt 1000 $cs"
         "fig7_salt500_contact expt1 0.05 -var dip 65 -var salt 500 $cs"
         "fig7_salt250_contact expt1 0.05 -var dip 65 -var salt 250 $cs"
         "expt1_slow_contact expt1 0.01 $cs" "expt3_slow_contact expt3 0.01 $cs"
         "expt2_slow_contact expt2 0.01 $cs")
fvs="-var saltmodel paper"
fv=("expt1_fv expt1 0.05 $fvs" "expt2_fv expt2 0.05 $fvs" "expt3_fv expt3 0.05 $fvs"
    "expt1_slow_fv expt1 0.01 $fvs" "expt3_slow_fv expt3 0.01 $fvs" "expt2_slow_fv expt2 0.01 $fvs"
    "fig7_salt1000_fv expt1 0.05 -var dip 65 -var salt 1000 $fvs"
    "fig7_salt500_fv expt1 0.05 -var dip 65 -var salt 500 $fvs"
    "fig7_salt250_fv expt1 0.05 -var dip 65 -var salt 250 $fvs")
syntectonic=("expt1 expt1 0.05" "expt1_sedfill expt1 0.05 -var sediment fill")
wedge=("wedge wedge 0.317")
slab=250; [ "$preset" = tiny ] && slab=1000     # the tiny spheres need 1000 m (4 rmax)
threed=("expt1_3d expt1 0.05 -var dim 3 -var depth $slab"
        "fault_tip_3d expt1 0.05 -var dim 3 -var depth 1500 -var zends walls -var taper_from 0 -var taper_to 1000 -var restart_disp 20")
# sections (examples/sections/NAME.toml, written into a deck by python/saltdem-section)
sections=("domino section:domino 0.05" "pinchout section:pinchout 0.05" "pillow section:pillow 0.05")
eta100=("expt1_eta100x expt1 0.05 -var eta 5e10 -var S 400" "expt3_eta100x expt3 0.05 -var eta 5e10 -var S 400"
        "expt2_eta100x expt2 0.05 -var eta 5e10 -var S 400"
        "expt1_slow_eta100x expt1 0.01 -var eta 5e10 -var S 400"
        "expt3_slow_eta100x expt3 0.01 -var eta 5e10 -var S 400"
        "expt2_slow_eta100x expt2 0.01 -var eta 5e10 -var S 400")
runs=()
case $series in
  expts) runs=("${expts[@]}") ;;
  fig6)  runs=("${fig6[@]}") ;;
  fig7)  runs=("${fig7[@]}") ;;
  seeds) runs=("${seeds[@]}") ;;
  study) runs=("${study[@]}") ;;
  contact) runs=("${contact[@]}") ;;
  eta100) runs=("${eta100[@]}") ;;
  fv)    runs=("${fv[@]}") ;;
  syntectonic) runs=("${syntectonic[@]}") ;;
  wedge) runs=("${wedge[@]}") ;;
  sections) runs=("${sections[@]}") ;;
  3d)    runs=("${threed[@]}") ;;
  gallery)
    if [ "$preset" = medium ]; then runs=("expt1 expt1 0.05" "expt3 expt3 0.05" "${fig7[@]}")
    else runs=("${expts[@]}" "${fig7[@]}" "${eta100[@]}" "${contact[@]}" "${seeds[@]}" "${fig6[@]}"); fi ;;
  *) echo "run-series: series '$series' must be expts, fig6, fig7, seeds, study, contact, fv, eta100, syntectonic, wedge, sections, 3d or gallery" >&2; exit 2 ;;
esac
msuffix=""
case ${SALTMODEL:-} in
  ""|stated) ;;
  paper) for k in "${!runs[@]}"; do runs[$k]="${runs[$k]} -var saltmodel paper"; done
         msuffix=_paper ;;
  *) echo "run-series: SALTMODEL '$SALTMODEL' must be stated or paper" >&2; exit 2 ;;
esac

# The restart file to resume NAME from: the newest of the pair in DIR that matches its checksum
# (fix saltdem/checksum writes FILE.sha256 beside each).  A newer file that fails (damaged, or
# cut short by a kill while it was written) is passed over, and the runner says so.  Files without
# checksums (written before the decks made them) count only when neither file has one.  Nothing
# usable stops the series rather than start the run again over its frames.
pick_restart() {
  local dir=$1 deck=$2 name=$3 f any=0 bad=()
  local files
  files=$(cd "$dir" && ls -t "$deck".restart.a "$deck".restart.b 2>/dev/null || true)
  [ -z "$files" ] && return 0
  for f in $files; do [ -f "$dir/$f.sha256" ] && any=1; done
  for f in $files; do
    if [ "$any" = 0 ]; then echo "$f"; return 0; fi
    if [ -f "$dir/$f.sha256" ] && (cd "$dir" && sha256sum --status -c "$f.sha256" 2>/dev/null); then
      [ ${#bad[@]} -gt 0 ] && echo "run-series: $name: ${bad[*]} fails its checksum (damaged, or cut short while written): resuming from the older $f" >&2
      echo "$f"; return 0
    fi
    bad+=("$f")
  done
  echo "run-series: $name: no restart file in $dir matches its checksum (${bad[*]}): remove the directory to start the run again" >&2
  return 1
}

# The paper's scenes run from their section descriptions (examples/sections: the same
# trajectories as examples/expt*.in and wedge.in, bit for bit); the study's variants and the
# syntectonic series use deck variables the sections do not have, and keep the decks.
from_sections=1
case $series in study|syntectonic) from_sections=0 ;; esac
[ "${DECKS:-0}" = 1 ] && from_sections=0

for r in "${runs[@]}"; do
  read -r name deck rate vars <<< "$r"
  if [ "$from_sections" = 1 ]; then
    case $deck in
      expt1) if [[ " $vars " == *" -var dip 65 "* ]]; then deck=section:fig7; vars=${vars/-var dip 65/}
             else deck=section:expt1; fi ;;
      expt2|expt3|wedge) deck=section:$deck ;;
    esac
  fi
  [ -n "${ONLY:-}" ] && [[ " $ONLY " != *" $name "* ]] && continue
  out="$(realpath -m "${OUT:-$root/out}")/${series}_${preset}${msuffix}/$name"    # absolute: the run changes into it
  if [ -f "$out/done" ]; then echo "run-series: $name done already ($out)"; continue; fi
  mkdir -p "$out"
  resume=()
  from=$(pick_restart "$out" "${deck#section:}" "$name")    # (a section writes its restart files under its own name)
  [ -n "$from" ] && resume=(-var restart "$from")
  # the run reads its scene files (decks, includes, materials, packer) from its own copy, taken
  # at its first segment: an edit to the repository's files while it runs (LAMMPS reads an
  # include again at each jump of its frame loop) or between segments does not reach it
  snap=$out/scene-files
  if [ ! -d "$snap" ]; then
    rm -rf "$snap.tmp" && mkdir -p "$snap.tmp/examples" "$snap.tmp/tools"
    cp -r "$root/examples/scene" "$root"/examples/*.in "$snap.tmp/examples/"
    cp -r "$root/potentials" "$snap.tmp/" && cp "$root/tools/pack.in" "$snap.tmp/tools/"
    mv "$snap.tmp" "$snap"
  fi
  deckfile=$snap/examples/$deck.in
  if [[ $deck == section:* ]]; then
    deck=${deck#section:}
    [ -f "$out/$deck.in" ] && [ -n "$from" ] || \
      "$py" "$root/python/saltdem-section" "$root/examples/sections/$deck.toml" -o "$out/$deck.in" > /dev/null
    deckfile=$out/$deck.in
  fi
  echo "run-series: $name (${deckfile#"$out"/} -var rate $rate $vars ${resume[*]}) in $out"
  make=""
  [ "$deckfile" = "$out/$deck.in" ] && make="python/saltdem-section examples/sections/$deck.toml -o $deck.in && "
  lmpin=examples/$deck.in; [ -n "$make" ] && lmpin=$deck.in
  echo "${make}lmp -in $lmpin -var preset $preset -var rate $rate $vars $*" | tr -s ' ' | sed 's/ $//' > "$out/cmd.txt"
  start=$(date +%s)
  # segment number from the segments' own output (a killed one left its stdout but no wall time)
  seg=$(( $(find "$out" -maxdepth 1 -name 'stdout.*.txt' | wc -l) + 1 ))    # log.lammps, log.2.lammps, ...
  log=log.lammps; [ "$seg" -gt 1 ] && log=log.$seg.lammps
  # shellcheck disable=SC2086
  (cd "$out" && ${MPIRUN:-} "$lmp" -in "$deckfile" -var root "$snap" \
      -var preset "$preset" -var rate "$rate" $vars "${resume[@]}" -log "$log" "$@" > stdout.$seg.txt)
  echo "$(( $(date +%s) - start ))" >> "$out/wall_segments.txt"
  faults=(--fault-x 3125); [ "$deck" = expt2 ] && faults=(--fault-x 5000 7500)
  [ "$deck" = expt3 ] && faults=()
  scene=fault; [ "$deck" = expt2 ] && scene=keystone; [ "$deck" = expt3 ] && scene=tilted
  if [ "$deckfile" = "$out/$deck.in" ]; then    # a section: its faults from its description
    read -r -a fx <<< "$("$py" "$root/python/saltdem-section" "$root/examples/sections/$deck.toml" --faults)"
    faults=(--types "$("$py" "$root/python/saltdem-section" "$root/examples/sections/$deck.toml" --types)")
    scene=tilted
    [ ${#fx[@]} -gt 0 ] && { faults+=(--fault-x "${fx[@]}"); scene=fault; }
    [ "$deck" = expt2 ] && scene=keystone
  fi
  # the wedge: no basement fault (measured as a scene without one), its stages are the front's
  # migration, the incremental strain over 250 m of it
  [ "$deck" = wedge ] && { faults=(--increment 250 --at 500 1000 1500 2000 3000); scene=tilted; }
  # 3D: sections at z = depth/2 and 0 of a periodic slab, or at five planes between end walls
  args3d=" $vars $* "
  is3d=0; [[ $args3d == *" -var dim 3 "* ]] && is3d=1
  if [ "$is3d" = 1 ]; then
    depth=$(sed -n 's/.* -var depth \([0-9.e+]*\) .*/\1/p' <<< "$args3d")
    if [[ $args3d == *" -var zends walls "* ]]; then
      zs=$("$py" -c "print(' '.join(f'{$depth * (k + 0.5) / 5:g}' for k in range(5)))")
    else
      zs=$("$py" -c "print(f'{$depth / 2:g} 0')")
    fi
    RATE=$rate "$root/examples/post3d.sh" "$out" "$deck" "$zs" "${faults[@]}"
  else
    "$py" "$root/python/saltdem-post" figure "$out/dump.$deck.*.txt" -o "$out/figures" \
        --name "$name.png" --title "$name ($preset, $rate m/s)" --rate "$rate" "${faults[@]}" -q
    "$py" "$root/python/saltdem-post" outcomes "$out/dump.$deck.*.txt" -o "$out/outcomes" \
        --rate "$rate" "${faults[@]}" --scene "$scene" -q
  fi
  awk '{s += $1} END {print s}' "$out/wall_segments.txt" > "$out/wall.txt"
  touch "$out/done"
  if [ "$is3d" = 1 ]; then echo "run-series: $name: sections, outcomes and figures in $out/post3d"
  else echo "run-series: $name: figure $out/figures/$name.png, outcomes $out/outcomes/outcomes.md"; fi
done
