#!/bin/sh
# cli.sh: shell tests of the built `pointseg` tool (clients/cli/).
#   tests/integration/cli.sh BUILD     uses BUILD/pointseg
# Writes two separated spheres (awk, golden-spiral points) as XYZ and a JSON
# body, segments them in every output format, and checks help, version,
# usage errors and bad input.  Prints "PASS cli:NAME" / "FAIL cli:NAME: why"
# / "SKIP cli:NAME: why" like tests/support/testlib.h; exits 1 on any failure.
SUITE=cli
. "$(dirname "$0")/lib.sh"
N_PER_SPHERE=200
N=$((2 * N_PER_SPHERE))

if [ ! -x "$PS" ]; then
    fail setup "$PS is not built"
    exit 1
fi

# Two unit spheres 5 apart, N_PER_SPHERE points each: rows "x y z".
awk -v m="$N_PER_SPHERE" 'BEGIN {
    pi = atan2(0, -1); golden = pi * (3 - sqrt(5));
    for (s = 0; s < 2; s++) for (i = 0; i < m; i++) {
        y = 1 - 2 * (i + 0.5) / m; r = sqrt(1 - y * y); t = golden * i;
        printf "%.6f %.6f %.6f\n", 5 * s + r * cos(t), y, r * sin(t);
    }
}' >"$tmp/spheres.xyz"

# The same points as a JSON body asking for labels.
awk 'BEGIN { printf "{\"points\": [" }
     { printf "%s[%s,%s,%s]", (NR > 1 ? "," : ""), $1, $2, $3 }
     END { printf "], \"params\": {\"output\": \"labels\", \"k\": 8}}\n" }' \
    "$tmp/spheres.xyz" >"$tmp/body.json"

# run NAME CMD...: runs CMD, stdout to $tmp/NAME.out, stderr to $tmp/NAME.err,
# status in $rc.
run() {
    name=$1
    shift
    "$@" >"$tmp/$name.out" 2>"$tmp/$name.err"
    rc=$?
}

# expect_usage_error NAME PATTERN CMD...: exit 2 and a "pointseg: " message
# on stderr matching PATTERN, nothing on stdout.
expect_usage_error() {
    name=$1 pattern=$2
    shift 2
    run "$name" "$@"
    if [ "$rc" -ne 2 ]; then
        fail "$name" "exit status $rc, expected 2"
    elif ! grep -q "^pointseg: .*$pattern" "$tmp/$name.err"; then
        fail "$name" "stderr lacks '$pattern': $(head -c 200 "$tmp/$name.err")"
    elif [ -s "$tmp/$name.out" ]; then
        fail "$name" "wrote to stdout"
    else
        pass "$name"
    fi
}

test_help() {
    for cmd in "--help" "segment --help"; do
        # shellcheck disable=SC2086
        run help $PS $cmd
        if [ "$rc" -ne 0 ]; then
            fail "help" "'pointseg $cmd' exit status $rc"
            return
        fi
        for p in k centrality samples persistence ncut-threshold feature-threshold minima f2 threads \
                 output include; do
            if ! grep -q -- "--$p" "$tmp/help.out"; then
                fail "help" "'pointseg $cmd' does not list --$p"
                return
            fi
        done
        if ! grep -A2 -- "--ncut-threshold" "$tmp/help.out" | grep -q "default 0)"; then
            fail "help" "'pointseg $cmd' does not show the ncut_threshold default"
            return
        fi
    done
    pass "help"
}

test_version() {
    run version "$PS" --version
    if [ "$rc" -eq 0 ] && grep -q '^pointseg [0-9][0-9.]*$' "$tmp/version.out"; then
        pass "version"
    else
        fail "version" "exit $rc, output '$(cat "$tmp/version.out")'"
    fi
}

# Labels: one per point, and the two spheres (separate kNN components)
# share no segment.
test_labels() {
    run labels "$PS" segment "$tmp/spheres.xyz" --output labels
    if [ "$rc" -ne 0 ]; then
        fail "labels" "exit status $rc: $(head -c 200 "$tmp/labels.err")"
        return
    fi
    count=$(wc -l <"$tmp/labels.out")
    if [ "$count" -ne "$N" ]; then
        fail "labels" "$count labels for $N points"
        return
    fi
    shared=$(awk -v m="$N_PER_SPHERE" '
        NR <= m { a[$1] = 1 } NR > m && ($1 in a) { s++ } END { print s + 0 }' \
        "$tmp/labels.out")
    if [ "$shared" -ne 0 ]; then
        fail "labels" "$shared points of the second sphere share a label with the first"
    elif ! grep -qv '^[0-9][0-9]*$' "$tmp/labels.out"; then
        pass "labels"
    else
        fail "labels" "a line is not a label: $(grep -v '^[0-9][0-9]*$' "$tmp/labels.out" | head -1)"
    fi
}

test_json() {
    if ! command -v python3 >/dev/null 2>&1; then
        skip "json" "python3 not found"
        return
    fi
    run json "$PS" segment "$tmp/spheres.xyz" --include=centrality,point-supernode
    if [ "$rc" -ne 0 ]; then
        fail "json" "exit status $rc: $(head -c 200 "$tmp/json.err")"
        return
    fi
    if msg=$(python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
n = int(sys.argv[2])
assert d["n_points"] == n and d["dimension"] == 3, "n_points/dimension"
for key in ("labels", "centrality", "point_supernode"):
    assert len(d[key]) == n, key + " length"
assert d["n_segments"] == len(d["segments"]) >= 2, "segments"
assert d["params"]["k"] == 7, "params.k"
for key in ("supernodes", "hierarchy", "merges", "timings_ms"):
    assert key in d, key
' "$tmp/json.out" "$N" 2>&1); then
        pass "json"
    else
        fail "json" "$(echo "$msg" | tail -1)"
    fi
}

test_ply() {
    run ply "$PS" segment "$tmp/spheres.xyz" --output ply -o "$tmp/out.ply"
    if [ "$rc" -ne 0 ] || [ -s "$tmp/ply.out" ]; then
        fail "ply" "exit status $rc, or output on stdout despite -o"
        return
    fi
    header=$(head -c 400 "$tmp/out.ply" | awk '/^end_header/ { exit } { print }')
    size=$(wc -c <"$tmp/out.ply")
    header_size=$(($(printf '%s\nend_header\n' "$header" | wc -c)))
    if [ "$(printf '%s\n' "$header" | head -1)" != "ply" ]; then
        fail "ply" "does not start with 'ply'"
    elif ! printf '%s\n' "$header" | grep -q "^element vertex $N\$"; then
        fail "ply" "header lacks 'element vertex $N'"
    elif [ "$size" -ne $((header_size + N * 15)) ]; then
        fail "ply" "$size bytes, expected $((header_size + N * 15))"
    else
        pass "ply"
    fi
}

# stdin gives the same labels as the file; a JSON body's params apply, and
# flags override them.
test_stdin_and_body_params() {
    run stdin "$PS" segment - --output labels <"$tmp/spheres.xyz"
    if [ "$rc" -ne 0 ] || ! cmp -s "$tmp/stdin.out" "$tmp/labels.out"; then
        fail "stdin" "exit status $rc or labels differ from the file's"
        return
    fi
    pass "stdin"
    run body "$PS" segment "$tmp/body.json"
    if [ "$rc" -ne 0 ] || [ "$(wc -l <"$tmp/body.out")" -ne "$N" ]; then
        fail "body_params" "exit status $rc or not $N labels from a body asking for labels"
        return
    fi
    run body_flag "$PS" segment "$tmp/body.json" --output json
    if [ "$rc" -eq 0 ] && head -c 1 "$tmp/body_flag.out" | grep -q '{' &&
        grep -q '"k":8' "$tmp/body_flag.out"; then
        pass "body_params"
    else
        fail "body_params" "flag --output json did not override the body, or body k=8 lost"
    fi
}

# A PLY header line without a keyword, as Blender 2.4x writes, is skipped
# with a warning on stderr and in the JSON document; the labels are those
# of the same file without that line.
test_header_line_without_keyword() {
    {
        printf 'ply\nformat ascii 1.0\n'
        printf 'Created by Blender3D 247 - www.blender.org, source file: spheres.blend\n'
        printf 'element vertex %d\nproperty float x\nproperty float y\nproperty float z\n' "$N"
        printf 'end_header\n'
        cat "$tmp/spheres.xyz"
    } >"$tmp/blender.ply"
    run blender "$PS" segment "$tmp/blender.ply"
    if [ "$rc" -ne 0 ]; then
        fail "ply_header_warning" "exit status $rc: $(head -c 200 "$tmp/blender.err")"
    elif ! grep -q "^pointseg: warning: .*blender.ply: PLY header line 3 skipped: no keyword in \"Created by Blender3D 247" \
        "$tmp/blender.err"; then
        fail "ply_header_warning" "no warning on stderr: $(head -c 200 "$tmp/blender.err")"
    elif ! python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
labels = [int(l) for l in open(sys.argv[2])]
assert len(d["warnings"]) == 1 and d["warnings"][0].startswith("PLY header line 3 skipped"), d["warnings"]
assert d["labels"] == labels, "labels differ from the XYZ file without the header"
' "$tmp/blender.out" "$tmp/labels.out" 2>"$tmp/blender.py"; then
        fail "ply_header_warning" "$(tail -1 "$tmp/blender.py")"
    else
        pass "ply_header_warning"
    fi
}

test_errors() {
    printf 'this is not a point set\n' >"$tmp/bad.txt"
    expect_usage_error bad_input "bad.txt: " "$PS" segment "$tmp/bad.txt"
    expect_usage_error missing_file "nothere.xyz: " "$PS" segment "$tmp/nothere.xyz"
    expect_usage_error unknown_flag "--frobnicate" "$PS" segment "$tmp/spheres.xyz" --frobnicate
    expect_usage_error bad_value "parameter 'k' must be an integer in \[1, 64\], got 'abc'" \
        "$PS" segment "$tmp/spheres.xyz" --k abc
    expect_usage_error missing_value "--k" "$PS" segment "$tmp/spheres.xyz" --k
    expect_usage_error no_input "no INPUT" "$PS" segment
    expect_usage_error unknown_command "frob" "$PS" frob
    expect_usage_error server "needs --server" "$PS" segment "$tmp/spheres.xyz" --async
}

test_help
test_version
test_labels
test_json
test_ply
test_stdin_and_body_params
test_header_line_without_keyword
test_errors
[ "$failures" -eq 0 ]
