# sanitizer_options.sh: how the sanitized builds (BUILD/san, BUILD/tsan) end
# on a finding, for every script that runs them; source it:
#   . tests/sanitizer_options.sh
# A finding stops the program (ASan and UBSan abort, LeakSanitizer too at
# exit; ThreadSanitizer exits with status 66), so that a test sees it.
# Values already in the environment win.  Not executable: tests/run.sh runs
# no suite from here.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export TSAN_OPTIONS=${TSAN_OPTIONS:-halt_on_error=1:exitcode=66}
