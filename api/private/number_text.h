/*
 * number_text.h: fast number-to-text writers for the encoders' per-point
 * arrays (internal to api/; one snprintf or cJSON node per point is too
 * slow for 1M points).
 * Each writes at p, without a terminating NUL, and returns the end.
 */
#ifndef PS_NUMBER_TEXT_H
#define PS_NUMBER_TEXT_H

/* Most characters each writer produces. */
enum { PS_INT_TEXT_MAX = 11, PS_DOUBLE_TEXT_MAX = 24 };

/* v in decimal: "-2147483648" at most. */
char *ps_put_int(char *p, int v);

/* v as %.9g would write it (enough to tell float-size values apart; in
 * rare half-way cases the ninth digit may differ by one), or "null" when v
 * is not finite.  Zero is "0". */
char *ps_put_double(char *p, double v);

#endif
