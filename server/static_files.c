/* static_files.c: safe lookup of static files (no "..", no symlink) and
 * their media types. */
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

/* Opens dir/rel one component at a time, following no symlink (and so
 * never leaving dir): an fd, or -1 when a component is missing, a symlink,
 * or not a directory where one is needed. */
static int open_beneath(const char *dir, const char *rel) {
    char part[256];
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    while (fd >= 0 && *rel) {
        const char *slash = strchr(rel, '/');
        size_t len = slash ? (size_t)(slash - rel) : strlen(rel);
        int next = -1;
        if (len < sizeof part) {
            memcpy(part, rel, len);
            part[len] = 0;
            next = len ? openat(fd, part, O_RDONLY | O_CLOEXEC | O_NOFOLLOW | (slash ? O_DIRECTORY : 0))
                       : dup(fd);
        }
        close(fd);
        fd = next;
        rel += len + (slash != NULL);
    }
    return fd;
}

int ps_static_open(const char *dir, const char *url_path, size_t *size, const char **media_type) {
    char path[4096];
    struct stat st;
    if (!dir || !*dir || !path_is_safe(url_path)) return -1;
    int n = snprintf(path, sizeof path, "%s%s", url_path + 1,
                     url_path[strlen(url_path) - 1] == '/' ? "index.html" : "");
    if (n < 0 || (size_t)n >= sizeof path) return -1;
    int fd = open_beneath(dir, path);
    if (fd < 0) return -1;
    if (fstat(fd, &st) || !S_ISREG(st.st_mode)) {
        close(fd);
        return -1;
    }
    *size = (size_t)st.st_size;
    *media_type = media_type_of(path);
    return fd;
}
