/*
 * random_bits.h: the one pseudo-random sequence of the tests and the
 * benchmarks, Marsaglia's xorshift64 (shifts 13, 7, 17), and the uniform
 * and normal numbers drawn from it.  Deterministic: a state (nonzero) gives
 * the same numbers on every machine.
 */
#ifndef PS_RANDOM_BITS_H
#define PS_RANDOM_BITS_H

#include <stdint.h>

/* The next 64 bits of the sequence; *state (nonzero) in/out. */
uint64_t ps_random_bits(uint64_t *state);

/* Uniform in [0, 1), from the next value's top 53 bits. */
double ps_uniform_next(uint64_t *state);

/* A standard normal number (Box-Muller over ps_uniform_next). */
double ps_gaussian_next(uint64_t *state);

#endif
