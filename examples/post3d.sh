#!/usr/bin/env bash
# Sections, outcomes, figures and the cover's map view of a 3D run (docs/3d.md).
#
#   examples/post3d.sh RUN_DIR NAME "Z ..." [saltdem-post outcomes/figure options, e.g. --fault-x 3125]
#
# RUN_DIR holds the run's frames dump.NAME.STEP.txt.  Each section is the slab of spheres within
# one median diameter's half-width of the plane z = Z, written as 2D frames (saltdem-post
# section3d), on which the 2D tools run as on a 2D run.  Writes RUN_DIR/post3d/: sections/,
# outcomes_zZ/ (outcomes.md, outcomes.json), figures/NAME_zZ.png, and mapview.png/.json (the
# cover's top from the first frame to the last).  RATE (default 0.05) is the drive rate in m/s;
# Python: /usr/bin/python3 or $PYTHON.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
run=$(cd "${1:?usage: post3d.sh RUN_DIR NAME \"Z ...\" [options]}" && pwd)
name=${2:?usage: post3d.sh RUN_DIR NAME \"Z ...\" [options]}
read -r -a zs <<< "${3:?usage: post3d.sh RUN_DIR NAME \"Z ...\" [options]}"
shift 3
py=${PYTHON:-/usr/bin/python3}
post="$root/python/saltdem-post"
rate=${RATE:-0.05}
out="$run/post3d"
compgen -G "$run/dump.$name.*.txt" > /dev/null || {
  echo "post3d: no frames dump.$name.*.txt in $run" >&2; exit 1; }
mkdir -p "$out"
"$py" "$post" section3d "$run/dump.$name.*.txt" --z "${zs[@]}" -o "$out/sections" -q
for z in "${zs[@]}"; do
  # Z as section3d writes it in its file names
  z=$("$py" -c "import numpy; print(numpy.format_float_positional(float('$z'), trim='-'))")
  "$py" "$post" outcomes "$out/sections/dump.$name.*_z$z.txt" -o "$out/outcomes_z$z" \
      --rate "$rate" --title "$name, section z = $z m" -q "$@"
  "$py" "$post" figure "$out/sections/dump.$name.*_z$z.txt" -o "$out/figures" \
      --name "${name}_z$z.png" --title "$name, section z = $z m ($rate m/s)" --rate "$rate" -q "$@"
done
mapfile -t frames < <(ls "$run"/dump."$name".*.txt | sort -t. -k3 -n)
"$py" "$post" mapview "${frames[0]}" "${frames[-1]}" -o "$out/mapview.png" --json "$out/mapview.json"
echo "post3d: $out"
