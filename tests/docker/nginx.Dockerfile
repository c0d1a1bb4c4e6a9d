# nginx.Dockerfile: a stand-in for the official nginx image (no registry is
# reachable from the tests), from Debian's nginx: the configuration is
# mounted at /etc/nginx/nginx.conf, nginx runs in the foreground.
FROM debian:bookworm-slim
RUN apt-get update \
 && apt-get install -y --no-install-recommends nginx \
 && rm -rf /var/lib/apt/lists/*
EXPOSE 8080
CMD ["nginx", "-g", "daemon off;"]
