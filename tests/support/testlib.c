/* testlib.c: the harness behind testlib.h (results, skips, the main loop). */
#include "testlib.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static int current_failed;
static int current_skipped;
static char current_reason[512];

void ps_test_fail(const char *file, int line, const char *fmt, ...) {
    va_list ap;
    char msg[400];
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fprintf(stderr, "  %s:%d: %s\n", file, line, msg);
    if (!current_failed)
        snprintf(current_reason, sizeof current_reason, "%s:%d: %s", file, line, msg);
    current_failed++;
}

void ps_test_skip(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(current_reason, sizeof current_reason, fmt, ap);
    va_end(ap);
    current_skipped = 1;
}

static int is_dir(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

const char *ps_test_shared_dir(void) {
    const char *env = getenv("POINTSEG_SHARED");
    if (env && is_dir(env)) return env;
    if (is_dir("../shared/data")) return "../shared/data";
    return NULL;
}

static const char *base_name(const char *path) {
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

int ps_test_main(const char *file, const ps_test_case *tests, size_t count,
                 int argc, char **argv) {
    const char *filter = argc > 1 ? argv[1] : NULL;
    int failures = 0;
    setvbuf(stdout, NULL, _IOLBF, 0);
    for (size_t i = 0; i < count; i++) {
        if (filter && !strstr(tests[i].name, filter)) continue;
        current_failed = current_skipped = 0;
        current_reason[0] = 0;
        tests[i].fn();
        if (current_failed) {
            printf("FAIL %s:%s: %s\n", base_name(file), tests[i].name, current_reason);
            failures++;
        } else if (current_skipped) {
            printf("SKIP %s:%s: %s\n", base_name(file), tests[i].name, current_reason);
        } else {
            printf("PASS %s:%s\n", base_name(file), tests[i].name);
        }
    }
    return failures ? 1 : 0;
}
