#!/bin/sh
# make_figures.sh [BUILD]: renders docs/figures/compare.png, a few PSB dev
# models side by side: a human segmentation, pointseg's default method
# (auto) and the paper's method.  Needs ../shared/data/psb-dev and a build.
set -eu
BUILD=${1:-build}
PSB=${POINTSEG_SHARED:-../shared/data}/psb-dev
OUT=docs/figures
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
[ -d "$PSB" ] || { echo "SKIP: $PSB not found"; exit 0; }
# id and a view direction that shows its parts (--view X,Y,Z --up X,Y,Z)
set -- "1 0,0,1 0,1,0" "181 0,0,1 0,1,0" "381 0,0,1 0,1,0" "21 0,0,1 0,1,0" "61 0,1,0 0,0,1"
list=""
for model in "$@"; do
    set -- $model
    id=$1 view=$2 up=$3
    python3 "$OUT/seg_to_ply.py" "$PSB/off/$id.off" "$PSB/seg/$id/${id}_0.seg" "$tmp/$id-human.ply"
    "$BUILD/pointseg" segment "$PSB/off/$id.off" --output ply -o "$tmp/$id-auto.ply"
    "$BUILD/pointseg" segment "$PSB/off/$id.off" --method paper --output ply -o "$tmp/$id-paper.ply"
    for kind in human auto paper; do
        "$BUILD/pointseg" render "$tmp/$id-$kind.ply" -o "$tmp/$id-$kind.png" \
            --width 320 --height 320 --view "$view" --up "$up"
        list="$list $tmp/$id-$kind.png"
    done
done
# shellcheck disable=SC2086
python3 "$OUT/grid_png.py" 3 "$OUT/compare.png" $list
echo "wrote $OUT/compare.png (columns: human, auto, paper)"
