/* random_bits.c: xorshift64 and the numbers drawn from it (random_bits.h). */
#include "random_bits.h"

#include <math.h>

uint64_t ps_random_bits(uint64_t *state) {
    *state ^= *state << 13, *state ^= *state >> 7, *state ^= *state << 17;
    return *state;
}

double ps_uniform_next(uint64_t *state) {
    return (double)(ps_random_bits(state) >> 11) / 9007199254740992.0;
}

double ps_gaussian_next(uint64_t *state) {
    double u = 1 - ps_uniform_next(state); /* in (0, 1] */
    return sqrt(-2 * log(u)) * cos(6.283185307179586 * ps_uniform_next(state));
}
