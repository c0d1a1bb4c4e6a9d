/*
 * png_write.h: writes an 8-bit RGB image as a PNG file (IHDR, one IDAT
 * compressed with zlib, IEND; CRC32 from zlib).
 */
#ifndef PS_CLI_PNG_WRITE_H
#define PS_CLI_PNG_WRITE_H

#include <stddef.h>

/* Writes rgb (#height rows by #width pixels by 3 bytes, top row first) to
 * path.  Returns 0, or -1 with errno set (ENOMEM when zlib failed). */
int cli_png_write(const char *path, const unsigned char *rgb, int width, int height);

#endif
