# pointseg: build, test and run.
#
#   make            build/pointseg (command-line tool) and build/pointsegd (daemon)
#   make run        install missing packages, build, start the daemon with
#                   working defaults (no Redis needed)
#   make test       install missing packages, build, run every test
#   make web / test-browser              the web viewer / its Chromium test
#   make bench-quality / bench-speed     print the benchmark figures
#   make bench-solids                    noisy plain solids: parts kept?
#   make bench-scale                     1M to 10M points: times, peak RSS
#   make BUILD=dir SAN=1                 an AddressSanitizer + UBSan build in dir
#   make BUILD=dir TSAN=1 tsan-tests-build
#                                        the threaded code's tests and the
#                                        daemon's under ThreadSanitizer
#
# Sources are found by wildcard: a new .c in core/, a folder of core/ or api/
# joins its library, a new tests/unit/test_*.c (tests/unit/FOLDER/test_*.c
# for a module of core/FOLDER/) becomes a test binary, with no edit here.

BUILD ?= build
SAN ?= 0
TSAN ?= 0
CC ?= cc
PKGS := lapacke libmicrohttpd libcjson libcurl zlib hiredis

OPT ?= -O2
CFLAGS ?= $(OPT) -g
WARN := -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wmissing-prototypes
# Each layer sees the headers of the layers below it and its own; api's
# private headers (api/private/) only api and the tests (white-box) see.
INC_core := -Icore
INC_api := -Icore -Iapi -Iapi/private
INC_server := -Icore -Iapi -Iserver
INC_clients := -Icore -Iapi -Iclients/c
INC_tests := -Icore -Iapi -Iapi/private -Iserver -Iclients/c -Itests/support
layer_includes = $(INC_$(firstword $(subst /, ,$(1))))
ALL_CFLAGS = -std=c11 -D_POSIX_C_SOURCE=200809L -pthread $(WARN) $(CFLAGS) \
             $(shell pkg-config --cflags libcjson 2>/dev/null) -MMD -MP
LDLIBS := -lflann $(shell pkg-config --libs $(PKGS) 2>/dev/null) -lopenblas -lm -pthread

ifeq ($(SAN),1)
ALL_CFLAGS += -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
LDFLAGS += -fsanitize=address,undefined
endif
ifeq ($(TSAN),1)
ALL_CFLAGS += -fsanitize=thread -fno-omit-frame-pointer
LDFLAGS += -fsanitize=thread
endif

CORE_SRC := $(wildcard core/*.c core/*/*.c)
API_SRC := $(wildcard api/*.c)
SERVER_SRC := $(wildcard server/*.c)
CLI_SRC := $(wildcard clients/cli/*.c)
CCLIENT_SRC := $(wildcard clients/c/*.c)
TESTLIB_SRC := $(wildcard tests/support/*.c)
UNIT_SRC := $(wildcard tests/unit/test_*.c tests/unit/*/test_*.c)
INTEG_SRC := $(wildcard tests/integration/test_*.c)
BENCH_SRC := $(wildcard tests/bench/*.c)

obj = $(patsubst %.c,$(BUILD)/obj/%.o,$(1))
CORE_LIB := $(BUILD)/libpointseg.a
API_LIB := $(BUILD)/libpointseg_api.a
CCLIENT_LIB := $(if $(CCLIENT_SRC),$(BUILD)/libpointseg_client.a)
SERVER_LIB := $(BUILD)/libpointseg_server.a
TESTLIB_OBJ := $(call obj,$(TESTLIB_SRC))
UNIT_BIN := $(patsubst tests/unit/%.c,$(BUILD)/tests/%,$(UNIT_SRC))
INTEG_BIN := $(patsubst tests/integration/%.c,$(BUILD)/itests/%,$(INTEG_SRC))
BENCH_BIN := $(patsubst tests/bench/%.c,$(BUILD)/bench/%,$(BENCH_SRC))
PROGRAMS := $(BUILD)/pointseg $(if $(SERVER_SRC),$(BUILD)/pointsegd)

.PHONY: all deps deps-test run test unit integration fuzz bench-quality bench-speed bench-scale bench-load bench-solids clean tests-build \
        tsan-tests-build \
        install uninstall test-scale test-docker web test-browser
.DEFAULT_GOAL := all

all: $(PROGRAMS)

deps:
	@scripts/install-deps.sh
deps-test:
	@scripts/install-deps.sh --test

$(BUILD)/obj/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) $(call layer_includes,$<) -c $< -o $@

$(CORE_LIB): $(call obj,$(CORE_SRC))
	@rm -f $@; ar rcs $@ $^
$(API_LIB): $(call obj,$(API_SRC))
	@rm -f $@; ar rcs $@ $^
$(BUILD)/libpointseg_client.a: $(call obj,$(CCLIENT_SRC))
	@rm -f $@; ar rcs $@ $^
$(SERVER_LIB): $(call obj,$(filter-out server/main.c,$(SERVER_SRC)))
	@rm -f $@; ar rcs $@ $^

$(BUILD)/pointseg: $(call obj,$(CLI_SRC)) $(CCLIENT_LIB) $(API_LIB) $(CORE_LIB)
	$(CC) $(LDFLAGS) $^ $(LDLIBS) -o $@
$(BUILD)/pointsegd: $(call obj,server/main.c) $(SERVER_LIB) $(API_LIB) $(CORE_LIB)
	$(CC) $(LDFLAGS) $^ $(LDLIBS) -o $@

$(BUILD)/tests/%: $(BUILD)/obj/tests/unit/%.o $(TESTLIB_OBJ) $(CCLIENT_LIB) $(SERVER_LIB) $(API_LIB) $(CORE_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(LDFLAGS) $^ $(LDLIBS) -o $@
$(BUILD)/itests/%: $(BUILD)/obj/tests/integration/%.o $(TESTLIB_OBJ) $(CCLIENT_LIB) $(API_LIB) $(CORE_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(LDFLAGS) $^ $(LDLIBS) -o $@
$(BUILD)/bench/%: $(BUILD)/obj/tests/bench/%.o $(TESTLIB_OBJ) $(CCLIENT_LIB) $(API_LIB) $(CORE_LIB)
	@mkdir -p $(dir $@)
	$(CC) $(LDFLAGS) $^ $(LDLIBS) -o $@

# The benchmarks build with the tests, so that `make test` keeps them
# compiling and build/bench/ never holds a stale one.
tests-build: $(PROGRAMS) $(UNIT_BIN) $(INTEG_BIN) $(BENCH_BIN)

# The tests of the code that runs threads side by side (the parallel loop,
# the kd-tree queries, the draws, the job queue, the Redis workers), and the
# daemon with its integration tests, built for ThreadSanitizer: a data race
# fails them (a raced daemon exits with status 66, its report in its log).
TSAN_TESTS := util/test_parallel util/test_select_parallel graph/test_kdtree_query \
              test_ensemble test_core_share test_jobs test_jobstore_redis
tsan-tests-build: $(patsubst %,$(BUILD)/tests/%,$(TSAN_TESTS)) $(BUILD)/pointsegd $(INTEG_BIN)

# ---- running --------------------------------------------------------------

run: deps web
	@$(MAKE) --no-print-directory all
	@scripts/run.sh $(BUILD)

# The whole suite: unit tests in a plain and a sanitized build, the
# threaded code's under ThreadSanitizer, then the integration tests (daemon
# over HTTP, also with the daemon under the sanitizers) and short fuzz runs.
# The last line is "N passed, N failed".
test: deps-test
	@$(MAKE) --no-print-directory tests-build
	@$(MAKE) --no-print-directory BUILD=$(BUILD)/san SAN=1 tests-build
	@$(MAKE) --no-print-directory BUILD=$(BUILD)/tsan TSAN=1 tsan-tests-build
	@tests/run.sh $(BUILD)

unit: tests-build
	@tests/run.sh --unit-only $(BUILD)

fuzz: deps-test
	@tests/fuzz/run.sh $(BUILD) long

# The 304 PSB models (psb-dev and the unpacked psb-train) in both input
# modes, with the stability check; loud SKIP without the data.
BENCH_QUALITY_ARGS ?= --input vertices --input surface:40000 --stability
bench-quality: deps
	@$(MAKE) --no-print-directory $(BENCH_BIN) $(BUILD)/pointseg
	@$(BUILD)/bench/bench_quality $(BENCH_QUALITY_ARGS) $(BENCH_ARGS)

bench-speed: deps
	@$(MAKE) --no-print-directory $(BENCH_BIN) $(BUILD)/pointseg
	@$(BUILD)/bench/bench_speed $(BENCH_ARGS)

# 1M, 2M, 4M and 10M points sampled on the horse, one child process each
# (BENCH_ARGS="--sizes 1000000,2000000" for fewer); needs about 6 GB.
bench-scale: deps
	@$(MAKE) --no-print-directory $(BUILD)/bench/bench_scale
	@$(BUILD)/bench/bench_scale $(BENCH_ARGS)

bench-load: deps
	@$(MAKE) --no-print-directory $(BUILD)/bench/bench_load $(BUILD)/pointsegd
	@$(BUILD)/bench/bench_load $(BENCH_ARGS)

# Plain solids scanned with noise (synthetic, no data needed): segment
# counts and 1 - RI of the noisy labels against the clean ones.
bench-solids: deps
	@$(MAKE) --no-print-directory $(BUILD)/bench/bench_solids
	@$(BUILD)/bench/bench_solids

# ---- installing and scale-out ----------------------------------------------
# make install [PREFIX=/usr/local] [DESTDIR=]: both programs, their man pages,
# the systemd unit (docker/pointsegd.service) and the web client's served
# files (*.html, *.js, *.css, vendor/) if present.
PREFIX ?= /usr/local
BINDIR = $(PREFIX)/bin
MANDIR = $(PREFIX)/share/man
WEBDIR = $(PREFIX)/share/pointseg/web
UNITDIR ?= $(PREFIX)/lib/systemd/system

install: all
	install -d $(DESTDIR)$(BINDIR) $(DESTDIR)$(MANDIR)/man1 $(DESTDIR)$(MANDIR)/man8 $(DESTDIR)$(UNITDIR)
	install -m 755 $(PROGRAMS) $(DESTDIR)$(BINDIR)/
	install -m 644 docs/man/pointseg.1 $(DESTDIR)$(MANDIR)/man1/
	install -m 644 docs/man/pointsegd.8 $(DESTDIR)$(MANDIR)/man8/
	sed -e 's|@BINDIR@|$(BINDIR)|' -e 's|@WEBDIR@|$(WEBDIR)|' docker/pointsegd.service \
	    >$(DESTDIR)$(UNITDIR)/pointsegd.service
	if [ -d clients/web ]; then \
	    install -d $(DESTDIR)$(WEBDIR) && \
	    for f in clients/web/*.html clients/web/*.js clients/web/*.css; do \
	        if [ -f "$$f" ]; then install -m 644 "$$f" $(DESTDIR)$(WEBDIR)/ || exit 1; fi; \
	    done; \
	    if [ -d clients/web/vendor ]; then cp -R clients/web/vendor $(DESTDIR)$(WEBDIR)/; fi; \
	fi

uninstall:
	rm -f $(DESTDIR)$(BINDIR)/pointseg $(DESTDIR)$(BINDIR)/pointsegd
	rm -f $(DESTDIR)$(MANDIR)/man1/pointseg.1 $(DESTDIR)$(MANDIR)/man8/pointsegd.8
	rm -f $(DESTDIR)$(UNITDIR)/pointsegd.service
	rm -rf $(DESTDIR)$(PREFIX)/share/pointseg

# redis-server, three pointsegd --redis and a real nginx on loopback, as in
# docker/compose.yaml, with a replica SIGKILLed and Redis restarted mid-run
# (installs nginx and redis-server when root, else skips); then again with
# the daemons built with AddressSanitizer + UBSan (build/san) and with
# ThreadSanitizer (build/tsan).  Not part of
# `make test` (the script is not executable, so tests/run.sh passes it by).
test-scale: all
	@$(MAKE) --no-print-directory BUILD=$(BUILD)/san SAN=1 $(BUILD)/san/pointseg $(BUILD)/san/pointsegd
	@$(MAKE) --no-print-directory BUILD=$(BUILD)/tsan TSAN=1 $(BUILD)/tsan/pointseg $(BUILD)/tsan/pointsegd
	@sh tests/integration/scale.sh $(BUILD) $(BUILD)/san $(BUILD)/tsan

# docker/Dockerfile built and run (the horse through it), then
# docker/compose.yaml brought up and its replicas and Redis killed
# (tests/docker/run.sh; root: installs docker.io and starts dockerd, makes
# its Debian base images with debootstrap; skips saying why otherwise).
test-docker: all
	@sh tests/docker/run.sh $(BUILD)

# The web viewer: three.js (pinned in clients/web/package-lock.json) copied
# into clients/web/vendor/, which pointsegd serves at /.  test-browser runs
# it in headless Chromium (tests/browser/; installs chromium when root).
WEB_THREE := clients/web/node_modules/three
web:
	@scripts/web-deps.sh
	@npm ci --prefix clients/web --no-audit --no-fund --loglevel=error
	@mkdir -p clients/web/vendor
	@cp $(WEB_THREE)/build/three.module.js $(WEB_THREE)/build/three.core.js \
	    $(WEB_THREE)/examples/jsm/controls/OrbitControls.js clients/web/vendor/

test-browser: deps web
	@$(MAKE) --no-print-directory $(BUILD)/pointsegd
	@tests/browser/run.sh $(BUILD)

clean:
	rm -rf $(BUILD)

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)
.SECONDARY:
