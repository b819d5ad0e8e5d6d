# SPDX-License-Identifier: Apache-2.0
# libisect — GNU make build.  `make` builds the shared and static libraries,
# `make demo` renders the demo pictures (the main job), `make test` runs every
# test (C unit tests and the golden corpus, plain and under ASan+UBSan, the
# Fortran and Python suites, ABI and export checks, the corpus regeneration
# check), `make bench` the benchmarks, `make install PREFIX=... DESTDIR=...`
# installs.
# meson.build builds the same library and runs the same tests; CMakeLists.txt
# builds the library alone, for CMake users. `make test-consumers` builds small
# programs against libisect through each route of README.md, "Using libisect
# from your project".

CC      ?= cc
PYTHON  ?= python3
PREFIX  ?= /usr/local
LIBDIR  ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
DOCDIR  ?= $(PREFIX)/share/doc/isect
DESTDIR ?=

VERSION := $(shell sh scripts/version.sh)
ABI     := $(shell sh scripts/version.sh abi)

B := build
# -ffp-contract=off: the exact predicates and the cancellation-free formulas
# are written for plain IEEE operations; a compiler-fused a*b+c would change
# their rounding (clang fuses by default).
WARN    := -std=c99 -Wall -Wextra -Wpedantic -Werror
OPT     ?= -O2
LIBCFLAGS := $(WARN) $(OPT) -ffp-contract=off -fPIC -fvisibility=hidden \
             -DISECT_BUILDING_LIBRARY -Ilibisect/include -Ilibisect/src
SANITIZE := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
TESTCFLAGS := $(WARN) -O1 -g -Ilibisect/include -Itests/c

SRCS    := $(sort $(wildcard libisect/src/*/*.c))
HDRS    := $(wildcard libisect/src/*/*.h) libisect/include/isect.h
OBJS    := $(SRCS:libisect/src/%.c=$(B)/obj/%.o)
SAN_OBJS := $(SRCS:libisect/src/%.c=$(B)/san/obj/%.o)

SONAME  := libisect.so.$(ABI)
SHLIB   := $(B)/libisect.so.$(VERSION)
STLIB   := $(B)/libisect.a
SAN_STLIB := $(B)/san/libisect.a

UNIT_TESTS := $(patsubst tests/c/%.c,%,$(sort $(wildcard tests/c/test_*.c)))
RUNNER_SRCS := $(filter-out tests/c/test_%.c,$(wildcard tests/c/*.c))
CJSON   := $(shell pkg-config --libs libcjson 2>/dev/null || echo -lcjson)
CJSON_CFLAGS := $(shell pkg-config --cflags libcjson 2>/dev/null)

.PHONY: all lib test test-c test-consumers bench install uninstall clean demo venv deps
all: lib
lib: $(SHLIB) $(B)/$(SONAME) $(B)/libisect.so $(STLIB)

$(B)/obj/%.o: libisect/src/%.c $(HDRS)
	@mkdir -p $(@D)
	$(CC) $(LIBCFLAGS) -c $< -o $@

$(B)/san/obj/%.o: libisect/src/%.c $(HDRS)
	@mkdir -p $(@D)
	$(CC) $(LIBCFLAGS) $(SANITIZE) -g -c $< -o $@

$(SHLIB): $(OBJS) libisect/isect.map
	$(CC) -shared -Wl,-soname,$(SONAME) -Wl,--version-script=libisect/isect.map \
	    -Wl,--no-undefined -o $@ $(OBJS) -lm

$(B)/$(SONAME): $(SHLIB)
	ln -sf $(notdir $(SHLIB)) $@
$(B)/libisect.so: $(B)/$(SONAME)
	ln -sf $(SONAME) $@

$(STLIB): $(OBJS)
	rm -f $@
	ar rcs $@ $(OBJS)
$(SAN_STLIB): $(SAN_OBJS)
	rm -f $@
	ar rcs $@ $(SAN_OBJS)

# ---------------------------------------------------------------- tests
# Unit tests link the shared library (so they see exactly the exported ABI);
# their sanitized twins link the sanitized static library.
$(B)/tests/%: tests/c/%.c tests/c/check.h tests/c/mesh_fixtures.h tests/c/exact_dyadic.h $(B)/$(SONAME) $(B)/libisect.so
	@mkdir -p $(@D)
	$(CC) $(TESTCFLAGS) $< -o $@ -L$(B) -lisect -Wl,-rpath,'$$ORIGIN/..' -lm
$(B)/san/tests/%: tests/c/%.c tests/c/check.h tests/c/mesh_fixtures.h tests/c/exact_dyadic.h $(SAN_STLIB)
	@mkdir -p $(@D)
	$(CC) $(TESTCFLAGS) $(SANITIZE) $< -o $@ $(SAN_STLIB) -lm

$(B)/tests/corpus_runner: $(RUNNER_SRCS) $(wildcard tests/c/*.h) $(B)/$(SONAME) $(B)/libisect.so
	@mkdir -p $(@D)
	$(CC) $(TESTCFLAGS) $(CJSON_CFLAGS) $(RUNNER_SRCS) -o $@ -L$(B) -lisect \
	    -Wl,-rpath,'$$ORIGIN/..' $(CJSON) -lm
$(B)/san/tests/corpus_runner: $(RUNNER_SRCS) $(wildcard tests/c/*.h) $(SAN_STLIB)
	@mkdir -p $(@D)
	$(CC) $(TESTCFLAGS) $(CJSON_CFLAGS) $(SANITIZE) $(RUNNER_SRCS) -o $@ $(SAN_STLIB) $(CJSON) -lm

TEST_BINS := $(UNIT_TESTS:%=$(B)/tests/%) $(UNIT_TESTS:%=$(B)/san/tests/%)
ifneq ($(RUNNER_SRCS),)
TEST_BINS += $(B)/tests/corpus_runner $(B)/san/tests/corpus_runner
endif

test-c: lib $(TEST_BINS)

# The Python environment of the tests (and of the demo): one venv at .venv
# with the pinned requirements and, once the bindings exist, the package.
venv: .venv/.stamp
.venv/.stamp: requirements.txt $(SRCS) $(HDRS) $(shell find bindings/python -name '*.py' -o -name '*.h' -o -name '*.toml' 2>/dev/null | grep -v egg-info)
	$(PYTHON) -m venv .venv
	.venv/bin/pip install -q -r requirements.txt
	@if [ -f bindings/python/pyproject.toml ]; then \
	    echo ".venv/bin/pip install ./bindings/python"; \
	    .venv/bin/pip install -q ./bindings/python || exit 1; fi
	touch $@

# Debian packages the tests and the demo need (apt-get when root and missing).
deps:
	bash scripts/install_deps.sh

# deps runs first, in its own make, so the rest sees the installed tools.
test:
	$(MAKE) --no-print-directory deps
	$(MAKE) --no-print-directory test-c test-fortran venv fuzz-build
	sh scripts/run_tests.sh

# Tiny C and Fortran programs built against libisect the ways other projects
# take it in: pkg-config after make install, CMake find_package and
# FetchContent, a meson subproject, an fpm dependency (make test runs it too;
# fpm comes from the venv).
test-consumers: lib fortran venv
	sh tests/install/consumers.sh

# ---------------------------------------------------------------- bench
$(B)/bench/%: bench/%.c $(STLIB)
	@mkdir -p $(@D)
	$(CC) $(WARN) -O2 -Ilibisect/include $< -o $@ $(STLIB) -lm
# The mesh benchmark compares with Embree 3 (Debian libembree-dev).
$(B)/bench/bench_mesh: bench/bench_mesh.c tests/c/mesh_fixtures.h $(STLIB)
	@mkdir -p $(@D)
	$(CC) $(WARN) -O2 -Ilibisect/include -Itests/c $< -o $@ $(STLIB) -lembree3 -lm
# The kernel benchmark's textbook loops are compiled as a user's own code:
# -O2 -march=native with GCC's default FMA contraction (which -std=c99 turns
# off); the library it is compared with is $(STLIB) as built above.
$(B)/bench/bench_kernels: bench/bench_kernels.c $(STLIB)
	@mkdir -p $(@D)
	$(CC) $(WARN) -O2 -march=native -ffp-contract=fast -Ilibisect/include $< -o $@ $(STLIB) -lm
bench: $(B)/bench/bench_batch $(B)/bench/bench_mesh $(B)/bench/bench_kernels venv
	mkdir -p bench/results
	$(B)/bench/bench_batch
	$(B)/bench/bench_mesh
	$(B)/bench/bench_kernels
	.venv/bin/python bench/python_bench.py
	.venv/bin/python bench/python_mesh_bench.py
	.venv/bin/python bench/python_kernels_bench.py
	.venv/bin/python bench/summary.py

# ---------------------------------------------------------------- demo
# The main job: renders every primitive through the Python API (batch calls,
# threads) to demo/scene.png, and demo/exactly_once.png (libisect vs Embree).
demo:
	$(MAKE) --no-print-directory deps
	$(MAKE) --no-print-directory venv
	.venv/bin/python demo/render.py

# ---------------------------------------------------------------- install
install: lib
	install -d $(DESTDIR)$(INCLUDEDIR) $(DESTDIR)$(LIBDIR)/pkgconfig
	install -m 644 libisect/include/isect.h $(DESTDIR)$(INCLUDEDIR)/isect.h
	install -m 755 $(SHLIB) $(DESTDIR)$(LIBDIR)/
	ln -sf $(notdir $(SHLIB)) $(DESTDIR)$(LIBDIR)/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libisect.so
	install -m 644 $(STLIB) $(DESTDIR)$(LIBDIR)/libisect.a
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(LIBDIR)|' \
	    -e 's|@INCLUDEDIR@|$(INCLUDEDIR)|' -e 's|@VERSION@|$(VERSION)|' \
	    libisect/isect.pc.in > $(DESTDIR)$(LIBDIR)/pkgconfig/isect.pc
	install -d $(DESTDIR)$(DOCDIR)
	install -m 644 LICENSE NOTICE $(DESTDIR)$(DOCDIR)/

uninstall:
	rm -f $(DESTDIR)$(INCLUDEDIR)/isect.h $(DESTDIR)$(LIBDIR)/$(notdir $(SHLIB)) \
	      $(DESTDIR)$(LIBDIR)/$(SONAME) $(DESTDIR)$(LIBDIR)/libisect.so \
	      $(DESTDIR)$(LIBDIR)/libisect.a $(DESTDIR)$(LIBDIR)/pkgconfig/isect.pc \
	      $(DESTDIR)$(DOCDIR)/LICENSE $(DESTDIR)$(DOCDIR)/NOTICE

clean:
	rm -rf $(B)

# Fortran module, Fortran tests, installed-examples test, ABI baseline.
include mk/fortran.mk
# libFuzzer harnesses (make fuzz, make fuzz-build).
include mk/fuzz.mk

# ThreadSanitizer build of the library and the thread test.
include mk/tsan.mk
