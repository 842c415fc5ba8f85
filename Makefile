# udar: explicit Lagrangian FEM for high-velocity impact.  `make help` lists the targets.
# Dependencies are Debian packages only (`make deps`); MPI is always linked
# (one rank is the serial run).

SHELL := /bin/bash
FC      := mpif90
PYTHON  := /usr/bin/python3
CHECK_JOBS ?= 2
BUILD   ?= release
# Built for the CPU that builds it (18 % faster than AVX2-only here, doc/design.md
# D1); `make ARCH=x86-64-v3` (AVX2 + FMA, every x86 server since 2013) for a binary
# that must also run on other CPUs, e.g. compute nodes unlike the login node.
ARCH    ?= native
HDF5_INC := -I/usr/include/hdf5/openmpi
HDF5_LIB := -L/usr/lib/x86_64-linux-gnu/hdf5/openmpi -lhdf5_fortran -lhdf5
LIBS    := $(HDF5_LIB) -lmetis

ifeq ($(BUILD),debug)
  FFLAGS := -O0 -g -fcheck=all -ffpe-trap=invalid,zero,overflow -fbacktrace -Wall -Wno-maybe-uninitialized
  EXE    := bin/udar-debug
else
  FFLAGS := -O3 -march=$(ARCH) -g -fno-math-errno -fno-trapping-math -flto=auto
  EXE    := bin/udar
endif
FFLAGS += -std=f2018 -ffree-line-length-none $(HDF5_INC)
BDIR   := build/$(BUILD)

# in dependency order (each object waits for the previous one's module)
SRC := src/core/kinds.f90 src/core/vectors.f90 src/core/ordering.f90 src/core/strings.f90 src/core/exact_sum.f90 src/core/hash.f90 src/core/files.f90 src/core/file_kind.f90 src/core/signals.f90 src/core/memory.f90 src/parallel/comms.f90 src/parallel/partition.f90 src/parallel/decomposition.f90 src/core/fatal.f90 src/core/log.f90 \
       src/core/version.f90 src/core/input_errors.f90 src/model/config.f90 src/io/nml_scan.f90 \
       src/io/deck.f90 src/io/gmsh_reader.f90 src/io/field_output.f90 src/io/history.f90 \
       src/contact/contact_search.f90 src/contact/contact_kernels.f90 src/twod/segment2.f90 src/contact/contact_faces.f90 src/model/contact_model.f90 src/model/domain.f90 src/model/run_state.f90 src/particles/particle_model.f90 src/io/checkpoint.f90 src/model/eos.f90 src/model/flow_models.f90 src/model/strength.f90 src/element/tet4.f90 src/twod/tri3.f90 src/element/hydro.f90 src/element/fracture.f90 src/particles/sph.f90 src/particles/particle_driver.f90 \
       src/element/element_shared.f90 src/element/element_driver.f90 src/twod/tri_driver.f90 src/solver/element_passes.f90 src/solver/nodal.f90 src/solver/setup.f90 src/parallel/distribution.f90 src/contact/contact_setup.f90 src/contact/contact_erosion.f90 src/contact/eroded_voids.f90 src/contact/contact_driver.f90 src/solver/run.f90
OBJ := $(patsubst src/%.f90,$(BDIR)/%.o,$(SRC))
MAIN_OBJ := $(BDIR)/main.o

UNIT_TESTS := $(patsubst tests/unit/%.f90,$(BDIR)/tests/%,$(wildcard tests/unit/test_*.f90))

ifeq ($(shell id -u),0)
  export OMPI_ALLOW_RUN_AS_ROOT=1
  export OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
endif
export OMPI_MCA_rmaps_base_oversubscribe=1

DEB_PKGS := gfortran make pkg-config openmpi-bin libopenmpi-dev libhdf5-openmpi-dev hdf5-tools \
            libmetis-dev gmsh python3-numpy python3-h5py python3-matplotlib slurm-wlm munge
SUDO := $(if $(filter 0,$(shell id -u)),,sudo)

.PHONY: all deps run check check-unit check-regression bench validate clean help meshes debug FORCE

all: deps-quiet $(EXE)

help:
	@echo "make deps      install missing Debian packages (no-op when all are present)"
	@echo "make all       build $(EXE) (BUILD=debug: bin/udar-debug with run-time checks)"
	@echo "make run       build, run the default deck (OFHC copper Taylor bar), print its result"
	@echo "make check     build, run every test; last line 'N passed, N failed'"
	@echo "make bench     ns per element-cycle and memory per element (not a test)"
	@echo "make validate  longer validation runs (results in doc/validation.md)"
	@echo "make meshes    generate every input/ mesh with gmsh"
	@echo "make clean     remove build products and generated meshes"

deps:
	@missing=""; for p in $(DEB_PKGS); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  $(SUDO) apt-get update -qq && \
	  $(SUDO) env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
	    -o DPkg::Lock::Timeout=600 $$missing; \
	fi

deps-quiet:
	@command -v $(FC) >/dev/null && command -v gmsh >/dev/null && [ -x $(PYTHON) ] && command -v slurmctld >/dev/null \
	  && [ -f /usr/include/metis.h ] && [ -d /usr/include/hdf5/openmpi ] || $(MAKE) --no-print-directory deps

# ---- build
# objects are rebuilt when the compiler or its flags change: a link-time
# optimized binary of objects built with different flags is a silent mix
FLAGS_STAMP := $(BDIR)/flags.stamp
$(FLAGS_STAMP): FORCE
	@mkdir -p $(BDIR)
	@echo '$(FC) $(FFLAGS)' | cmp -s - $@ || echo '$(FC) $(FFLAGS)' > $@
FORCE:

$(BDIR)/%.o: src/%.f90 $(FLAGS_STAMP)
	@mkdir -p $(dir $@) $(BDIR)/mod
	$(FC) $(FFLAGS) -J$(BDIR)/mod -I$(BDIR)/mod -c $< -o $@

# chain: object i needs object i-1 (module order)
define chain
$(word $(1),$(OBJ)): $(word $(shell expr $(1) - 1),$(OBJ))
endef
$(foreach i,$(shell seq 2 $(words $(OBJ))),$(eval $(call chain,$(i))))
$(MAIN_OBJ): $(lastword $(OBJ))

$(EXE): $(OBJ) $(MAIN_OBJ)
	@mkdir -p bin
	$(FC) $(FFLAGS) $^ $(LIBS) -o $@

debug:
	@$(MAKE) --no-print-directory BUILD=debug bin/udar-debug

TEST_SUPPORT := $(BDIR)/tests/unit_checks.o $(BDIR)/tests/unit_domains.o
$(BDIR)/tests/unit_checks.o: tests/unit/support/unit_checks.f90 $(FLAGS_STAMP)
	@mkdir -p $(dir $@)
	$(FC) $(FFLAGS) -J$(BDIR)/tests -c $< -o $@
$(BDIR)/tests/unit_domains.o: tests/unit/support/unit_domains.f90 $(OBJ)
	@mkdir -p $(dir $@)
	$(FC) $(FFLAGS) -I$(BDIR)/mod -J$(BDIR)/tests -c $< -o $@

$(BDIR)/tests/%: tests/unit/%.f90 $(OBJ) $(TEST_SUPPORT)
	@mkdir -p $(dir $@)
	$(FC) $(FFLAGS) -I$(BDIR)/mod -I$(BDIR)/tests -J$(BDIR)/tests $< $(OBJ) $(TEST_SUPPORT) $(LIBS) -o $@

# ---- meshes: gmsh .geo -> .msh beside it
GEO := $(wildcard input/*/*.geo tests/regression/*/*.geo)
MSH := $(GEO:.geo=.msh)
%.msh: %.geo
	gmsh -3 -format msh41 -v 2 $< -o $@ > $@.log 2>&1 || (cat $@.log; exit 1)
	@rm -f $@.log
# meshes made by a script (numpy: Debian's python)
MSH += tests/regression/deep_node/deep_node.msh
tests/regression/deep_node/deep_node.msh: tests/tools/deep_node_mesh.py
	$(PYTHON) $< $@
MSH += tests/regression/buried_particles/buried_particles.msh
tests/regression/buried_particles/buried_particles.msh: tests/tools/buried_cube_mesh.py tests/tools/deep_node_mesh.py
	$(PYTHON) $< $@
MSH += tests/regression/buried_particles/buried_particles_half.msh
tests/regression/buried_particles/buried_particles_half.msh: tests/tools/buried_cube_mesh.py tests/tools/deep_node_mesh.py
	$(PYTHON) $< $@ --half
# normal_cylinder.geo includes the oblique one: remesh when that changes
input/normal_cylinder/normal_cylinder.msh: input/oblique_cylinder/oblique_cylinder.geo
meshes: deps-quiet $(MSH)

# ---- run the default deck: OFHC copper Taylor bar (Johnson and Cook 1983)
run: all input/taylor_ofhc/taylor_ofhc.msh
	cd input/taylor_ofhc && ../../bin/udar taylor_ofhc.nml
	$(PYTHON) postproc/taylor.py input/taylor_ofhc/out/taylor_ofhc.h5 --axis z --wall 0 \
	  --reference-length 16.21e-3 --reference-diameter 13.56e-3

# ---- tests
check: deps-quiet
	@$(MAKE) --no-print-directory BUILD=release bin/udar
	@$(MAKE) --no-print-directory BUILD=debug bin/udar-debug build/debug/tests/.built
	@$(MAKE) --no-print-directory meshes
	@CHECK_JOBS=$(CHECK_JOBS) tests/run_tests.sh

build/debug/tests/.built: $(patsubst tests/unit/%.f90,build/debug/tests/%,$(wildcard tests/unit/test_*.f90))
	@touch $@

bench: all meshes
	@tests/bench.sh

validate: all meshes
	@tests/validate.sh

clean:
	rm -rf build bin tests/work $(MSH)
