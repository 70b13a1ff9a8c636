/* noise.h: 3D Perlin gradient noise, fractal sums over octaves, and colour palettes. */
#ifndef FIXRAY_NOISE_H
#define FIXRAY_NOISE_H

#include "real.h"

/* The lattice repeats every RT_NOISE_PERIOD cells, so coordinates are reduced modulo it and
 * doubled per octave without ever leaving the fixed-point range. */
#define RT_NOISE_PERIOD 256
#define RT_NOISE_MAX_OCTAVES 8
/* Weight of a fully summed octave in rt_noise_detail.last. */
#define RT_NOISE_WEIGHT_ONE 256

/* How much of a fractal sum of `total` octaves a point gets: the first `octaves` of them, the
 * last one weighted by last / RT_NOISE_WEIGHT_ONE (1..RT_NOISE_WEIGHT_ONE); octaves = 0 sums
 * nothing. What is left out counts at its mean (turbulence: E|noise| per octave). */
typedef struct rt_noise_detail {
    int octaves, total;
    int32_t last;
} rt_noise_detail;

/* Hash of a lattice point (coordinates taken modulo RT_NOISE_PERIOD). */
uint32_t rt_noise_hash(int32_t i, int32_t j, int32_t k);

/* Gradient noise at p, in about [-1, 1]; continuous, zero at lattice points. Evaluated in
 * integers (Q16.16 lattice coordinates), the same in every build for the same coordinates. */
real rt_noise(vec3 p);

/* Sum of `octaves` noises, octave o at frequency 2^o and amplitude 2^-o. */
real rt_fbm(vec3 p, int octaves);

/* Sum of |noise|, octave o at frequency 2^o and amplitude 2^-o (Perlin's turbulence). */
real rt_turbulence(vec3 p, int octaves);

/* rt_fbm and rt_turbulence over the octaves of d, the last one weighted by d.last. */
real rt_fbm_detail(vec3 p, rt_noise_detail d);
real rt_turbulence_detail(vec3 p, rt_noise_detail d);

/* The octaves (at most `octaves`) worth summing where one pixel covers `footprint` noise
 * units (0 or less: every octave at full weight). Octave o, of wavelength 2^-o, is summed in
 * full while 2^-o >= 2 footprint and not at all once 2^-o <= footprint; in between its weight
 * falls linearly in log2(footprint), so the picture changes smoothly as the footprint does.
 * Integer arithmetic on the footprint's Q16.16 value: the same rule in every build. */
rt_noise_detail rt_noise_detail_for(real footprint, int octaves);

/* Colour of palette `id` at t (t taken modulo 1 would be the caller's choice; t is clamped to
 * [0, 1]). */
vec3 rt_palette(int id, real t);

/* Reduce every coordinate modulo RT_NOISE_PERIOD. */
vec3 rt_noise_wrap(vec3 p);

#endif
