/* test_core_share.c: jobs asking for the service's choice get the cores no
 * other job holds (at least one), explicit requests are kept and counted,
 * and given-back cores go to the next job. */
#include "core_share.h"
#include "testlib.h"

static void test_idle_then_loaded(void) {
    ps_core_share_init(2);
    int first = ps_core_share_take(0);
    CHECK_MSG(first == 2, "alone: %d threads", first);
    int second = ps_core_share_take(0);
    CHECK_MSG(second == 1, "beside a 2-core job: %d threads", second);
    ps_core_share_give(first);
    int third = ps_core_share_take(0);
    CHECK_MSG(third == 1, "beside a 1-core job: %d threads", third);
    ps_core_share_give(second);
    ps_core_share_give(third);
    int alone_again = ps_core_share_take(0);
    CHECK_MSG(alone_again == 2, "alone again: %d threads", alone_again);
    ps_core_share_give(alone_again);
}

static void test_explicit_requests_kept_and_counted(void) {
    ps_core_share_init(4);
    int explicit_job = ps_core_share_take(3);
    CHECK(explicit_job == 3);
    int other = ps_core_share_take(0);
    CHECK_MSG(other == 1, "beside 3 of 4 cores held: %d threads", other);
    ps_core_share_give(other);
    int more = ps_core_share_take(8);
    CHECK(more == 8);
    CHECK(ps_core_share_take(0) == 1);
}

PS_TEST_MAIN(TEST(test_idle_then_loaded), TEST(test_explicit_requests_kept_and_counted))
