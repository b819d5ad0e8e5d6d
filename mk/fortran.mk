# SPDX-License-Identifier: Apache-2.0
# mk/fortran.mk — the Fortran module, its tests, the C and Fortran examples,
# and the ABI check. Included at the end of the top-level Makefile, whose
# variables (B, SONAME, VERSION, WARN, PYTHON, DESTDIR, PREFIX, LIBDIR,
# INCLUDEDIR) and targets (lib, install, uninstall) it uses.
#
#   make fortran        build/fortran/isect.mod and libisect_fortran.a
#   make test-fortran   build the Fortran tests and the examples (make test)
#   make check-fortran  build and run them, the flat-corpus sync check, the
#                       installed-examples test and the ABI check
#   make flat-corpus    re-export tests/cases/flat/*.txt after the JSON changed
#   make abi-baseline   rewrite libisect/abi/libisect.so.1.abi (only when an
#                       ABI change is intended: a new release's additions)
#   make install        also installs isect.mod, isect.f90, libisect_fortran.a
#                       and isect-fortran.pc (see README.md, "Using libisect from Fortran")

# GNU make's built-in FC is f77; the module is Fortran 2008.
ifeq ($(origin FC),default)
FC := gfortran
endif
FFLAGS ?= -O2
FWARN := -std=f2008 -Wall -Wextra -Wpedantic -Werror
# Tests: no "floating-point exceptions are signalling" note at STOP (NaN and
# subnormal inputs raise flags on purpose).
FTESTFLAGS := -ffpe-summary=none
HAVE_FC := $(shell command -v $(FC) >/dev/null 2>&1 && echo yes)

FB := $(B)/fortran
# The installed module's object code (the Fortran forms and helpers are
# module procedures): a static library, so there is no second soname and no
# second ABI to keep; its code is a few thin wrappers.
FORTRAN_LIB := $(FB)/libisect_fortran.a
FORTRAN_MOD := $(FB)/isect.mod
FORTRAN_TESTS := $(FB)/test_layout $(FB)/test_forms $(FB)/corpus_runner
C_EXAMPLES := $(patsubst examples/c/%.c,$(B)/examples/c/%,$(wildcard examples/c/*.c))
FORTRAN_EXAMPLES := $(patsubst examples/fortran/%.f90,$(B)/examples/fortran/%,\
                      $(wildcard examples/fortran/*.f90))
# Link against the build tree's shared library, found at run time through
# the rpath (the binaries sit two levels below $(B)).
FORTRAN_LINK := -L$(B) -lisect -Wl,-rpath,'$$ORIGIN/..'

.PHONY: fortran test-fortran check-fortran install-fortran uninstall-fortran \
        abi-baseline flat-corpus examples

fortran: $(FORTRAN_LIB) $(FORTRAN_MOD)

# -fPIC: the archive may be linked into a shared object of the user's.
$(FB)/isect.o: bindings/fortran/isect.f90
	@mkdir -p $(@D)
	$(FC) $(FWARN) $(FFLAGS) -fPIC -J$(FB) -c $< -o $@
# gfortran writes isect.mod while compiling isect.o (and leaves it untouched
# when the interface did not change, so it may be older than the object).
$(FORTRAN_MOD): $(FB)/isect.o ;

$(FORTRAN_LIB): $(FB)/isect.o
	rm -f $@
	ar rcs $@ $<

# Test-only modules and objects live in $(FB)/tests, so that directory, not
# $(FB), is the one holding modules that are never installed.
$(FB)/tests/test_report.o: tests/fortran/test_report.f90
	@mkdir -p $(@D)
	$(FC) $(FWARN) $(FFLAGS) -J$(FB)/tests -c $< -o $@
$(FB)/tests/test_report.mod: $(FB)/tests/test_report.o ;

$(FB)/tests/layout_probe.o: tests/fortran/layout_probe.c libisect/include/isect.h
	@mkdir -p $(@D)
	$(CC) $(WARN) -O1 -Ilibisect/include -c $< -o $@

# Every Fortran test links the module's archive and the build tree's shared
# library (-lisect needs the unversioned link too); test_layout also the C
# probe of isect.h.
FORTRAN_TEST_DEPS := $(FB)/tests/test_report.o $(FB)/tests/test_report.mod \
                     $(FORTRAN_LIB) $(FORTRAN_MOD) $(B)/$(SONAME) $(B)/libisect.so

$(FB)/test_layout: tests/fortran/test_layout.f90 $(FB)/tests/layout_probe.o $(FORTRAN_TEST_DEPS)
	$(FC) $(FWARN) $(FFLAGS) $(FTESTFLAGS) -I$(FB) -I$(FB)/tests -J$(FB)/tests $< -o $@ \
	    $(FB)/tests/layout_probe.o $(FB)/tests/test_report.o $(FORTRAN_LIB) $(FORTRAN_LINK)

$(FB)/%: tests/fortran/%.f90 $(FORTRAN_TEST_DEPS)
	$(FC) $(FWARN) $(FFLAGS) $(FTESTFLAGS) -I$(FB) -I$(FB)/tests -J$(FB)/tests $< -o $@ \
	    $(FB)/tests/test_report.o $(FORTRAN_LIB) $(FORTRAN_LINK)

# The examples against the build tree (tests/install/test_installed.sh builds
# them again against an installed tree, through pkg-config).
$(B)/examples/c/%: examples/c/%.c $(B)/$(SONAME) $(B)/libisect.so
	@mkdir -p $(@D)
	$(CC) $(WARN) -O2 -Ilibisect/include $< -o $@ -L$(B) -lisect \
	    -Wl,-rpath,'$$ORIGIN/../..'
$(B)/examples/fortran/%: examples/fortran/%.f90 $(FORTRAN_LIB) $(FORTRAN_MOD) $(B)/$(SONAME) \
                          $(B)/libisect.so
	@mkdir -p $(@D)
	$(FC) $(FWARN) $(FFLAGS) -I$(FB) -J$(@D) $< -o $@ $(FORTRAN_LIB) -L$(B) -lisect \
	    -Wl,-rpath,'$$ORIGIN/../..'
examples: $(C_EXAMPLES) $(FORTRAN_EXAMPLES)

test-fortran: lib $(FORTRAN_TESTS) examples

# The steps scripts/run_tests.sh runs, for running them on their own.
check-fortran: test-fortran
	$(FB)/test_layout libisect/include/isect.h
	$(FB)/test_forms
	$(FB)/corpus_runner tests/cases/flat/*.txt
	$(PYTHON) tests/golden/export_flat.py --check
	sh tests/install/test_installed.sh
	sh tests/abi/check_abi.sh

# ---------------------------------------------------------------- install
# isect.mod goes next to isect.h, so the -I of `pkg-config --cflags isect`
# finds it, and isect.f90 beside it (the module's source, for a compiler
# that cannot read gfortran's .mod); isect-fortran.pc adds -lisect_fortran to
# isect's flags.
install: install-fortran
uninstall: uninstall-fortran

ifeq ($(HAVE_FC),yes)
install-fortran: $(FORTRAN_LIB) $(FORTRAN_MOD)
	install -d $(DESTDIR)$(INCLUDEDIR) $(DESTDIR)$(LIBDIR)/pkgconfig
	install -m 644 $(FORTRAN_MOD) $(DESTDIR)$(INCLUDEDIR)/isect.mod
	install -m 644 bindings/fortran/isect.f90 $(DESTDIR)$(INCLUDEDIR)/isect.f90
	install -m 644 $(FORTRAN_LIB) $(DESTDIR)$(LIBDIR)/libisect_fortran.a
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(LIBDIR)|' \
	    -e 's|@INCLUDEDIR@|$(INCLUDEDIR)|' -e 's|@VERSION@|$(VERSION)|' \
	    bindings/fortran/isect-fortran.pc.in > $(DESTDIR)$(LIBDIR)/pkgconfig/isect-fortran.pc
else
install-fortran:
	@echo "note: $(FC) not found; the Fortran module isect is not installed"
endif

uninstall-fortran:
	rm -f $(DESTDIR)$(INCLUDEDIR)/isect.mod $(DESTDIR)$(INCLUDEDIR)/isect.f90 \
	      $(DESTDIR)$(LIBDIR)/libisect_fortran.a \
	      $(DESTDIR)$(LIBDIR)/pkgconfig/isect-fortran.pc

# The Fortran runner's copy of the corpus (tests/golden/export_flat.py).
flat-corpus:
	$(PYTHON) tests/golden/export_flat.py

# ---------------------------------------------------------------- ABI
abi-baseline:
	sh tests/abi/check_abi.sh --update
