/* bench_machine.c: the CPU model, the date and the clock of the benchmarks (bench_machine.h). */
#include "bench_machine.h"

#include "pointseg.h"

#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

void ps_bench_cpu_name(char *cpu, size_t cap) {
    char line[512];
    snprintf(cpu, cap, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    while (f && fgets(line, sizeof line, f)) {
        char *colon = strchr(line, ':');
        if (strncmp(line, "model name", 10) != 0 || !colon) continue;
        snprintf(cpu, cap, "%s", colon + 2);
        cpu[strcspn(cpu, "\n")] = 0;
        break;
    }
    if (f) fclose(f);
}

void ps_bench_utc_now(char *date, size_t cap) {
    time_t t = time(NULL);
    struct tm tm;
    strftime(date, cap, "%Y-%m-%d %H:%M:%S UTC", gmtime_r(&t, &tm));
}

void ps_bench_print_machine(const char *program) {
    char cpu[256], date[64];
    ps_bench_cpu_name(cpu, sizeof cpu);
    ps_bench_utc_now(date, sizeof date);
    printf("pointseg %s %s, %s\nmachine: nproc %ld, CPU %s", PS_VERSION, program, date,
           sysconf(_SC_NPROCESSORS_ONLN), cpu);
}

double ps_bench_now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}
