#!/bin/sh
# run.sh: builds the fuzz targets (the decoders, the daemon's multipart
# path, whole requests to the daemon, the --redis URL parser, and the core
# on small point sets of its own) with
# libFuzzer + ASan + UBSan and runs each on a copy of its seed
# corpus.
#   tests/fuzz/run.sh BUILD [short|long]   20 s per target (short; FUZZ_SECONDS
#                                          overrides it) or 600 s (long);
#                                          FUZZ_TARGETS="ply json" runs only those;
#                                          FUZZ_JOBS targets at a time (default:
#                                          one per core; each fuzzer is one process)
# Targets build with the Makefile's warning flags (WARN).
# Prints "PASS fuzz:<target>", "FAIL fuzz:<target>: <reason>" or
# "SKIP fuzz:<target>: <reason>" per target; exits non-zero on any failure.
# Crash inputs are kept in BUILD/fuzz/<target>-crash-*.
set -u
BUILD=${1:-build}
MODE=${2:-short}
TARGETS="${FUZZ_TARGETS:-ply json text multipart head redis_url segment}"
case "$MODE" in
short) SECONDS_EACH=${FUZZ_SECONDS:-20} ;;
long) SECONDS_EACH=600 ;;
*) echo "usage: $0 BUILD [short|long]" >&2; exit 2 ;;
esac
cd "$(dirname "$0")/../.." || exit 2

if ! command -v clang >/dev/null 2>&1; then
    for t in $TARGETS; do echo "SKIP fuzz:$t: clang is not installed"; done
    exit 0
fi

# The decoder targets: only the decoders and what they need; no core, no daemon.
DECODER_SOURCES="api/api_error.c api/pointset.c $(ls api/decode*.c)"
DECODER_LIBS="$(pkg-config --cflags --libs libcjson) -lm"
# segment: the core alone.
CORE_SOURCES="$(ls core/*.c core/*/*.c)"
CORE_LIBS="-lflann $(pkg-config --cflags --libs lapacke) -lopenblas -lm -pthread"
# multipart, head: the daemon's HTTP layer in-process, so the core and
# everything of the daemon but its main.
DAEMON_SOURCES="$CORE_SOURCES $(ls api/*.c server/*.c | grep -v '^server/main\.c$') tests/fuzz/daemon_harness.c"
DAEMON_LIBS="$CORE_LIBS $(pkg-config --cflags --libs libmicrohttpd libcjson zlib hiredis)"
# redis_url: the URL parser and the connection code it lives with.
REDIS_SOURCES="server/redis_link.c"
REDIS_LIBS="$(pkg-config --cflags --libs hiredis) -pthread"
# The project's warning flags, from the Makefile (the one list of them).
WARN=$(sed -n 's/^WARN := //p' Makefile)
OUT="$BUILD/fuzz"
mkdir -p "$OUT/obj"
JOBS=${FUZZ_JOBS:-$(getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
# The compile flags every object takes; headers of the libraries too.
FUZZ_CFLAGS="-std=c11 -D_POSIX_C_SOURCE=200809L $WARN -g -O1 -fno-sanitize-recover=undefined \
 -Icore -Iapi -Iapi/private -Iserver -Itests/fuzz \
 $(pkg-config --cflags libcjson lapacke libmicrohttpd zlib hiredis)"
export FUZZ_CFLAGS OUT

# The object of source $1 (instrumented for the fuzzers, not linked with them).
object_of() { echo "$OUT/obj/$(echo "$1" | tr / _ | sed 's/\.c$/.o/')"; }

# Sets sources and libs to target $1's.
sources_of() {
    case "$1" in
    multipart | head) sources=$DAEMON_SOURCES libs=$DAEMON_LIBS ;;
    redis_url) sources=$REDIS_SOURCES libs=$REDIS_LIBS ;;
    segment) sources=$CORE_SOURCES libs=$CORE_LIBS ;;
    *) sources=$DECODER_SOURCES libs=$DECODER_LIBS ;;
    esac
}

# Compiles once each source the targets need, JOBS at a time; 0 or non-zero
# with the log in $OUT/objects.log.
# shellcheck disable=SC2016 # the xargs child's shell expands $1, $2
compile_objects() {
    needed=""
    for t in $TARGETS; do
        sources_of "$t"
        needed="$needed $sources"
    done
    # shellcheck disable=SC2086
    for src in $(printf '%s\n' $needed | sort -u); do
        echo "$src $(object_of "$src")"
    done | xargs -n 2 -P "$JOBS" sh -c \
        'clang $FUZZ_CFLAGS -fsanitize=fuzzer-no-link,address,undefined -c "$1" -o "$2"' sh \
        >"$OUT/objects.log" 2>&1
}

# Links target $1 from its sources' objects; 0 or non-zero with the log.
link_target() {
    sources_of "$1"
    objects=""
    for src in $sources; do objects="$objects $(object_of "$src")"; done
    # shellcheck disable=SC2086
    clang $FUZZ_CFLAGS -fsanitize=fuzzer,address,undefined "tests/fuzz/fuzz_$1.c" $objects $libs \
        -o "$OUT/fuzz_$1" >"$OUT/fuzz_$1.log" 2>&1
}

# Fuzzes target $1 (built); its one result line goes to $OUT/fuzz_$1.result.
fuzz_target() {
    t=$1
    log="$OUT/fuzz_$t.log"
    corpus="$OUT/corpus_$t"
    rm -rf "$corpus"
    mkdir -p "$corpus"
    cp tests/fuzz/seeds/"$t"/* "$corpus"/ 2>/dev/null
    if "$OUT/fuzz_$t" -max_total_time="$SECONDS_EACH" -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=0 -artifact_prefix="$OUT/fuzz_$t-" "$corpus" >"$log" 2>&1; then
        echo "PASS fuzz:$t" >"$OUT/fuzz_$t.result"
    else
        reason=$(grep -m1 -E 'ERROR|runtime error|SUMMARY' "$log" | cut -c1-160)
        echo "FAIL fuzz:$t: ${reason:-exit status non-zero} (see $log)" >"$OUT/fuzz_$t.result"
    fi
}

for t in $TARGETS; do rm -f "$OUT/fuzz_$t.result"; done
if ! compile_objects; then
    for t in $TARGETS; do
        echo "FAIL fuzz:$t: does not build (see $OUT/objects.log)" >"$OUT/fuzz_$t.result"
    done
fi
# FUZZ_JOBS fuzzers at a time, in batches; the results print in TARGETS' order.
running=0
for t in $TARGETS; do
    [ -e "$OUT/fuzz_$t.result" ] && continue
    if ! link_target "$t"; then
        echo "FAIL fuzz:$t: does not build (see $OUT/fuzz_$t.log)" >"$OUT/fuzz_$t.result"
        continue
    fi
    fuzz_target "$t" &
    running=$((running + 1))
    if [ "$running" -ge "$JOBS" ]; then
        wait
        running=0
    fi
done
wait
failed=0
for t in $TARGETS; do
    if [ -s "$OUT/fuzz_$t.result" ]; then
        cat "$OUT/fuzz_$t.result"
    else
        echo "FAIL fuzz:$t: no result (see $OUT/fuzz_$t.log)"
    fi
    grep -q '^PASS' "$OUT/fuzz_$t.result" 2>/dev/null || failed=1
done
exit $failed
