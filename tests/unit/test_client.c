/*
 * test_client.c: the C client's pieces that need no daemon (the calls that
 * do are tested against a live pointsegd in tests/integration/test_daemon.c).
 */
#include "pointseg_client.h"
#include "testlib.h"

static void test_final_states(void) {
    CHECK(ps_client_job_is_final("done"));
    CHECK(ps_client_job_is_final("failed"));
    CHECK(ps_client_job_is_final("cancelled"));
    CHECK(!ps_client_job_is_final("queued"));
    CHECK(!ps_client_job_is_final("running"));
    CHECK(!ps_client_job_is_final(""));
    CHECK(!ps_client_job_is_final("Done"));
}

PS_TEST_MAIN(TEST(test_final_states))
