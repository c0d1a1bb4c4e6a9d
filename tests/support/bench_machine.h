/*
 * bench_machine.h: what the benchmark programs print about where and when
 * they ran (the CPU model, the UTC time) and their clock.
 */
#ifndef PS_BENCH_MACHINE_H
#define PS_BENCH_MACHINE_H

#include <stddef.h>

/* The first "model name" of /proc/cpuinfo, or "unknown". */
void ps_bench_cpu_name(char *cpu, size_t cap);

/* Now as "YYYY-MM-DD HH:MM:SS UTC". */
void ps_bench_utc_now(char *date, size_t cap);

/* Prints "pointseg VERSION program, DATE" and "machine: nproc N, CPU
 * MODEL" on a second line, which it leaves open for the caller to end. */
void ps_bench_print_machine(const char *program);

/* The monotonic clock in milliseconds, for timing. */
double ps_bench_now_ms(void);

#endif
