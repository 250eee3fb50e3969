# Entry points promised by the README. Each installs what is missing, builds and runs.
BUILD ?= build
JOBS ?= 2
DEMO_OUT ?= demo-out
DEBS = cmake g++ make libsundials-dev libsuitesparse-dev libeigen3-dev libspectra-dev \
       libboost-program-options-dev libgtest-dev libyaml-cpp-dev libhdf5-dev gnuplot-nox \
       gmsh calculix-ccx pybind11-dev python3-dev python3-numpy python3-scipy python3-pytest \
       python3-matplotlib libopenmpi-dev openmpi-bin chromium libxml2-utils

.PHONY: deps build demo test bench work-precision docs format clean validate sanitize

deps:
	@missing=""; for p in $(DEBS); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  SUDO=""; [ "$$(id -u)" = 0 ] || SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing; \
	fi

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DEVAS_PYTHON=ON \
	  -DPython3_EXECUTABLE=/usr/bin/python3
	cmake --build $(BUILD) -j$(JOBS)

demo: build
	./scripts/demo.sh $(BUILD) $(DEMO_OUT)
	./$(BUILD)/evas study work-precision scenes/demo.yaml --t-end 0.05 --repeats 2 \
	  --out $(DEMO_OUT)/study --quiet
	@echo "work-precision diagram of the demo scene: $(DEMO_OUT)/study/study.png"
	./validation/engine/run.sh $(BUILD) $(DEMO_OUT)/validation
	./$(BUILD)/evas periodic validation/engine/engine.yaml --out $(DEMO_OUT)/periodic --overwrite --quiet
	@echo "steady cycle of the engine's Case 1 (evas periodic): $(DEMO_OUT)/periodic/results.h5"
	./$(BUILD)/evas run validation/engine/engine.yaml --initial $(DEMO_OUT)/periodic/state.yaml \
	  --out $(DEMO_OUT)/steady --overwrite --quiet
	@echo "six settled cycles of Case 1 (from the periodic state): $(DEMO_OUT)/steady/results.h5"
	./scripts/figures.sh $(BUILD) $(DEMO_OUT)/steady/results.h5 $(DEMO_OUT)/figures
	@echo "figures of the engine (evas plot): $(DEMO_OUT)/figures"
	./$(BUILD)/evas report $(DEMO_OUT)/steady/results.h5 --out $(DEMO_OUT)/report \
	  --overwrite > /dev/null
	@echo "report of the engine's Case 1, settled (evas report): $(DEMO_OUT)/report/index.html"
	./$(BUILD)/evas problem andrews --work-precision --out $(DEMO_OUT)/problems/andrews
	./$(BUILD)/evas problem car-axis --work-precision --out $(DEMO_OUT)/problems/car-axis
	./$(BUILD)/evas problem fekete --work-precision --out $(DEMO_OUT)/problems/fekete
	./$(BUILD)/evas problem crank --work-precision --out $(DEMO_OUT)/problems/crank
	./$(BUILD)/evas problem chemakzo --work-precision --out $(DEMO_OUT)/problems/chemakzo
	./$(BUILD)/evas problem transamp --work-precision --out $(DEMO_OUT)/problems/transamp
	./$(BUILD)/evas problem wheelset --work-precision --out $(DEMO_OUT)/problems/wheelset

# The paper's validation: Case 1 (soft mounts) vs Case 2 (rigid ground), main-bearing
# loads and their order spectra (docs/validation.md).
VALIDATION_OUT ?= validation-out
validate: build
	CONVERGED=1 ./validation/engine/run.sh $(BUILD) $(VALIDATION_OUT)
	./validation/engine/runup.sh $(BUILD) $(VALIDATION_OUT)/runup

# Every test (C++, CTest; Python, pytest), then the Python package installed
# (scripts/install_python.sh) and checked by calling it with each python3.
test: build
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS)
	./scripts/install_python.sh $(BUILD)

# Sanitizers and fuzzing (docs/fuzzing.md), run by CI after `make test`: the
# sanitizer subset of the suite and the evas program under ASan + UBSan, then a
# short libFuzzer run of every input reader; one clang build in $(SAN_BUILD).
SAN_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 8
sanitize: build
	JOBS=$(JOBS) ./scripts/sanitize.sh $(SAN_BUILD)
	JOBS=$(JOBS) EVAS_BIN=$(abspath $(BUILD))/evas ./scripts/fuzz.sh $(FUZZ_SECONDS) $(SAN_BUILD)

bench: build
	cmake --build $(BUILD) -j$(JOBS) --target evas_bench
	JOBS=$(JOBS) ./bench/baseline.sh $(BUILD)
	./$(BUILD)/bench/evas_bench docs/performance.md validation/engine/engine.yaml \
	  $(BUILD)/baseline/build/evas $(BUILD)/baseline/src/validation/engine/engine.yaml
	python3 bench/sweep_scaling.py $(BUILD) validation/engine/engine.yaml >> docs/performance.md

# Work-precision of every integrator on the paper's engine, Case 1 and Case 2
# (about 20 minutes), kept in docs/work-precision/ (tables, figures, CSV).
WP_OUT ?= work-precision-out
work-precision: build
	./validation/engine/work_precision.sh $(BUILD) $(WP_OUT)
	for c in 1 2; do for f in study.md study.csv study.png; do \
	  cp $(WP_OUT)/case$$c/$$f docs/work-precision/case$$c-$$f || exit 1; done; done

# Regenerate the parameter reference in docs/elements.md from the declarations.
docs: build
	tmp=$$(mktemp -d) && ./$(BUILD)/evas periodic validation/engine/engine.yaml --out $$tmp/periodic -q && \
	  ./$(BUILD)/evas run validation/engine/engine.yaml --initial $$tmp/periodic/state.yaml \
	    --out $$tmp/case1 -q && \
	  ./scripts/figures.sh $(BUILD) $$tmp/case1/results.h5 docs/figures && \
	  rm -f docs/figures/*.gp docs/figures/*.dat && rm -rf $$tmp
	{ sed '/<!-- BEGIN GENERATED: evas elements -->/q' docs/elements.md; \
	  ./$(BUILD)/evas elements | sed '1{/^# /d;}' | sed '1{/^$$/d;}'; \
	  echo '<!-- END GENERATED -->'; } > docs/elements.md.new && mv docs/elements.md.new docs/elements.md
	{ sed '/<!-- BEGIN GENERATED: evas run --help-settings -->/q' docs/user-guide.md; \
	  ./$(BUILD)/evas run --help-settings; \
	  sed -n '/<!-- BEGIN GENERATED: evas run --help-settings -->/,$$p' docs/user-guide.md | \
	    sed -n '/<!-- END GENERATED -->/,$$p'; } > docs/user-guide.md.new && \
	  mv docs/user-guide.md.new docs/user-guide.md

# Regenerate the validation engine's modal bodies kept in validation/bodies/
# (gmsh -> ccx -> evas, reduced to the node sets; docs/engine-bodies.md).
BODIES ?= crankshaft block
.PHONY: bodies
bodies: build
	for b in $(BODIES); do \
	  ./$(BUILD)/evas modal build validation/bodies/$$b.yaml --out validation/bodies || exit 1; done

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) $(DEMO_OUT) $(VALIDATION_OUT) $(WP_OUT)
