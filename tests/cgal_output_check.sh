#!/usr/bin/env bash
# dtlab check on CGAL's output: CGAL's Delaunay triangulation (cgal_baseline --ele) of every
# point set dtlab gen makes that has a triangle must check as a valid Delaunay triangulation
# (exit 0), and the same file with one triangle turned clockwise must not (exit 1, naming it).
#   usage: cgal_output_check.sh DTLAB CGAL_BASELINE WORKDIR
set -uo pipefail
dtlab=$1 cgal=$2 dir=$3
mkdir -p "$dir"
failed=0
kinds="uniform clusters grid rotated-grid ngon circle collinear near-duplicates huge-tiny-box
       gaussian uneven-clusters kuzmin log-radial disc-in-box curves parabola facing-arcs spiral
       convex-hull"
for kind in $kinds; do
    base=$dir/$kind
    "$dtlab" gen "$kind" 3000 --seed 5 -o "$base.xy" >/dev/null || { echo "gen $kind failed"; failed=1; continue; }
    if ! "$cgal" "$base.xy" --repeat 1 --ele "$base" >/dev/null; then
        echo "FAIL $kind: cgal_baseline --ele failed"; failed=1; continue
    fi
    out=$("$dtlab" check "$base.ele" 2>&1); rc=$?
    if [[ $rc != 0 || $out != *"Delaunay"* ]]; then
        echo "FAIL $kind: dtlab check exit $rc: $(head -3 <<<"$out")"; failed=1
    else
        echo "ok   $kind: $(head -1 <<<"$out")"
    fi
done
# The control: swap two vertices of the first triangle; the check must fail and name it.
base=$dir/uniform
awk 'NR == 2 { t = $3; $3 = $4; $4 = t } { print }' "$base.ele" > "$dir/turned.ele"
cp "$base.node" "$dir/turned.node"
out=$("$dtlab" check "$dir/turned.ele" 2>&1); rc=$?
if [[ $rc != 1 || $out != *"clockwise"* ]]; then
    echo "FAIL control: a clockwise triangle gave exit $rc: $(head -3 <<<"$out")"; failed=1
else
    echo "ok   control: $(head -1 <<<"$out")"
fi
exit $failed
