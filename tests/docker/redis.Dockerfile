# redis.Dockerfile: a stand-in for the official redis image (no registry is
# reachable from the tests), from Debian's redis-server: same command line,
# data in /data, reachable from other containers (like the official
# entrypoint, which turns protected mode off), redis-cli for the healthcheck.
FROM debian:bookworm-slim
RUN apt-get update \
 && apt-get install -y --no-install-recommends redis-server \
 && rm -rf /var/lib/apt/lists/* \
 && mkdir -p /data && chown redis:redis /data
WORKDIR /data
USER redis
EXPOSE 6379
ENTRYPOINT ["/bin/sh", "-c", "exec \"$@\" --protected-mode no", "redis"]
CMD ["redis-server"]
