#!/bin/sh
# run.sh: builds the fuzz targets (the decoders, the daemon's multipart
# path, whole requests to the daemon, the --redis URL parser, and the core
# on small point sets of its own) with
# libFuzzer + ASan + UBSan and runs each on a copy of its seed
# corpus.
#   tests/fuzz/run.sh BUILD [short|long]   20 s per target (short; FUZZ_SECONDS
#                                          overrides it) or 600 s (long);
#                                          FUZZ_TARGETS="ply json" runs only those
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
mkdir -p "$OUT"
failed=0
for t in $TARGETS; do
    bin="$OUT/fuzz_$t"
    log="$OUT/fuzz_$t.log"
    case "$t" in
    multipart | head) sources=$DAEMON_SOURCES libs=$DAEMON_LIBS ;;
    redis_url) sources=$REDIS_SOURCES libs=$REDIS_LIBS ;;
    segment) sources=$CORE_SOURCES libs=$CORE_LIBS ;;
    *) sources=$DECODER_SOURCES libs=$DECODER_LIBS ;;
    esac
    # shellcheck disable=SC2086
    if ! clang -std=c11 -D_POSIX_C_SOURCE=200809L $WARN -g -O1 -fsanitize=fuzzer,address,undefined \
        -fno-sanitize-recover=undefined -Icore -Iapi -Iapi/private -Iserver -Itests/fuzz $sources "tests/fuzz/fuzz_$t.c" \
        $libs -o "$bin" >"$log" 2>&1; then
        echo "FAIL fuzz:$t: does not build (see $log)"
        failed=1
        continue
    fi
    corpus="$OUT/corpus_$t"
    rm -rf "$corpus"
    mkdir -p "$corpus"
    cp tests/fuzz/seeds/"$t"/* "$corpus"/ 2>/dev/null
    if "$bin" -max_total_time="$SECONDS_EACH" -max_len=8192 -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=0 -artifact_prefix="$OUT/fuzz_$t-" "$corpus" >"$log" 2>&1; then
        echo "PASS fuzz:$t"
    else
        reason=$(grep -m1 -E 'ERROR|runtime error|SUMMARY' "$log" | cut -c1-160)
        echo "FAIL fuzz:$t: ${reason:-exit status non-zero} (see $log)"
        failed=1
    fi
done
exit $failed
