# SPDX-License-Identifier: Apache-2.0
# mk/fuzz.mk — libFuzzer harnesses (tests/fuzz/), built with clang and
# AddressSanitizer + UndefinedBehaviorSanitizer. Included from the top-level
# Makefile, whose variables (B, WARN, LIBCFLAGS, SRCS, HDRS, RUNNER_SRCS, CJSON,
# CJSON_CFLAGS) it uses.
#
#   make fuzz-build             the harnesses, build/fuzz/fuzz_*, and their seeds
#   make fuzz FUZZ_SECONDS=N    run each harness for N seconds (default 60)
#   make fuzz-seeds             write the seed corpora from tests/cases/*.json
#   make fuzz-build FUZZ_DEFS=-DFUZZ_ANY_RANGE   also the held-back checks
#
# The library is compiled a third time with the fuzzer's coverage
# instrumentation (-fsanitize=fuzzer-no-link), so the fuzzer is guided by the
# library's own branches, not only the harnesses'. Each harness keeps the
# corpus it grows in build/fuzz/corpus/NAME (reused by the next run) and
# reads the seeds in build/fuzz/seeds/NAME; crashes are written to
# build/fuzz/artifacts/ and replayed with `build/fuzz/fuzz_NAME FILE`.

FUZZ_CC ?= clang
FUZZ_SECONDS ?= 60
FZ := $(B)/fuzz
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g
# The harnesses follow the library's C rules (-std=c99 ... -Werror) and its
# floating-point rule (no contraction: they recompute dot products that must
# round as the library's do).
# FUZZ_DEFS: -DFUZZ_ANY_RANGE (the checks held back for problems spanning more than 2^400)
# turn on the checks held back for open defects (README, "Reliability"); a
# clean rebuild of build/fuzz is needed after changing them.
FUZZ_DEFS ?=
FUZZ_CFLAGS := $(WARN) -O1 -ffp-contract=off $(FUZZ_SAN) -Ilibisect/include -Itests/fuzz $(FUZZ_DEFS)
FUZZ_NAMES := shape spawn mesh mesh_parity polygon2 corpus winding
FUZZ_BINS := $(FUZZ_NAMES:%=$(FZ)/fuzz_%)
FUZZ_OBJS := $(SRCS:libisect/src/%.c=$(FZ)/obj/%.o)
FUZZ_LIB := $(FZ)/libisect.a
FUZZ_COMMON := $(FZ)/common/fuzz_input.o $(FZ)/common/fuzz_checks.o
# The corpus runner's sources; its main() is renamed corpus_runner_main so
# the harness can run whole files through it.
FUZZ_RUNNER_OBJS := $(RUNNER_SRCS:tests/c/%.c=$(FZ)/runner/%.o)

.PHONY: fuzz fuzz-build fuzz-seeds

$(FZ)/obj/%.o: libisect/src/%.c $(HDRS)
	@mkdir -p $(@D)
	$(FUZZ_CC) $(LIBCFLAGS) $(FUZZ_SAN) -fsanitize=fuzzer-no-link -c $< -o $@

$(FUZZ_LIB): $(FUZZ_OBJS)
	rm -f $@
	ar rcs $@ $(FUZZ_OBJS)

$(FZ)/common/%.o: tests/fuzz/%.c $(wildcard tests/fuzz/*.h) libisect/include/isect.h
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link -c $< -o $@

$(FZ)/runner/%.o: tests/c/%.c $(wildcard tests/c/*.h) libisect/include/isect.h
	@mkdir -p $(@D)
	$(FUZZ_CC) $(FUZZ_CFLAGS) $(CJSON_CFLAGS) -Itests/c -fsanitize=fuzzer-no-link \
	    -Dmain=corpus_runner_main -c $< -o $@

$(FZ)/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_COMMON) $(FUZZ_LIB)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer $< -o $@ $(FUZZ_COMMON) $(FUZZ_LIB) -lm

$(FZ)/fuzz_corpus: tests/fuzz/fuzz_corpus.c $(FUZZ_COMMON) $(FUZZ_RUNNER_OBJS) $(FUZZ_LIB)
	$(FUZZ_CC) $(FUZZ_CFLAGS) $(CJSON_CFLAGS) -Itests/c -fsanitize=fuzzer $< -o $@ \
	    $(FUZZ_COMMON) $(FUZZ_RUNNER_OBJS) $(FUZZ_LIB) $(CJSON) -lm

# Seeds: a few small inputs per harness, decoded from the golden cases.
$(FZ)/seeds/.stamp: tests/fuzz/make_seeds.py $(wildcard tests/cases/*.json)
	rm -rf $(FZ)/seeds
	python3 tests/fuzz/make_seeds.py tests/cases $(FZ)/seeds
	touch $@
fuzz-seeds: $(FZ)/seeds/.stamp

fuzz-build: $(FUZZ_BINS) $(FZ)/seeds/.stamp

# Every harness runs even after one fails; make fails at the end.
fuzz: fuzz-build
	@fail=0; for h in $(FUZZ_NAMES); do \
	    sh scripts/run_fuzz.sh $(FZ) $$h $(FUZZ_SECONDS) || fail=1; done; exit $$fail
