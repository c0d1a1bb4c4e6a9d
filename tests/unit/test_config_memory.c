/* test_config_memory.c: the --max-memory default's cgroup limit, read from a
 * cgroup v2 memory.max or a v1 memory.limit_in_bytes: a number lower than
 * the machine's memory caps it; "max", v1's "unlimited" (a number near
 * 2^63), 0, junk and a missing file leave it. */
#include "config.h"
#include "testlib.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#define MACHINE ((size_t)16 << 30)

/* ps_memory_capped(MACHINE, a temporary file holding text). */
static size_t capped_by(const char *text) {
    char path[] = "/tmp/pointseg_cgroupXXXXXX";
    int fd = mkstemp(path);
    if (fd < 0) return 0;
    FILE *f = fdopen(fd, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    size_t bytes = ps_memory_capped(MACHINE, path);
    unlink(path);
    return bytes;
}

static void test_limit_below_the_machine_caps(void) {
    CHECK(capped_by("1073741824\n") == (size_t)1 << 30);   /* v2 or v1: 1 GiB */
    CHECK(capped_by("536870912") == (size_t)1 << 29);
}

static void test_no_limit_leaves_the_machine(void) {
    CHECK(capped_by("max\n") == MACHINE);                    /* v2 */
    CHECK(capped_by("9223372036854771712\n") == MACHINE);    /* v1 unlimited */
    CHECK(capped_by("68719476736\n") == MACHINE);            /* 64 GiB: above */
    CHECK(capped_by("0\n") == MACHINE);
    CHECK(capped_by("") == MACHINE);
    CHECK(ps_memory_capped(MACHINE, "/nonexistent/memory.max") == MACHINE);
}

PS_TEST_MAIN(TEST(test_limit_below_the_machine_caps), TEST(test_no_limit_leaves_the_machine))
