#!/bin/bash
# The full Expt 1 run's figure, outcomes and gallery section, from its run directory.
#
#   bash bench/segments/expt1_full_run/finish.sh RUN_DIR [--splice]
#
# RUN_DIR: where the segments ran (the README's out/full); its frames dump.expt1.STEP.txt and
# the kept ones (expt1_full_run/frames/*.gz under $SALTDEM_SEGMENTS, default
# ~/.cache/saltdem/segments: not in git, the README; unpacked where RUN_DIR lacks them) are read.  Writes the
# gallery's run directory out/gallery_full/expt1_full (links to the frames, figures/,
# outcomes/, cmd.txt, wall.txt: the sum of wall_segments.txt here).  With --splice the
# gallery's expt1_full row and sections in docs/gallery.md and docs/gallery/runs.md are replaced
# by this run's (tools/docs/gallery_page.py --splice)
# (the notes' '## expt1_full' lines, docs/gallery/notes.md, say what it shows: edit them
# first).  Run from anywhere; Python: /usr/bin/python3 or $PYTHON.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
run=$(cd "${1:?usage: finish.sh RUN_DIR [--splice]}" && pwd)
splice=${2:-}
py=${PYTHON:-/usr/bin/python3}
post="$root/python/saltdem-post"
out="$root/out/gallery_full/expt1_full"

segs=${SALTDEM_SEGMENTS:-${SALTDEM_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/saltdem}/segments}
mkdir -p "$out"
if compgen -G "$segs/expt1_full_run/frames/dump.expt1.*.txt.gz" > /dev/null; then
  for gz in "$segs"/expt1_full_run/frames/dump.expt1.*.txt.gz; do
    f=$(basename "$gz" .gz)
    [ -f "$run/$f" ] || gunzip -c "$gz" > "$run/$f"
  done
else
  echo "finish: no kept frames in $segs/expt1_full_run/frames (they are not in git; set" \
       "SALTDEM_SEGMENTS): using only the frames in $run" >&2
fi
compgen -G "$run/dump.expt1.*.txt" > /dev/null || {
  echo "finish: no frames dump.expt1.*.txt in $run: run the full Expt 1 first (the README)" >&2; exit 1; }
rm -f "$out"/dump.expt1.*.txt
ln -s "$run"/dump.expt1.*.txt "$out"/
echo "mpirun -np 2 lmp -in examples/expt1.in -var preset full -var restart_disp 25" > "$out/cmd.txt"
awk '$1 ~ /^[0-9]+$/ {s += $1} END {print s}' "$here/wall_segments.txt" > "$out/wall.txt"
"$py" "$post" figure "$out/dump.expt1.*.txt" -o "$out/figures" --name expt1_full.png \
    --title "expt1_full (full, 0.05 m/s)" --rate 0.05 --fault-x 3125 -q
"$py" "$post" outcomes "$out/dump.expt1.*.txt" -o "$out/outcomes" --rate 0.05 --fault-x 3125 \
    --scene fault -q
echo "finish: $out (wall $(cat "$out/wall.txt") s)"
[ "$splice" = --splice ] || exit 0

# its row and section in docs/gallery.md and its section in docs/gallery/runs.md replace the old
"$py" "$root/tools/docs/gallery_page.py" "$out" --notes "$root/docs/gallery/notes.md" \
    -o "$root/docs/gallery.md" --splice
