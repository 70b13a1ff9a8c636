# Makefile: builds fixray's host programs (rt-float, rt-fixed, rt-cmp, rt-scenec, rt-edges) and runs the tests.
#
#   make            build/rt-float, build/rt-fixed, build/rt-fixed16, build/rt-cmp, build/rt-edges,
#                   the intro players
#   make run        set up if needed, play the intro in a window (without a display: render it
#                   headless into build/out/intro/ with progress lines, fps, fixed vs float stills)
#   make test       set up if needed, build everything and run the test suite (tests/run.sh)
#   make check      the fast inner loop: the unit tests and a few host frames (tests/run.sh unit frames)
#   make quality    adaptive and probe mode against full mode on every example and hard scene,
#                   both builds: a table, and docs/quality.md
#   make bench      the intro's frames per second per platform, one table in docs/bench.md: desktop
#                   (320x240 and 640x480, both builds, 1 thread and every core), the ARM926 and
#                   the Cortex-M3 and M0 under QEMU (instructions per frame, fps at 200, 50, 16 and
#                   133 MHz);
#                   QUICK=1: a smoke run
#   make bench-demo the demo scene's ms per frame, both builds side by side
#   make tradeoff   accuracy against cost: render options one at a time, float, fixed and fixed16,
#                   PSNR against the reference, ms per frame and ARM926 instructions per frame
#                   (QEMU): docs/tradeoff.md and a plot; QUICK=1: smoke
#   make bench-subsample  full vs adaptive rendering: points traced, rays, time, PSNR
#   make bench-effects    effects on demand vs every effect forced on, per example scene
#   make bench-modes      full, adaptive and probe mode: exact instruction counts (callgrind on
#                   both desktop builds, QEMU icount on the ARM926) and the desktop's tracing time
#   make scene-programs   compile each scene into its own program; code size; same frames
#   make docs-images      render the pictures of README.md and docs/ again (make test checks them)
#   make arm        build/arm/intro-fixed.elf and intro-float.elf (ARM926, bare metal); sizes
#   make qemu       play the ARM intro in QEMU's window (REAL=float: the soft-float image)
#   make qemu-frames FRAMES="0 250 500" [REAL=fixed|float]   intro frames rendered under QEMU
#                   (both: SETTINGS="--octaves 2 --grid 4 ...", render's settings, on the board)
#   make qemu-bench instructions per intro frame under QEMU, fixed vs soft-float (and the cycle
#                   model's estimate beside them)
#   make qemu-profile [FRAMES="425 875"] [REAL=fixed|float|fixed16|m3|m0] [SETTINGS=...]  where the
#                   board's cycles and instructions go: per function inside the frames, ranked by
#                   the core's cycle model (ARM926; m3, m0: the Cortex-M3 and M0 images), with CPI
#                   and D-cache misses (a QEMU TCG plugin)
#   make test-cycles the cycle model against hand-counted programs (tests/cycles.sh)
#   make arm-text-order  rewrite platform/arm/text-order.ld (hot functions first) from a profile
#   make m3         build/m3/intro-fixed.elf (Cortex-M3, QEMU lm3s6965evb, 128x64 OLED); sizes
#   make qemu-m3    play the intro on the emulated OLED in QEMU's window
#   make qemu-m3-frames FRAMES="0 425 875"   128x64 frames rendered band by band on the M3
#   make m0         build/m0/intro-fixed.elf (Cortex-M0, QEMU microbit, 16 KiB of SRAM); its sizes
#   make qemu-m0-frames FRAMES="0 425 875"   the same frames rendered on the M0, 16 KiB of RAM
#                   (instructions and the Cortex-M0 cycle model's cycles per frame)
#   make stress     the randomised property test (tests/test_stability.c) at -O2 in both builds,
#                   STRESS_RAYS rays per shape (default 20,000,000)
#   make fuzz [SECONDS=N] every libFuzzer target N s each: the scene parser, timeline and tracer
#                   (both builds), the command line, the image readers, the render settings; then
#                   the corpus's scenes through release and event-counting rt-fixed (same bytes)
#   make soak [STEP=N]    every (Nth) frame of the intro, twice, both builds: same pictures, flat memory
#   make clean      remove build products (keeps the fetched libfixmath source in build/deps)
#
# Variants (object trees under build/obj/<variant>):
#   float, fixed          -O2, the programs users run
#   fixed16               -O2, fixed point with unit vectors in Q16.16 (-DFX_UNIT_FRAC=16): the
#                         cheaper, less precise variant (docs/numerics.md)
#   san-float, san-fixed, san-fixed16  -O1 with AddressSanitizer + UBSan and numeric event
#                         counting: tests
#   san-fixed-sd          san-fixed with the ARM926's division-free path (-DFX_SOFT_DIVIDE=1)
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
CPPFLAGS := -Ifixed -Isrc/core -Isrc/scene -Isrc/app -Iplatform -isystem $(FIXMATH_DIR)/libfixmath $(FIXMATH_DEFS)
OPT := -O2
SAN := -O1 -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
# The scene fuzzer: libFuzzer through clang, with ASan + UBSan and numeric event counting.
FUZZ_CC := clang
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all
FUZZ_CFLAGS := -O1 -fno-omit-frame-pointer -fsanitize=fuzzer-no-link $(FUZZ_SAN)

# The tracer core (src/core/, fixed/) and the integer-only scene code that every program,
# the boards included, runs: the timeline and the render settings (src/scene/). The same
# sources in every variant.
SUBSAMPLE_SRCS := src/core/subsample.c src/core/subsample_split.c src/core/subsample_fill.c \
                  src/core/subsample_shortcut.c src/core/subsample_local.c
TRACER_SRCS := fixed/fx.c src/core/trace.c src/core/shapes.c src/core/prepare.c src/core/camera.c \
               src/core/render.c $(SUBSAMPLE_SRCS) src/core/probe.c src/core/noise.c src/core/texture.c
SCENE_SRCS := src/scene/scn.c src/scene/knobs.c
CORE_SRCS := $(TRACER_SRCS) $(SCENE_SRCS)
# The intro is compiled into the programs from scenes/intro.scene by rt-scenec.
GEN := $(BUILD)/gen
APP_SRCS := src/app/app.c src/app/cli.c src/app/play.c src/app/frame.c src/scene/scn_parse.c src/scene/scn_lex.c \
            src/app/image.c src/app/outpath.c platform/headless.c platform/threads.c platform/sdl.c $(GEN)/scene_intro.c
# SDL2 (the player's window), asked of pkg-config when a recipe runs: after setup.sh.
SDL_CFLAGS = $(shell pkg-config --cflags sdl2)
SDL_LIBS = $(shell pkg-config --libs sdl2)
TESTS := test_numeric test_shapes test_noise test_subsample test_scene test_stability test_optics
# Tests of the fixed-point format itself, built in san-fixed and san-fixed16.
FIXED_TESTS := test_format
TEST_SRCS := $(patsubst %,tests/%.c,$(TESTS) $(FIXED_TESTS))
# The cheaper fixed-point variant: unit in Q16.16 instead of Q2.30.
FIXED16_DEFS := -DFX_UNIT_FRAC=16
# The ARM926's division-free path (FX_SOFT_DIVIDE, fixed/real_fixed.h) on the host: san-fixed-sd.
SOFT_DIVIDE_DEFS := -DFX_SOFT_DIVIDE=1
SOFT_DIVIDE_TESTS := test_numeric test_shapes test_subsample

# On x86-64 the fixed core is compiled without access to floating-point registers: any float
# or double that creeps into it stops the build.
ifeq ($(shell uname -m),x86_64)
FIXED_CORE_GUARD := -mgeneral-regs-only
endif

HOST_PROGS := $(BUILD)/rt-float $(BUILD)/rt-fixed $(BUILD)/rt-fixed16 $(BUILD)/rt-cmp $(BUILD)/rt-scenec \
              $(BUILD)/rt-edges
SAN_PROGS := $(foreach v,san-float san-fixed,$(BUILD)/$(v)/rt $(addprefix $(BUILD)/$(v)/,$(TESTS))) \
             $(BUILD)/san-fixed16/rt $(foreach v,san-fixed san-fixed16,$(addprefix $(BUILD)/$(v)/,$(FIXED_TESTS))) \
             $(addprefix $(BUILD)/san-fixed-sd/,rt $(SOFT_DIVIDE_TESTS))

.PHONY: all run test check quality bench bench-demo tradeoff bench-subsample bench-effects bench-modes scene-programs docs-images stress clean distclean setup san \
        setup-arm setup-test setup-gui arm arm-file-flags qemu qemu-frames qemu-bench qemu-profile test-cycles arm-text-order fuzz soak fuzz-progs m3 qemu-m3 qemu-m3-frames m0 qemu-m0-frames
all: $(HOST_PROGS)
san: $(SAN_PROGS)

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
OTHER_OBJS_$(1) := $$(patsubst %.c,$(BUILD)/obj/$(1)/%.o,$(APP_SRCS) $(TEST_SRCS) src/scene/scn_cwrite.c src/tools/cmp.c src/tools/scenec.c src/tools/topt.c src/tools/edges.c platform/null.c tests/fuzz_scene.c \
                   tests/fuzz_cli.c tests/fuzz_image.c tests/fuzz_knobs.c)
FIXMATH_LIB_$(1) := $$(if $$(filter 1,$(2)),$(BUILD)/obj/$(1)/libfixmath.a)

$$(CORE_OBJS_$(1)): $(BUILD)/obj/$(1)/%.o: %.c | $(FIXMATH_STAMP)
	@mkdir -p $$(@D)
	$(or $(6),$(CC)) $(BASE_CFLAGS) $(3) $(4) $(CPPFLAGS) -DREAL_FIXED=$(2) -DFX_COUNT_EVENTS=$(5) -MMD -MP -c $$< -o $$@

$$(OTHER_OBJS_$(1)): $(BUILD)/obj/$(1)/%.o: %.c | $(FIXMATH_STAMP)
	@mkdir -p $$(@D)
	$(or $(6),$(CC)) $(BASE_CFLAGS) $(3) $(CPPFLAGS) $$(SDL_CFLAGS) -DREAL_FIXED=$(2) -DFX_COUNT_EVENTS=$(5) -MMD -MP -c $$< -o $$@

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
$(eval $(call variant,fixed16,1,$(OPT) $(FIXED16_DEFS),$(FIXED_CORE_GUARD),0))
$(eval $(call variant,san-float,0,$(SAN),,1))
$(eval $(call variant,san-fixed,1,$(SAN),,1))
$(eval $(call variant,san-fixed16,1,$(SAN) $(FIXED16_DEFS),,1))
$(eval $(call variant,san-fixed-sd,1,$(SAN) $(SOFT_DIVIDE_DEFS),,1))
$(eval $(call variant,fuzz-float,0,$(FUZZ_CFLAGS),,1,$(FUZZ_CC)))
$(eval $(call variant,fuzz-fixed,1,$(FUZZ_CFLAGS),,1,$(FUZZ_CC)))

# The programs with a window (rt-float, rt-fixed: play; the intro players) link SDL2 through
# platform/sdl.c; the tools never open one and link the null display, platform/null.c.
TOOL_LIBS := -lpng -lm -lpthread
LIBS = $(TOOL_LIBS) $(SDL_LIBS)

$(BUILD)/rt-float: $(CORE_OBJS_float) $(APP_OBJS_float)
	$(CC) $(OPT) -o $@ $^ $(LIBS)

$(BUILD)/rt-fixed: $(CORE_OBJS_fixed) $(APP_OBJS_fixed) $(FIXMATH_LIB_fixed)
	$(CC) $(OPT) -o $@ $^ $(LIBS)

$(BUILD)/rt-fixed16: $(CORE_OBJS_fixed16) $(APP_OBJS_fixed16) $(FIXMATH_LIB_fixed)
	$(CC) $(OPT) -o $@ $^ $(LIBS)

$(BUILD)/rt-cmp: $(BUILD)/obj/float/src/tools/cmp.o $(BUILD)/obj/float/src/tools/topt.o \
                $(BUILD)/obj/float/src/scene/knobs.o \
                $(BUILD)/obj/float/src/app/image.o $(BUILD)/obj/float/src/app/outpath.o
	$(CC) $(OPT) -o $@ $^ $(TOOL_LIBS)

# The scene compiler runs at build time, so it is built from the float objects.
$(BUILD)/rt-scenec: $(BUILD)/obj/float/src/tools/scenec.o $(BUILD)/obj/float/src/tools/topt.o \
                   $(BUILD)/obj/float/src/scene/scn_parse.o $(BUILD)/obj/float/src/scene/scn_lex.o \
                   $(BUILD)/obj/float/src/scene/scn_cwrite.o \
                   $(BUILD)/obj/float/src/app/outpath.o $(CORE_OBJS_float)
	$(CC) $(OPT) -o $@ $^ -lm

# The subsampling bound (tests/bench_subsample.sh): float, like the reference it measures.
# The command line of render (src/app/cli.c) over the headless platform and the null display.
EDGES_SRCS := src/tools/edges.c src/scene/scn_parse.c src/scene/scn_lex.c src/app/cli.c \
              src/app/image.c src/app/outpath.c platform/headless.c platform/threads.c platform/null.c
$(BUILD)/rt-edges: $(patsubst %.c,$(BUILD)/obj/float/%.o,$(EDGES_SRCS)) $(CORE_OBJS_float)
	$(CC) $(OPT) -o $@ $^ $(TOOL_LIBS)

$(GEN)/scene_intro.c: scenes/intro.scene $(BUILD)/rt-scenec
	@mkdir -p $(@D)
	$(BUILD)/rt-scenec $< -o $@ --name scn_intro

define san_progs
$(BUILD)/$(1)/rt: $$(CORE_OBJS_$(1)) $$(APP_OBJS_$(1)) $$(FIXMATH_LIB_$(1))
	@mkdir -p $$(@D)
	$$(CC) $(SAN) -o $$@ $$^ $$(LIBS)

$(BUILD)/$(1)/test_%: $(BUILD)/obj/$(1)/tests/test_%.o $(BUILD)/obj/$(1)/src/scene/scn_parse.o \
                     $(BUILD)/obj/$(1)/src/scene/scn_lex.o $$(CORE_OBJS_$(1)) $$(FIXMATH_LIB_$(1))
	@mkdir -p $$(@D)
	$$(CC) $(SAN) -o $$@ $$^ -lcmocka -lm
endef
$(eval $(call san_progs,san-float))
$(eval $(call san_progs,san-fixed))
$(eval $(call san_progs,san-fixed16))
$(eval $(call san_progs,san-fixed-sd))

# The randomised property test at -O2, for long runs (make stress).
$(BUILD)/stress-float: $(BUILD)/obj/float/tests/test_stability.o $(CORE_OBJS_float)
	$(CC) $(OPT) -o $@ $^ -lcmocka -lm
$(BUILD)/stress-fixed: $(BUILD)/obj/fixed/tests/test_stability.o $(CORE_OBJS_fixed) $(FIXMATH_LIB_fixed)
	$(CC) $(OPT) -o $@ $^ -lcmocka -lm


# ---- the intro players (build/intro-fixed, build/intro-float): the original's 64 kB limit -----
# The intro in a window and nothing else (src/app/player.c over play.c). Built for size: unused
# functions dropped, no unwind tables, the numeric layer and the shapes at -O2 and the rest at -Os
# (the shading, subsampling, textures and noise too: the player needs the room; a desktop has
# speed to spare).
# The stripped file grows a page (4 KiB) at once when the code reaches the page its data starts
# on: the build prints how much room is left (readelf -lW build/intro-fixed: code end against RW
# start).
# Compiled -fno-pie, as they are linked (-no-pie): absolute addresses in the code (a 5-byte mov
# where position-independent code takes a 7-byte lea), constant tables of pointers read-only
# data instead of relocated data; -fno-plt: calls into SDL2, libpng and libc go through the GOT
# (bound at start-up), with no PLT stubs.
PLAYER_HOT := fixed/fx.c src/core/shapes.c src/core/probe.c
PLAYER_COLD := $(SUBSAMPLE_SRCS) src/core/trace.c src/core/texture.c src/core/noise.c src/core/prepare.c src/core/camera.c src/core/render.c src/scene/scn.c src/scene/knobs.c \
               src/app/cli.c src/app/play.c src/app/frame.c src/app/image.c src/app/player.c src/app/outpath.c \
               platform/headless.c platform/threads.c platform/sdl.c $(GEN)/scene_intro.c
PLAYER_CFLAGS := $(BASE_CFLAGS) -DCLI_PLAYER=1 -ffunction-sections -fdata-sections -fno-asynchronous-unwind-tables \
                 -fno-unwind-tables -fno-stack-protector -fno-pie -fno-plt -DRT_COMPILED_PROBE=0 -DRT_SHADOW_SETS=0 \
                 -DRT_PLANE_CULL=0 -DRT_FINE_DETAIL=0
PLAYER_LDFLAGS := -no-pie -Wl,--gc-sections -Wl,-z,noseparate-code -Wl,--build-id=none -Wl,--no-eh-frame-hdr
PLAYER_LIMIT := 65536
PLAYERS := $(BUILD)/intro-fixed $(BUILD)/intro-float

# $(1) real, $(2) REAL_FIXED, $(3) libfixmath archive or empty
define player
PLAYER_OBJS_$(1) := $$(patsubst %.c,$(BUILD)/obj/player-$(1)/%.o,$(PLAYER_HOT) $(PLAYER_COLD))
$$(patsubst %.c,$(BUILD)/obj/player-$(1)/%.o,$(PLAYER_HOT)): $(BUILD)/obj/player-$(1)/%.o: %.c Makefile | $(FIXMATH_STAMP)
	@mkdir -p $$(@D)
	$$(CC) $(PLAYER_CFLAGS) -O2 $(if $(filter 1,$(2)),$(FIXED_CORE_GUARD)) $(CPPFLAGS) -DREAL_FIXED=$(2) -DFX_COUNT_EVENTS=0 -MMD -MP -c $$< -o $$@
$$(patsubst %.c,$(BUILD)/obj/player-$(1)/%.o,$(PLAYER_COLD)): $(BUILD)/obj/player-$(1)/%.o: %.c Makefile | $(FIXMATH_STAMP)
	@mkdir -p $$(@D)
	$$(CC) $(PLAYER_CFLAGS) -Os $(CPPFLAGS) $$(SDL_CFLAGS) -DREAL_FIXED=$(2) -DFX_COUNT_EVENTS=0 -MMD -MP -c $$< -o $$@
$(BUILD)/intro-$(1): $$(PLAYER_OBJS_$(1)) $$(if $(3),$(BUILD)/obj/player-$(1)/libfixmath.a)
	$$(CC) $(PLAYER_LDFLAGS) -o $$@ $$^ $$(LIBS)
	@strip -o $$@.stripped $$@ && set -- $$$$(readelf -lW $$@ | awk '$$$$1 == "LOAD" { print $$$$2, $$$$5 }') && \
	  printf 'player %s: %d bytes stripped (limit %d), %d bytes of code room before the file grows a page\n' $$@ \
	    $$$$(stat -c %s $$@.stripped) $(PLAYER_LIMIT) $$$$(($$$$3 - $$$$1 - $$$$2)) && rm -f $$@.stripped
# libfixmath at -Os (rt-fixed has it at -O2; a desktop has speed to spare), one section per
# function: the unused ones are dropped.
$(BUILD)/obj/player-$(1)/libfixmath/%.o: $(FIXMATH_STAMP) Makefile
	@mkdir -p $$(@D)
	$$(CC) -std=c11 -Os -ffunction-sections -fdata-sections -fno-pie $(FIXMATH_DEFS) -w -c $(FIXMATH_DIR)/libfixmath/$$*.c -o $$@
$(BUILD)/obj/player-$(1)/libfixmath.a: $$(patsubst %.c,$(BUILD)/obj/player-$(1)/libfixmath/%.o,$(FIXMATH_SRCS))
	rm -f $$@ && ar rcs $$@ $$^
-include $$(PLAYER_OBJS_$(1):.o=.d)
endef
$(eval $(call player,fixed,1,$(BUILD)/obj/fixed/libfixmath.a))
$(eval $(call player,float,0,))
all: $(PLAYERS)

# ---- ARM926 images: bare metal for qemu-system-arm -M versatilepb (platform/arm/) ---------
# The same core, the intro compiled in, and src/app/intro.c (play, frames, bench) over the ARM
# backend. Fixed: libfixmath compiled from the same fetched source; float: soft-float.
ARM_CC := arm-none-eabi-gcc
ARM_ARCH := -mcpu=arm926ej-s -marm -mfloat-abi=soft
# The boards play only the scene compiled into them: rt_scene holds that many objects (not 32),
# which saves RAM (the intro has 7; src/app/intro.c refuses a compiled scene with more).
BOARD_MAX_OBJECTS := 16
ARM_CFLAGS := $(ARM_ARCH) -ffreestanding -ffunction-sections -fdata-sections -DRT_MAX_OBJECTS=$(BOARD_MAX_OBJECTS) \
              -DRT_FINE_DETAIL=0
# --use-blx: calls between ARM and Thumb code are single BLX instructions (the ARM926 has them)
# instead of the linker's interworking veneers (8 or 12 B each, two or three instructions more a
# call): about 300 B less in the fixed image, frames as before.
ARM_LDFLAGS := $(ARM_ARCH) -nostartfiles -T platform/arm/link.ld -Wl,--gc-sections -Wl,--use-blx \
               -Wl,-z,noexecstack -Wl,--no-warn-rwx-segments
ARM_SRCS := $(CORE_SRCS) src/app/intro.c platform/board.c platform/arm/arm.c $(GEN)/scene_intro.c
ARM_ELFS := $(BUILD)/arm/intro-fixed.elf $(BUILD)/arm/intro-float.elf
# The cheaper fixed-point variant's image (make arm builds it too; qemu.sh bench fixed16).
ARM_ELF_FIXED16 := $(BUILD)/arm/intro-fixed16.elf

# $(1) real (fixed, fixed16 or float), $(2) REAL_FIXED, $(3) libfixmath archive or empty,
# $(4) extra flags
define arm_variant
ARM_OBJS_$(1) := $$(patsubst %.c,$(BUILD)/obj/arm-$(1)/%.o,$(ARM_SRCS)) $(BUILD)/obj/arm-$(1)/start.o

$(BUILD)/obj/arm-$(1)/%.o: %.c Makefile | $(FIXMATH_STAMP)
	@mkdir -p $$(@D)
	$(ARM_CC) $(BASE_CFLAGS) $(OPT) $(ARM_CFLAGS) $(4) $$(ARM_FILE_CFLAGS) $(CPPFLAGS) -DREAL_FIXED=$(2) -DFX_COUNT_EVENTS=0 -MMD -MP -c $$< -o $$@

$(BUILD)/obj/arm-$(1)/start.o: platform/arm/start.S
	@mkdir -p $$(@D)
	$(ARM_CC) $(ARM_ARCH) -c $$< -o $$@

$(BUILD)/obj/arm-$(1)/libfixmath/%.o: $(FIXMATH_STAMP)
	@mkdir -p $$(@D)
	$(ARM_CC) -std=c11 $(OPT) $(ARM_CFLAGS) $(FIXMATH_DEFS) -w -c $(FIXMATH_DIR)/libfixmath/$$*.c -o $$@

$(BUILD)/obj/arm-$(1)/libfixmath.a: $$(patsubst %.c,$(BUILD)/obj/arm-$(1)/libfixmath/%.o,$(FIXMATH_SRCS))
	rm -f $$@ && arm-none-eabi-ar rcs $$@ $$^

$(BUILD)/arm/intro-$(1).elf: $$(ARM_OBJS_$(1)) $(3) platform/arm/link.ld platform/arm/text-order.ld
	@mkdir -p $$(@D)
	$(ARM_CC) $(ARM_LDFLAGS) -Wl,-Map=$$@.map -o $$@ $$(ARM_OBJS_$(1)) $(3) -lm -lc -lgcc

-include $$(ARM_OBJS_$(1):.o=.d)
endef
$(eval $(call arm_variant,fixed,1,$(BUILD)/obj/arm-fixed/libfixmath.a))
$(eval $(call arm_variant,float,0,))
$(eval $(call arm_variant,fixed16,1,$(BUILD)/obj/arm-fixed/libfixmath.a,$(FIXED16_DEFS)))
# Built for size, which keeps the fixed image within its 64 KiB: code that runs once per command or
# once per frame before the counted rendering starts, and probe.c. ARM_COLD_SRCS are Thumb at -Os
# (a quarter smaller than ARM code at -Os; the ARM926 runs both, the linker makes the calls between
# them blx): the board's command line (intro.c, knobs.c, board.c) and the timeline (scn.c: 790 B
# smaller than ARM -Os for about 2,000 instructions more a frame, uncounted) and the camera's set-up
# (camera.c: 200 B smaller for about 5,800 instructions more a frame, uncounted). ARM_SMALL_SRCS
# are ARM code at -Os: rt_scene_prepare (64-bit arithmetic, which Thumb-1 does through library
# calls: Thumb would save about 430 B for 69,000 instructions more a frame) and probe.c (rendering
# code of --mode probe, at -Os since docs/probe.md measured it; Thumb: probe mode +1.9 %).
# `make qemu-profile` shows no function of the other files inside the frames. arm.c (the board's
# backend) is Thumb too but for its semihosting call and its clock read (ARM, the read at -O2: the
# frame's count takes in part of each call). Within the files at -O2, FX_BOARD_THUMB (fixed/real.h)
# makes Thumb at -Os the functions that run outside the counted frames or only in non-default
# modes: u_sincos_deg, fx_norm32, rt_render_band_rows, rt_render_band_count, rt_render_work_size,
# and probe mode's rt_trace_pixel_from, trace_first, ss_probe_new and rt_probe_masks_of (the
# sizes each step saved: docs/arm.md). tests/scene_programs.sh builds its ARM images with the same
# flags (make arm-file-flags).
ARM_COLD_SRCS := src/app/intro.c src/scene/knobs.c platform/board.c src/scene/scn.c \
                 platform/arm/arm.c src/core/camera.c
ARM_COLD_CFLAGS := -Os -mthumb
ARM_SMALL_SRCS := src/core/probe.c src/core/prepare.c
ARM_SMALL_CFLAGS := -Os
$(foreach r,fixed float fixed16,$(patsubst %.c,$(BUILD)/obj/arm-$(r)/%.o,$(ARM_COLD_SRCS))): ARM_FILE_CFLAGS := $(ARM_COLD_CFLAGS)
$(foreach r,fixed float fixed16,$(patsubst %.c,$(BUILD)/obj/arm-$(r)/%.o,$(ARM_SMALL_SRCS))): ARM_FILE_CFLAGS := $(ARM_SMALL_CFLAGS)
# `defines` and the image's -D flags, then one `FILE FLAGS` line per ARM source built with flags
# of its own (tests/scene_programs.sh).
arm-file-flags:
	@echo 'defines $(filter -D%,$(ARM_CFLAGS))'
	@$(foreach f,$(ARM_COLD_SRCS),echo '$(f) $(ARM_COLD_CFLAGS)';) $(foreach f,$(ARM_SMALL_SRCS),echo '$(f) $(ARM_SMALL_CFLAGS)';)

# The profiler's TCG plugin for qemu-system-arm (platform/arm/qemu_profile.c): a host library.
PROFILE_PLUGIN := $(BUILD)/arm/qemu_profile.so
$(PROFILE_PLUGIN): platform/arm/qemu_profile.c
	@mkdir -p $(@D)
	$(CC) -std=c11 $(WARN) -O2 -shared -fPIC -fvisibility=hidden -o $@ $<

# ---- Cortex-M3 image: bare metal for qemu-system-arm -M lm3s6965evb (platform/m3/) --------
# The same core and src/app/intro.c at the OLED's 128x64, over the M3 backend: Thumb-2, soft-float
# ABI, libfixmath compiled from the same fetched source. make m3 builds it and prints its sizes;
# qemu-m3 plays it on the emulated OLED; qemu-m3-frames renders FRAMES into build/qemu-m3/.
M3_ARCH := -mcpu=cortex-m3 -mthumb -mfloat-abi=soft
# The Cortex-M boards' sizes, to fit their RAM: frames of 128x64; the scene structure for the
# intro's 7 objects, 2 lights and 7 materials (intro.c refuses a compiled scene with more); the
# view's candidate tiles, 32 a side on the M3 (a 128-pixel row in tiles of 4), 16 on the M0 (tiles
# of 8: half the view's 512 bytes of sets, the same pictures). Both render grids 4 and 8 (8 the
# default) in bands of up to 8 rows (a row of grid-8 squares, platform/band.c), the per-square
# arrays for grids up to RT_GRID_BUILD_MAX. The M0 (16 KiB) writes its band in 3-byte pixels
# (RT_PIXEL_RGB24: 3 KiB, not 4), and its stack holds the ray tree to the intro's depth, 5
# (INTRO_MAX_DEPTH; tests/m0.sh measures the RAM).
CM_BOARD_DEFS := -DINTRO_W=128 -DINTRO_H=64 -DBOARD_W=128 -DBOARD_H=64 \
                 -DRT_MAX_OBJECTS=8 -DRT_MAX_LIGHTS=2 -DRT_MAX_MATERIALS=8
# The chips (platform/cortexm.S, cortexm.c): the SysTick's clock, the external interrupts.
M3_CHIP_DEFS := -DCM_SYSTICK_HZ=50000000 -DCM_IRQS=64
M0_CHIP_DEFS := -DCM_SYSTICK_HZ=16000000 -DCM_IRQS=32
M3_BOARD_DEFS := -DRT_VIEW_TILES=32 -DBOARD_BAND_ROWS=8 -DRT_GRID_BUILD_MAX=8 $(M3_CHIP_DEFS)
M0_BOARD_DEFS := -DRT_VIEW_TILES=16 -DBOARD_BAND_ROWS=8 -DRT_GRID_BUILD_MAX=8 -DRT_PIXEL_RGB24=1 \
                 -DINTRO_MAX_DEPTH=5 $(M0_CHIP_DEFS)
M3_CFLAGS := $(M3_ARCH) -ffreestanding -ffunction-sections -fdata-sections $(CM_BOARD_DEFS) $(M3_BOARD_DEFS)
M3_LDFLAGS := $(M3_ARCH) -nostartfiles -T platform/m3/link.ld -Wl,--gc-sections -Wl,-z,noexecstack \
              -Wl,--no-warn-rwx-segments
M3_OBJ := $(BUILD)/obj/m3-fixed
M3_OBJS := $(patsubst %.c,$(M3_OBJ)/%.o,$(CORE_SRCS) src/app/intro.c platform/board.c platform/band.c platform/cortexm.c platform/m3/m3.c $(GEN)/scene_intro.c) \
           $(M3_OBJ)/start.o
M3_ELF := $(BUILD)/m3/intro-fixed.elf
M3_FRAMES ?= 0 425 875

$(M3_OBJ)/%.o: %.c Makefile | $(FIXMATH_STAMP)
	@mkdir -p $(@D)
	$(ARM_CC) $(BASE_CFLAGS) $(or $(M3_COLD_OPT),$(OPT)) $(M3_CFLAGS) $(CPPFLAGS) -DREAL_FIXED=1 -DFX_COUNT_EVENTS=0 -MMD -MP -c $< -o $@
# The command line runs once per command, outside the counted rendering: built for size.
$(M3_OBJ)/src/app/intro.o $(M3_OBJ)/src/scene/knobs.o $(M3_OBJ)/platform/board.o: M3_COLD_OPT := -Os
$(M3_OBJ)/start.o: platform/cortexm.S Makefile
	@mkdir -p $(@D)
	$(ARM_CC) $(M3_ARCH) $(M3_CHIP_DEFS) -c $< -o $@
$(M3_OBJ)/libfixmath/%.o: $(FIXMATH_STAMP)
	@mkdir -p $(@D)
	$(ARM_CC) -std=c11 $(OPT) $(M3_ARCH) -ffreestanding -ffunction-sections -fdata-sections $(FIXMATH_DEFS) -w -c $(FIXMATH_DIR)/libfixmath/$*.c -o $@
$(M3_OBJ)/libfixmath.a: $(patsubst %.c,$(M3_OBJ)/libfixmath/%.o,$(FIXMATH_SRCS))
	rm -f $@ && arm-none-eabi-ar rcs $@ $^
$(M3_ELF): $(M3_OBJS) $(M3_OBJ)/libfixmath.a platform/m3/link.ld
	@mkdir -p $(@D)
	$(ARM_CC) $(M3_LDFLAGS) -Wl,-Map=$@.map -o $@ $(M3_OBJS) $(M3_OBJ)/libfixmath.a -lc -lgcc
-include $(M3_OBJS:.o=.d)

m3: setup-arm
	@$(MAKE) -s --no-print-directory $(M3_ELF) $(PROFILE_PLUGIN)
	@tests/m3.sh --print

qemu-m3: setup-gui
	@$(MAKE) -s --no-print-directory $(M3_ELF)
	@platform/m3/qemu.sh play $(SETTINGS)

qemu-m3-frames: setup-arm
	@$(MAKE) -s --no-print-directory $(M3_ELF) $(BUILD)/rt-fixed $(PROFILE_PLUGIN)
	@platform/m3/qemu.sh frames $(SETTINGS) $(if $(filter command line,$(origin FRAMES)),$(FRAMES),$(M3_FRAMES))

# ---- Cortex-M0 image: bare metal for qemu-system-arm -M microbit (platform/m0/) -------------
# The M3's image for ARMv6-M (an nRF51822: 16 KiB of SRAM, no long multiply, no divide, no CLZ):
# the same core, intro, board.c and band.c; fixed/fx_armv6m.h gives the numeric layer's products
# in 32-bit pieces. make m0 builds it and prints its sizes; qemu-m0-frames renders FRAMES into
# build/qemu-m0/ through semihosting (the board has no display).
M0_ARCH := -mcpu=cortex-m0 -mthumb -mfloat-abi=soft
M0_CFLAGS := $(M0_ARCH) -ffreestanding -ffunction-sections -fdata-sections $(CM_BOARD_DEFS) $(M0_BOARD_DEFS)
M0_LDFLAGS := $(M0_ARCH) -nostartfiles -T platform/m0/link.ld -Wl,--gc-sections -Wl,-z,noexecstack \
              -Wl,--no-warn-rwx-segments
M0_OBJ := $(BUILD)/obj/m0-fixed
M0_OBJS := $(patsubst %.c,$(M0_OBJ)/%.o,$(CORE_SRCS) src/app/intro.c platform/board.c platform/band.c platform/cortexm.c platform/m0/m0.c $(GEN)/scene_intro.c) \
           $(M0_OBJ)/start.o
M0_ELF := $(BUILD)/m0/intro-fixed.elf

$(M0_OBJ)/%.o: %.c Makefile | $(FIXMATH_STAMP)
	@mkdir -p $(@D)
	$(ARM_CC) $(BASE_CFLAGS) $(or $(M0_COLD_OPT),$(OPT)) $(M0_CFLAGS) $(CPPFLAGS) -DREAL_FIXED=1 -DFX_COUNT_EVENTS=0 -MMD -MP -c $< -o $@
# The command line runs once per command, outside the counted rendering: built for size.
$(M0_OBJ)/src/app/intro.o $(M0_OBJ)/src/scene/knobs.o $(M0_OBJ)/platform/board.o: M0_COLD_OPT := -Os
$(M0_OBJ)/start.o: platform/cortexm.S Makefile
	@mkdir -p $(@D)
	$(ARM_CC) $(M0_ARCH) $(M0_CHIP_DEFS) -c $< -o $@
$(M0_OBJ)/libfixmath/%.o: $(FIXMATH_STAMP)
	@mkdir -p $(@D)
	$(ARM_CC) -std=c11 $(OPT) $(M0_ARCH) -ffreestanding -ffunction-sections -fdata-sections $(FIXMATH_DEFS) -w -c $(FIXMATH_DIR)/libfixmath/$*.c -o $@
$(M0_OBJ)/libfixmath.a: $(patsubst %.c,$(M0_OBJ)/libfixmath/%.o,$(FIXMATH_SRCS))
	rm -f $@ && arm-none-eabi-ar rcs $@ $^
$(M0_ELF): $(M0_OBJS) $(M0_OBJ)/libfixmath.a platform/m0/link.ld
	@mkdir -p $(@D)
	$(ARM_CC) $(M0_LDFLAGS) -Wl,-Map=$@.map -o $@ $(M0_OBJS) $(M0_OBJ)/libfixmath.a -lc -lgcc
-include $(M0_OBJS:.o=.d)

m0: setup-arm
	@$(MAKE) -s --no-print-directory $(M0_ELF) $(PROFILE_PLUGIN)
	@tests/m0.sh --print

qemu-m0-frames: setup-arm
	@$(MAKE) -s --no-print-directory $(M0_ELF) $(BUILD)/rt-fixed $(PROFILE_PLUGIN)
	@platform/m0/qemu.sh frames $(SETTINGS) $(if $(filter command line,$(origin FRAMES)),$(FRAMES),$(M3_FRAMES))

# build/fuzz-<real>/fuzz_scene: the scene parser, timeline and tracer under libFuzzer.
define fuzz_prog
$(BUILD)/$(1)/fuzz_scene: $(BUILD)/obj/$(1)/tests/fuzz_scene.o $(BUILD)/obj/$(1)/src/scene/scn_parse.o \
                         $(BUILD)/obj/$(1)/src/scene/scn_lex.o $(BUILD)/obj/$(1)/src/scene/scn_cwrite.o \
                         $$(CORE_OBJS_$(1)) $$(FIXMATH_LIB_$(1))
	@mkdir -p $$(@D)
	$(FUZZ_CC) -fsanitize=fuzzer $(FUZZ_SAN) -o $$@ $$^ -lm
endef
$(eval $(call fuzz_prog,fuzz-float))
$(eval $(call fuzz_prog,fuzz-fixed))
# The other inputs users give, which take no real arithmetic (one build): the command line
# through cli.c's option table, the image readers (image.c), the settings' parser (knobs.c).
FZ := $(BUILD)/obj/fuzz-fixed
$(BUILD)/fuzz/fuzz_cli: $(FZ)/tests/fuzz_cli.o $(FZ)/src/app/cli.o $(FZ)/src/scene/knobs.o $(FZ)/fixed/fx.o $(FZ)/src/app/image.o \
                        $(FZ)/src/app/outpath.o $(FIXMATH_LIB_fuzz-fixed)
	@mkdir -p $(@D)
	$(FUZZ_CC) -fsanitize=fuzzer $(FUZZ_SAN) -o $@ $^ -lpng -lm
$(BUILD)/fuzz/fuzz_image: $(FZ)/tests/fuzz_image.o $(FZ)/src/app/image.o
	@mkdir -p $(@D)
	$(FUZZ_CC) -fsanitize=fuzzer $(FUZZ_SAN) -o $@ $^ -lpng
$(BUILD)/fuzz/fuzz_knobs: $(FZ)/tests/fuzz_knobs.o $(FZ)/src/scene/knobs.o $(FZ)/fixed/fx.o $(FIXMATH_LIB_fuzz-fixed)
	@mkdir -p $(@D)
	$(FUZZ_CC) -fsanitize=fuzzer $(FUZZ_SAN) -o $@ $^ -lm
FUZZ_PROGS := $(BUILD)/fuzz-float/fuzz_scene $(BUILD)/fuzz-fixed/fuzz_scene \
              $(addprefix $(BUILD)/fuzz/,fuzz_cli fuzz_image fuzz_knobs)
fuzz-progs: $(FUZZ_PROGS)


# ---- user commands -------------------------------------------------------------------------
setup:
	@./setup.sh

setup-arm:
	@./setup.sh --arm

setup-test:
	@./setup.sh --test

setup-gui:
	@./setup.sh --arm --gui

# Plays the intro in a window; without a display, renders it headless into build/out/intro/
# with progress lines and prints frames per second (src/tools/run-intro.sh). REAL=fixed|float.
RUN_REAL ?= float
run: setup
	@$(MAKE) -s --no-print-directory all
	@src/tools/run-intro.sh $(if $(filter command line,$(origin REAL)),$(REAL),$(RUN_REAL))

test: setup-test
	@$(MAKE) --no-print-directory all san arm m3 m0 fuzz-progs
	@tests/run.sh

# The fast inner loop: the unit tests of both builds under the sanitizers and the demo scene's
# frames (fixed vs float, determinism, a sanitized render): two parts of make test's suite.
check: setup
	@$(MAKE) --no-print-directory all san
	@tests/run.sh unit frames

SECONDS ?= 60
fuzz: setup-test
	@$(MAKE) --no-print-directory fuzz-progs $(BUILD)/rt-fixed $(BUILD)/san-fixed/rt
	@tests/fuzz.sh $(SECONDS)

STEP ?= 1
soak: setup-test
	@$(MAKE) --no-print-directory all
	@tests/soak.sh $(STEP)

bench: setup-arm
	@$(MAKE) -s --no-print-directory all $(ARM_ELFS) $(M3_ELF) $(M0_ELF) $(PROFILE_PLUGIN)
	@tests/bench_all.sh

tradeoff: setup-test
	@$(MAKE) --no-print-directory all $(ARM_ELFS) $(PROFILE_PLUGIN)
	@tests/tradeoff.sh

bench-demo: setup
	@$(MAKE) --no-print-directory all
	@tests/bench.sh

bench-subsample: setup
	@$(MAKE) --no-print-directory all
	@tests/bench_subsample.sh

bench-effects: setup
	@$(MAKE) --no-print-directory all
	@tests/bench_effects.sh

bench-modes: setup-test setup-arm
	@$(MAKE) -s --no-print-directory all $(ARM_ELFS)
	@tests/bench_modes.sh

# Adaptive and probe mode against full mode on every scene; writes docs/quality.md (tests/quality.sh).
quality: setup
	@$(MAKE) -s --no-print-directory all
	@tests/quality.sh --doc docs/quality.md

STRESS_RAYS ?= 20000000
stress: setup
	@$(MAKE) --no-print-directory $(BUILD)/stress-fixed $(BUILD)/stress-float
	$(BUILD)/stress-fixed $(STRESS_RAYS)
	$(BUILD)/stress-float $(STRESS_RAYS)

# The pictures of README.md and docs/ rendered again with the current build; make test checks
# that the fixed-point ones are current (src/tools/docs-images.sh).
docs-images: setup
	@$(MAKE) --no-print-directory all
	@src/tools/docs-images.sh

scene-programs: setup-arm
	@$(MAKE) --no-print-directory all arm
	@tests/scene_programs.sh --check --arm

# ---- the ARM926 board under QEMU (platform/arm/qemu.sh) -----------------------------------
REAL ?= fixed
FRAMES ?= 0 250 500
QEMU_BENCH ?= 0 1200 24
SETTINGS ?=

arm: setup-arm
	@$(MAKE) -s --no-print-directory $(ARM_ELFS) $(ARM_ELF_FIXED16) $(PROFILE_PLUGIN)
	@tests/arm.sh --print

qemu: setup-gui
	@$(MAKE) -s --no-print-directory $(ARM_ELFS)
	@platform/arm/qemu.sh play $(REAL) $(SETTINGS)

qemu-frames: setup-arm
	@$(MAKE) -s --no-print-directory $(ARM_ELFS) $(PROFILE_PLUGIN)
	@platform/arm/qemu.sh frames $(REAL) $(SETTINGS) $(FRAMES)

qemu-bench: setup-arm
	@$(MAKE) -s --no-print-directory $(ARM_ELFS) $(PROFILE_PLUGIN)
	@tests/qemu_bench.sh $(QEMU_BENCH)

# platform/arm/text-order.ld again from the cycle plugin's counts of the benchmark's frames: the
# functions run inside frames, densest first, at the start of .text (fewer I-cache misses in the
# cycle model; no instruction or picture changes). Then make arm relinks.
arm-text-order: setup-arm
	@$(MAKE) -s --no-print-directory $(ARM_ELFS) $(PROFILE_PLUGIN)
	@platform/arm/text-order.sh

# The cycle model against hand-counted programs and the boards' icount figures (tests/cycles.sh;
# make test runs it too).
test-cycles: setup-arm
	@$(MAKE) -s --no-print-directory $(ARM_ELFS) $(M3_ELF) $(M0_ELF) $(PROFILE_PLUGIN)
	@tests/cycles.sh

# FRAMES defaults to two frames of the issue that asked for the profiler (425: textures, 875: glass).
qemu-profile: setup-arm
	@$(MAKE) -s --no-print-directory $(ARM_ELFS) $(ARM_ELF_FIXED16) $(M3_ELF) $(M0_ELF) $(PROFILE_PLUGIN)
	@platform/arm/profile.sh $(REAL) $(SETTINGS) $(if $(filter command line environment,$(origin FRAMES)),$(FRAMES),425 875)

clean:
	rm -rf $(BUILD)/obj $(BUILD)/san-float $(BUILD)/san-fixed $(BUILD)/san-fixed16 $(BUILD)/san-fixed-sd $(BUILD)/out $(BUILD)/test $(BUILD)/gen \
	       $(BUILD)/scenes $(BUILD)/bench $(BUILD)/arm $(BUILD)/qemu $(BUILD)/m3 $(BUILD)/qemu-m3 $(BUILD)/m0 $(BUILD)/qemu-m0 $(BUILD)/stress-fixed \
	       $(BUILD)/stress-float $(BUILD)/fuzz-float $(BUILD)/fuzz-fixed $(BUILD)/soak $(HOST_PROGS) \
	       $(PLAYERS)

distclean:
	rm -rf $(BUILD)
