/* static_files.c: safe lookup of static files and their media types. */
#include "static_files.h"

#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

static const char *media_type_of(const char *path) {
    static const char *const types[][2] = {
        {".html", "text/html; charset=utf-8"}, {".js", "text/javascript; charset=utf-8"},
        {".mjs", "text/javascript; charset=utf-8"}, {".css", "text/css; charset=utf-8"},
        {".json", "application/json"}, {".svg", "image/svg+xml"}, {".png", "image/png"},
        {".ico", "image/x-icon"}, {".wasm", "application/wasm"}, {".ply", "application/ply"},
        {".txt", "text/plain; charset=utf-8"}, {".xyz", "text/plain; charset=utf-8"}};
    const char *dot = strrchr(path, '.');
    for (size_t i = 0; dot && i < sizeof types / sizeof types[0]; i++)
        if (!strcasecmp(dot, types[i][0])) return types[i][1];
    return "application/octet-stream";
}

/* No "..", no hidden segment, no backslash: stays inside dir. */
static int path_is_safe(const char *p) {
    if (p[0] != '/' || strchr(p, '\\')) return 0;
    for (const char *s = p; s; s = strchr(s + 1, '/'))
        if (s[1] == '.') return 0;
    return 1;
}

int ps_static_open(const char *dir, const char *url_path, size_t *size, const char **media_type) {
    char path[4096];
    struct stat st;
    if (!dir || !*dir || !path_is_safe(url_path)) return -1;
    int n = snprintf(path, sizeof path, "%s%s%s", dir, url_path,
                     url_path[strlen(url_path) - 1] == '/' ? "index.html" : "");
    if (n < 0 || (size_t)n >= sizeof path) return -1;
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return -1;
    if (fstat(fd, &st) || !S_ISREG(st.st_mode)) {
        close(fd);
        return -1;
    }
    *size = (size_t)st.st_size;
    *media_type = media_type_of(path);
    return fd;
}
