#!/usr/bin/env bash
# Sort and raster time of two tetrender builds on one scene, run alternately in the same session
# (this machine is noisy: compare the ratio, not the times), with the median of each.
#
#   bench/render_ab.sh OLD_TETRENDER NEW_TETRENDER SCENE [RUNS] [-- extra render options]
#
# Prints one line per run and a summary: median sort, raster, sort + raster (ms) per build and
# the ratio old / new. Each run renders SCENE with --stats to a temporary PNG; the two builds'
# pictures are compared byte for byte at the end (a difference is reported, not an error).
set -euo pipefail
if [[ $# -lt 3 ]]; then
    sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
    exit 2
fi
old=$1 new=$2 scene=$3
runs=${4:-5}
shift $(($# < 4 ? $# : 4))
[[ ${1:-} == -- ]] && shift
extra=("$@")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
stat() { sed -n "s/.*\"$1\":\([0-9.]*\).*/\1/p" "$2"; }
for ((r = 0; r < runs; ++r)); do
    for which in old new; do
        bin=$old
        [[ $which == new ]] && bin=$new
        "$bin" render "$scene" -o "$tmp/$which.png" --stats "${extra[@]}" >"$tmp/$which.json"
        sort_ms=$(stat sort_ms "$tmp/$which.json")
        raster_ms=$(stat raster_ms "$tmp/$which.json")
        echo "$which $sort_ms $raster_ms" | tee -a "$tmp/all"
    done
done
python3 - "$tmp/all" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
med = {}
for which in ("old", "new"):
    s = [float(r[1]) for r in rows if r[0] == which]
    t = [float(r[2]) for r in rows if r[0] == which]
    both = [a + b for a, b in zip(s, t)]
    med[which] = statistics.median(both)
    print(f"{which}: sort {statistics.median(s):.0f} ms, raster {statistics.median(t):.0f} ms, "
          f"sort + raster {med[which]:.0f} ms (median of {len(s)})")
print(f"old / new: {med['old'] / med['new']:.2f}")
PY
if cmp -s "$tmp/old.png" "$tmp/new.png"; then echo "pictures: identical"; else echo "pictures: differ"; fi
