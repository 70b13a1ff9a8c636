# Makefile: builds fixray's host programs (rt-float, rt-fixed, rt-cmp) and runs the tests.
#
#   make            build/rt-float, build/rt-fixed, build/rt-cmp
#   make run        set up if needed, render stills of the intro headless with both builds
#   make test       set up if needed, build everything and run the test suite
#   make bench      render frames with both builds side by side and print ms per frame
#   make bench-subsample  full vs adaptive rendering: points traced, rays, time, PSNR
#   make bench-effects    effects on demand vs every effect forced on, per example scene
#   make scene-programs   compile each scene into its own program; code size; same frames
#   make fuzz [SECONDS=N] fuzz the scene parser, timeline and tracer (libFuzzer), N s per build
#   make soak [STEP=N]    every (Nth) frame of the intro, twice, both builds: same pictures, flat memory
#   make clean      remove build products (keeps the fetched libfixmath source in build/deps)
#
# Variants (object trees under build/obj/<variant>):
#   float, fixed          -O2, the programs users run
#   san-float, san-fixed  -O1 with AddressSanitizer + UBSan and numeric event counting: tests
#   fuzz-float, fuzz-fixed  clang -O1, libFuzzer + ASan + UBSan + numeric event counting

BUILD := build
CC ?= cc
ifeq ($(origin CC),default)
CC := gcc
endif

WARN := -Wall -Wextra -Werror -Wundef -Wstrict-prototypes -Wshadow
# One libfixmath configuration for the library and its callers: no 112 KB trig caches;
# overflow detection and rounding stay on.
FIXMATH_DEFS := -DFIXMATH_NO_CACHE
FIXMATH_VERSION := 0~20220222
FIXMATH_TARBALL := $(BUILD)/deps/libfixmath_$(FIXMATH_VERSION).orig.tar.xz
FIXMATH_DIR := $(BUILD)/deps/libfixmath
FIXMATH_STAMP := $(FIXMATH_DIR)/.extracted
FIXMATH_SRCS := fix16.c fix16_sqrt.c fix16_trig.c fix16_exp.c

BASE_CFLAGS := -std=c11 $(WARN) -ffp-contract=off -fno-strict-aliasing -g
CPPFLAGS := -Ifixed -Isrc -Iplatform -isystem $(FIXMATH_DIR)/libfixmath $(FIXMATH_DEFS)
OPT := -O2
SAN := -O1 -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
# The scene fuzzer: libFuzzer through clang, with ASan + UBSan and numeric event counting.
FUZZ_CC := clang
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all
FUZZ_CFLAGS := -O1 -fno-omit-frame-pointer -fsanitize=fuzzer-no-link $(FUZZ_SAN)

# The tracer core: the same sources in every variant.
CORE_SRCS := fixed/fx.c src/trace.c src/shapes.c src/scene.c src/render.c src/subsample.c src/noise.c \
             src/texture.c src/scn.c
# The intro is compiled into the programs from scenes/intro.scene by rt-scenec.
GEN := $(BUILD)/gen
APP_SRCS := src/app.c src/scn_parse.c src/image.c src/outpath.c platform/headless.c $(GEN)/scene_intro.c
TESTS := test_numeric test_shapes test_noise test_subsample test_scene
TEST_SRCS := $(patsubst %,tests/%.c,$(TESTS))

# On x86-64 the fixed core is compiled without access to floating-point registers: any float
# or double that creeps into it stops the build.
ifeq ($(shell uname -m),x86_64)
FIXED_CORE_GUARD := -mgeneral-regs-only
endif

HOST_PROGS := $(BUILD)/rt-float $(BUILD)/rt-fixed $(BUILD)/rt-cmp $(BUILD)/rt-scenec
SAN_PROGS := $(foreach v,san-float san-fixed,$(BUILD)/$(v)/rt $(addprefix $(BUILD)/$(v)/,$(TESTS)))

.PHONY: all run test bench bench-subsample bench-effects scene-programs clean distclean setup san \
        fuzz soak fuzz-progs
all: $(HOST_PROGS)
san: $(SAN_PROGS)
fuzz-progs: $(FUZZ_PROGS)

# ---- libfixmath: fetched through apt by setup.sh, SHA-256 checked, extracted here ------------
$(FIXMATH_TARBALL):
	./setup.sh

$(FIXMATH_STAMP): $(FIXMATH_TARBALL)
	rm -rf $(FIXMATH_DIR) && mkdir -p $(FIXMATH_DIR)
	tar -xJf $< -C $(FIXMATH_DIR) --exclude=.git
	touch $@

# ---- variants ------------------------------------------------------------------------------
# $(1) variant, $(2) REAL_FIXED, $(3) flags, $(4) extra flags for the core, $(5) FX_COUNT_EVENTS,
# $(6) compiler (default $(CC))
define variant
OBJ_$(1) := $(BUILD)/obj/$(1)
CORE_OBJS_$(1) := $$(patsubst %.c,$(BUILD)/obj/$(1)/%.o,$(CORE_SRCS))
APP_OBJS_$(1) := $$(patsubst %.c,$(BUILD)/obj/$(1)/%.o,$(APP_SRCS))
OTHER_OBJS_$(1) := $$(patsubst %.c,$(BUILD)/obj/$(1)/%.o,$(APP_SRCS) $(TEST_SRCS) src/tools/cmp.c src/tools/scenec.c tests/fuzz_scene.c)
FIXMATH_LIB_$(1) := $$(if $$(filter 1,$(2)),$(BUILD)/obj/$(1)/libfixmath.a)

$$(CORE_OBJS_$(1)): $(BUILD)/obj/$(1)/%.o: %.c | $(FIXMATH_STAMP)
	@mkdir -p $$(@D)
	$(or $(6),$(CC)) $(BASE_CFLAGS) $(3) $(4) $(CPPFLAGS) -DREAL_FIXED=$(2) -DFX_COUNT_EVENTS=$(5) -MMD -MP -c $$< -o $$@

$$(OTHER_OBJS_$(1)): $(BUILD)/obj/$(1)/%.o: %.c | $(FIXMATH_STAMP)
	@mkdir -p $$(@D)
	$(or $(6),$(CC)) $(BASE_CFLAGS) $(3) $(CPPFLAGS) -DREAL_FIXED=$(2) -DFX_COUNT_EVENTS=$(5) -MMD -MP -c $$< -o $$@

# libfixmath is third-party code: the same optimisation and configuration, its own warnings.
$(BUILD)/obj/$(1)/libfixmath/%.o: $(FIXMATH_STAMP)
	@mkdir -p $$(@D)
	$(or $(6),$(CC)) -std=c11 $(3) $(FIXMATH_DEFS) -w -c $(FIXMATH_DIR)/libfixmath/$$*.c -o $$@

$(BUILD)/obj/$(1)/libfixmath.a: $$(patsubst %.c,$(BUILD)/obj/$(1)/libfixmath/%.o,$(FIXMATH_SRCS))
	rm -f $$@ && ar rcs $$@ $$^

-include $$(CORE_OBJS_$(1):.o=.d) $$(OTHER_OBJS_$(1):.o=.d)
endef

$(eval $(call variant,float,0,$(OPT),,0))
$(eval $(call variant,fixed,1,$(OPT),$(FIXED_CORE_GUARD),0))
$(eval $(call variant,san-float,0,$(SAN),,1))
$(eval $(call variant,san-fixed,1,$(SAN),,1))
$(eval $(call variant,fuzz-float,0,$(FUZZ_CFLAGS),,1,$(FUZZ_CC)))
$(eval $(call variant,fuzz-fixed,1,$(FUZZ_CFLAGS),,1,$(FUZZ_CC)))

LIBS := -lpng -lm

$(BUILD)/rt-float: $(CORE_OBJS_float) $(APP_OBJS_float)
	$(CC) $(OPT) -o $@ $^ $(LIBS)

$(BUILD)/rt-fixed: $(CORE_OBJS_fixed) $(APP_OBJS_fixed) $(FIXMATH_LIB_fixed)
	$(CC) $(OPT) -o $@ $^ $(LIBS)

$(BUILD)/rt-cmp: $(BUILD)/obj/float/src/tools/cmp.o $(BUILD)/obj/float/src/image.o $(BUILD)/obj/float/src/outpath.o
	$(CC) $(OPT) -o $@ $^ $(LIBS)

# The scene compiler runs at build time, so it is built from the float objects.
$(BUILD)/rt-scenec: $(BUILD)/obj/float/src/tools/scenec.o $(BUILD)/obj/float/src/scn_parse.o \
                   $(BUILD)/obj/float/src/outpath.o $(CORE_OBJS_float)
	$(CC) $(OPT) -o $@ $^ -lm

$(GEN)/scene_intro.c: scenes/intro.scene $(BUILD)/rt-scenec
	@mkdir -p $(@D)
	$(BUILD)/rt-scenec $< -o $@ --name scn_intro

define san_progs
$(BUILD)/$(1)/rt: $$(CORE_OBJS_$(1)) $$(APP_OBJS_$(1)) $$(FIXMATH_LIB_$(1))
	@mkdir -p $$(@D)
	$$(CC) $(SAN) -o $$@ $$^ $(LIBS)

$(BUILD)/$(1)/test_%: $(BUILD)/obj/$(1)/tests/test_%.o $(BUILD)/obj/$(1)/src/scn_parse.o $$(CORE_OBJS_$(1)) $$(FIXMATH_LIB_$(1))
	@mkdir -p $$(@D)
	$$(CC) $(SAN) -o $$@ $$^ -lcmocka -lm
endef
$(eval $(call san_progs,san-float))
$(eval $(call san_progs,san-fixed))

# build/fuzz-<real>/fuzz_scene: the scene parser, timeline and tracer under libFuzzer.
define fuzz_prog
$(BUILD)/$(1)/fuzz_scene: $(BUILD)/obj/$(1)/tests/fuzz_scene.o $(BUILD)/obj/$(1)/src/scn_parse.o $$(CORE_OBJS_$(1)) $$(FIXMATH_LIB_$(1))
	@mkdir -p $$(@D)
	$(FUZZ_CC) -fsanitize=fuzzer $(FUZZ_SAN) -o $$@ $$^ -lm
endef
$(eval $(call fuzz_prog,fuzz-float))
$(eval $(call fuzz_prog,fuzz-fixed))
FUZZ_PROGS := $(BUILD)/fuzz-float/fuzz_scene $(BUILD)/fuzz-fixed/fuzz_scene


# ---- user commands -------------------------------------------------------------------------
setup:
	@./setup.sh

# Stills of the intro, one per part, rendered by both builds and compared (the player is
# issue [sdl]); then the traced points of one of them.
INTRO_STILLS := 8 17 25 35 44
run: setup
	@$(MAKE) --no-print-directory all
	@mkdir -p $(BUILD)/out
	@for t in $(INTRO_STILLS); do \
	  $(BUILD)/rt-fixed render --size 640x480 --time $$t -o $(BUILD)/out/intro-$$t-fixed.png || exit 1; \
	  $(BUILD)/rt-float render --size 640x480 --time $$t -o $(BUILD)/out/intro-$$t-float.png || exit 1; \
	  printf 'intro t=%ss, fixed vs float: ' $$t; \
	  $(BUILD)/rt-cmp $(BUILD)/out/intro-$$t-fixed.png $(BUILD)/out/intro-$$t-float.png || exit 1; \
	done
	$(BUILD)/rt-fixed render --size 640x480 --time 35 --show-samples --stats -o $(BUILD)/out/intro-35-samples.png
	@echo "run: intro stills in $(BUILD)/out/intro-T-fixed.png and intro-T-float.png (T = $(INTRO_STILLS) s); intro-35-samples.png shows the points adaptive subsampling traced"

test: setup
	@$(MAKE) --no-print-directory all san fuzz-progs
	@tests/run.sh

SECONDS ?= 60
fuzz: setup
	@$(MAKE) --no-print-directory fuzz-progs
	@tests/fuzz.sh $(SECONDS)

STEP ?= 1
soak: setup
	@$(MAKE) --no-print-directory all
	@tests/soak.sh $(STEP)

bench: setup
	@$(MAKE) --no-print-directory all
	@tests/bench.sh

bench-subsample: setup
	@$(MAKE) --no-print-directory all
	@tests/bench_subsample.sh

bench-effects: setup
	@$(MAKE) --no-print-directory all
	@tests/bench_effects.sh

scene-programs: setup
	@$(MAKE) --no-print-directory all
	@tests/scene_programs.sh --check

clean:
	rm -rf $(BUILD)/obj $(BUILD)/san-float $(BUILD)/san-fixed $(BUILD)/out $(BUILD)/test $(BUILD)/gen \
	       $(BUILD)/scenes $(BUILD)/bench $(BUILD)/fuzz-float $(BUILD)/fuzz-fixed $(BUILD)/soak $(HOST_PROGS)

distclean:
	rm -rf $(BUILD)
