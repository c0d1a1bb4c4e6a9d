#!/bin/sh
# bench_quality.sh: shell tests of the quality benchmark's own reporting
# (tests/bench/bench_quality.c) on two psb-dev models.
#   tests/integration/bench_quality.sh BUILD     uses BUILD/bench/bench_quality
# --out then --against the same labels must report no change; against
# every vertex in one segment (--baseline none) the default must be better
# on both models; --dev-only must print "-" for the absent validation
# split, never nan; --out makes missing parent folders; people among
# themselves are printed; the uneven:N mode runs; the seen:N and view:N
# modes score only what their views see (fewer vertices from one view
# than from six, people's figure per mode); --seeds 3 prints the draws'
# agreement.  SKIP (loud) without ../shared/data/psb-dev.  Prints
# "PASS bench_quality:NAME" / "FAIL ..."; exits 1 on any failure.
SUITE=bench_quality
. "$(dirname "$0")/lib.sh"
BQ=$BUILD/bench/bench_quality
DATA=${POINTSEG_SHARED:-../shared/data}/psb-dev

if [ ! -x "$BQ" ]; then
    fail setup "$BQ is not built"
    exit 1
fi
if [ ! -d "$DATA/off" ]; then
    skip all "no PSB data at $DATA (the shared folder beside the checkout)"
    exit 0
fi

# bq ARGS...: bench_quality on models 1 and 2 of psb-dev, vertices, auto only.
bq() {
    "$BQ" "$DATA" --ids 1,2 --single --dev-only "$@"
}

# change_line OUTPUT: the vertices row of the --against table.
change_line() {
    sed -n '/^== change of 1-RI against/,$p' "$1" | grep '^vertices '
}

if bq --out "$tmp/auto" >"$tmp/first.txt" 2>&1 && bq --against "$tmp/auto" >"$tmp/same.txt" 2>&1; then
    line=$(change_line "$tmp/same.txt")
    case $line in
    *"+0.0000 +- 0.0000 (  2:   0 better,   0 worse; categories  0 /  0)"*) pass against_itself ;;
    *) fail against_itself "expected no change, got: $line" ;;
    esac
else
    fail against_itself "bench_quality failed: $(tail -n 3 "$tmp/first.txt" "$tmp/same.txt")"
fi

if bq --baseline none --out "$tmp/none" >/dev/null 2>&1 && bq --against "$tmp/none" >"$tmp/vs_none.txt" 2>&1; then
    line=$(change_line "$tmp/vs_none.txt")
    case $line in
    "vertices         -0."*"(  2:   2 better,   0 worse; categories  1 /  0)"*) pass against_one_segment ;;
    *) fail against_one_segment "expected both models better than one segment, got: $line" ;;
    esac
else
    fail against_one_segment "bench_quality failed: $(tail -n 3 "$tmp/vs_none.txt")"
fi

if grep -qiw -e nan -e inf "$tmp/first.txt"; then
    fail dev_only_no_nan "--dev-only printed nan or inf: $(grep -iw -e nan -e inf "$tmp/first.txt" | head -n 2)"
elif grep -q '^vertices  *auto  *0\.[0-9]* (  2)  *- (  0)' "$tmp/first.txt"; then
    pass dev_only_no_nan
else
    fail dev_only_no_nan "no '-' for the validation mean: $(grep '^vertices' "$tmp/first.txt" | head -n 1)"
fi

if bq --against "$tmp/missing" >"$tmp/missing.txt" 2>&1 &&
    change_line "$tmp/missing.txt" | grep -q -- '- (no earlier labels)'; then
    pass against_missing_folder
else
    fail against_missing_folder "$(change_line "$tmp/missing.txt")"
fi

if bq --baseline none --out "$tmp/a/b/c" >/dev/null 2>&1 && [ -s "$tmp/a/b/c/1.vertices.lab" ]; then
    pass out_makes_parents
else
    fail out_makes_parents "no $tmp/a/b/c/1.vertices.lab"
fi

# --seeds 3: the draws' agreement, a disagreement and two scores in [0, 1].
if bq --input surface:5000 --seeds 3 >"$tmp/seeds.txt" 2>&1 &&
    sed -n '/^== agreement of the 3 draws/,$p' "$tmp/seeds.txt" |
    grep -q '^surface:5000  *0\.[0-9]\{4\}; medoid 0\.[0-9]\{4\}, draw 0\.[0-9]\{4\} (  2)  *-'; then
    pass seeds_agreement
else
    fail seeds_agreement "$(sed -n '/^== agreement/,$p' "$tmp/seeds.txt" | head -n 3)"
fi

if grep -q '^people among themselves .*: development 0\.[0-9]\{4\} (2)$' "$tmp/first.txt"; then
    pass people_among_themselves
else
    fail people_among_themselves "$(grep '^people' "$tmp/first.txt" || echo 'no people line')"
fi

if bq --input uneven:20000 --out "$tmp/uneven" >"$tmp/uneven.txt" 2>&1 &&
    grep -q '^uneven:20000  *auto  *0\.[0-9]* (  2)' "$tmp/uneven.txt" &&
    [ -s "$tmp/uneven/1.uneven:20000.lab" ]; then
    pass uneven_mode
else
    fail uneven_mode "$(tail -n 3 "$tmp/uneven.txt")"
fi

# seen:N and view:N: labels for the seen vertices alone, fewer from the
# front than from six sides, and people among themselves once per mode.
if bq --input seen:20000 --input view:20000 --out "$tmp/seen" >"$tmp/seen.txt" 2>&1 &&
    grep -q '^seen:20000  *auto  *0\.[0-9]* (  2)' "$tmp/seen.txt" &&
    grep -q '^view:20000  *auto  *0\.[0-9]* (  2)' "$tmp/seen.txt" &&
    [ "$(grep -c '^people among themselves .* on [a-z]*:20000: development 0\.[0-9]\{4\} (2)$' "$tmp/seen.txt")" -eq 2 ]; then
    six=$(wc -w <"$tmp/seen/1.seen:20000.lab")
    front=$(wc -w <"$tmp/seen/1.view:20000.lab")
    if [ "$front" -gt 0 ] && [ "$front" -lt "$six" ]; then
        pass seen_and_view_modes
    else
        fail seen_and_view_modes "labels of model 1: $six seen from six sides, $front from the front"
    fi
else
    fail seen_and_view_modes "$(tail -n 3 "$tmp/seen.txt")"
fi

[ "$failures" -eq 0 ]
