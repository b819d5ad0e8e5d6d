# SPDX-License-Identifier: Apache-2.0
# mk/tsan.mk — the ThreadSanitizer build: the library and tests/c/test_threads.c
# compiled with -fsanitize=thread into $(B)/tsan. Included at the end of the
# top-level Makefile, whose variables (B, CC, LIBCFLAGS, TESTCFLAGS, SRCS, HDRS)
# and targets (test-c) it uses.
#
#   make tsan        build $(B)/tsan/tests/test_threads (part of make test-c)
#   make tsan-py     the Python package with its extension isect._isect compiled
#                    with -fsanitize=thread, in $(B)/tsan/py (needs the .venv)
#   make check-tsan  build both and run scripts/run_tsan.sh, which fails on any
#                    "WARNING: ThreadSanitizer" report (the steps make test runs)
#
# test_threads is also an ordinary unit test (tests/c/test_*.c), built plain
# and under ASan+UBSan by the Makefile's pattern rules; it needs -pthread there
# too.

TSAN_FLAGS := -fsanitize=thread -fno-omit-frame-pointer -g
TSAN_OBJS  := $(SRCS:libisect/src/%.c=$(B)/tsan/obj/%.o)
TSAN_STLIB := $(B)/tsan/libisect.a
TSAN_TESTS := $(B)/tsan/tests/test_threads

.PHONY: tsan tsan-py check-tsan

$(B)/tsan/obj/%.o: libisect/src/%.c $(HDRS)
	@mkdir -p $(@D)
	$(CC) $(LIBCFLAGS) $(TSAN_FLAGS) -c $< -o $@

$(TSAN_STLIB): $(TSAN_OBJS)
	rm -f $@
	ar rcs $@ $(TSAN_OBJS)

$(B)/tsan/tests/%: tests/c/%.c tests/c/check.h tests/c/mesh_fixtures.h tests/c/test_random.h \
                   $(TSAN_STLIB)
	@mkdir -p $(@D)
	$(CC) $(TESTCFLAGS) -pthread $(TSAN_FLAGS) $< -o $@ $(TSAN_STLIB) -lm

$(B)/tests/test_threads $(B)/san/tests/test_threads: TESTCFLAGS += -pthread

tsan: $(TSAN_TESTS)
test-c: tsan

# The extension is built by the package's own cffi script with the sanitizer
# added through CFLAGS/LDFLAGS (which the compiler driver of setuptools
# appends); the pure-Python modules are copied next to it. Run it with libtsan
# preloaded into the venv's (uninstrumented) python: scripts/run_tsan.sh.
TSAN_PY := $(B)/tsan/py
$(TSAN_PY)/.stamp: .venv/.stamp $(SRCS) $(HDRS) bindings/python/build_isect.py \
                   $(wildcard bindings/python/src/isect/*.py)
	@mkdir -p $(TSAN_PY)/isect
	cd bindings/python && CFLAGS="$(TSAN_FLAGS)" LDFLAGS="-fsanitize=thread" \
	    ../../.venv/bin/python -c 'import sys, build_isect; build_isect.ffibuilder.compile(tmpdir=sys.argv[1])' \
	    $(abspath $(TSAN_PY)) >/dev/null
	cp bindings/python/src/isect/*.py bindings/python/src/isect/py.typed $(TSAN_PY)/isect/
	touch $@
tsan-py: $(TSAN_PY)/.stamp

check-tsan: tsan tsan-py
	sh scripts/run_tsan.sh
