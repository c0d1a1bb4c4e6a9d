# base-images.sh: the images docker/Dockerfile and docker/compose.yaml need,
# made here because no image registry is reachable: debian:bookworm and
# debian:bookworm-slim from `debootstrap --variant=minbase` on the Debian
# mirror (docker import; made once, then found in Docker's image store), and
# stand-ins for the official redis and nginx images built from Debian's
# packages (tests/docker/redis.Dockerfile, nginx.Dockerfile), used only by
# tests/docker/compose.test.yaml.  Sourced by tests/docker/run.sh (which
# sets ROOT); each function returns non-zero (why on stderr) when it cannot.
MIRROR=${POINTSEG_DEBIAN_MIRROR:-http://deb.debian.org/debian}

make_debian_base() {
    docker image inspect debian:bookworm >/dev/null 2>&1 &&
        docker image inspect debian:bookworm-slim >/dev/null 2>&1 && return 0
    root=$(mktemp -d /var/tmp/pointseg-rootfs.XXXXXX)
    echo "docker: debootstrap --variant=minbase bookworm from $MIRROR" >&2
    if ! debootstrap --variant=minbase bookworm "$root" "$MIRROR" >"$root.log" 2>&1; then
        echo "debootstrap failed: $(tail -n 3 "$root.log")" >&2
        rm -rf "$root" "$root.log"
        return 1
    fi
    rm -rf "$root"/var/cache/apt/archives/*.deb "$root"/var/lib/apt/lists/*
    tar -C "$root" -c . | docker import - debian:bookworm >/dev/null &&
        docker tag debian:bookworm debian:bookworm-slim
    rc=$?
    rm -rf "$root" "$root.log"
    return $rc
}

make_stand_ins() {
    dir=$ROOT/tests/docker
    docker build -q -t pointseg-test/redis -f "$dir/redis.Dockerfile" "$dir" >/dev/null &&
        docker build -q -t pointseg-test/nginx -f "$dir/nginx.Dockerfile" "$dir" >/dev/null
}
