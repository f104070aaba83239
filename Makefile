# SPDX-License-Identifier: GPL-2.0-or-later
#
# The one entry point.
#   make            install missing dependencies, build everything, link bin/ lib/
#   make test       build, then run every test (ctest, then pytest); ends with
#                   the outcome counts per area (scripts/test.sh).  A skip not
#                   in tests/skips.txt, or an area without tests, fails it.
#   make demo       the main job (see README)
#   make bench      speed figures next to their anchors (not part of `make test`)
#   make compat     LinuxCNC 2.9's sample configurations on our HAL (docs/compat.md;
#                   not part of `make test`; COMPAT_ARGS passes options)
#   make lint       HDL through Verilator/Icarus/yosys, Python through black
#   make memcheck   valgrind memcheck over the C unit tests and a hostmot2 +
#                   hm2_sim HAL session (non-sanitized build/)
#   SANITIZE=1      build host code with ASan+UBSan into build-san/ (CI does this)
#   JOBS=n          parallel build jobs (default: number of cores)

SHELL := /bin/bash
ROOT := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))
JOBS ?= $(shell nproc)

# BUILD may be overridden (several developers sharing one tree each keep a
# private build dir); bin/ and lib/ at the repo root link to the default one.
ifeq ($(SANITIZE),1)
BUILD ?= $(ROOT)/build-san
CMAKE_FLAGS += -DSANITIZE=ON
else
BUILD ?= $(ROOT)/build
endif
export HM_BUILD := $(BUILD)
DEFAULT_BUILD := $(filter $(ROOT)/build $(ROOT)/build-san,$(BUILD))

# Every recipe runs with the venv's Verilator 5.048 and $(BUILD)/bin first on PATH.
ENV := source $(ROOT)/scripts/env.sh &&
PYTEST_ARGS ?=

.PHONY: all deps build test test-host demo bench lint memcheck clean distclean fuzz compat

all: build

deps: $(ROOT)/.venv/.pinned
$(ROOT)/.venv/.pinned: $(ROOT)/scripts/setup.sh
	bash $(ROOT)/scripts/setup.sh

build: deps
	@$(ENV) cmake -S $(ROOT) -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo $(CMAKE_FLAGS) >/dev/null
	@$(ENV) cmake --build $(BUILD) -j $(JOBS)
ifneq ($(DEFAULT_BUILD),)
	@ln -sfn $(BUILD)/bin $(ROOT)/bin
	@ln -sfn $(BUILD)/lib $(ROOT)/lib
endif
	@echo "build: ok ($(BUILD)); put $(ROOT)/bin on PATH or run: . scripts/env.sh"

# C unit tests first, then everything pytest collects (cocotb, HAL regression,
# end-to-end, docs examples), then the per-area counts.
test: build
	@$(ENV) SANITIZE=$(SANITIZE) JOBS=$(JOBS) PYTEST_ARGS="$(PYTEST_ARGS)" bash $(ROOT)/scripts/test.sh

test-host: build
	@$(ENV) cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

demo: build
	@$(ENV) bash $(ROOT)/scripts/demo.sh

bench: build
	@$(ENV) bash $(ROOT)/bench/run.sh

compat: build
	@$(ENV) cd $(ROOT) && python tests/compat/compat.py $(COMPAT_ARGS)

lint: deps
	@$(ENV) bash $(ROOT)/scripts/lint.sh

# valgrind needs the non-sanitized build (build/, whatever SANITIZE says).
memcheck: deps
	@$(MAKE) --no-print-directory build SANITIZE= BUILD=$(ROOT)/build
	@$(ENV) HM_BUILD=$(ROOT)/build python $(ROOT)/scripts/memcheck.py --build $(ROOT)/build

fuzz: deps
	@$(ENV) bash $(ROOT)/scripts/fuzz.sh

clean:
	rm -rf $(ROOT)/build $(ROOT)/build-san $(ROOT)/bin $(ROOT)/lib

distclean: clean
	rm -rf $(ROOT)/.venv
