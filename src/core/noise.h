/* noise.h: 3D Perlin gradient noise, fractal sums over octaves, and colour palettes. */
#ifndef FIXRAY_NOISE_H
#define FIXRAY_NOISE_H

#include "real.h"

/* The lattice repeats every RT_NOISE_PERIOD cells, so coordinates are reduced modulo it and
 * doubled per octave without ever leaving the fixed-point range. */
#define RT_NOISE_PERIOD 256
#define RT_NOISE_MAX_OCTAVES 8

/* Hash of a lattice point (coordinates taken modulo RT_NOISE_PERIOD). */
uint32_t rt_noise_hash(int32_t i, int32_t j, int32_t k);

/* Gradient noise at p, in about [-1, 1]; continuous, zero at lattice points. */
real rt_noise(vec3 p);

/* Sum of `octaves` noises, octave o at frequency 2^o and amplitude 2^-o. */
real rt_fbm(vec3 p, int octaves);

/* Sum of |noise|, octave o at frequency 2^o and amplitude 2^-o (Perlin's turbulence). */
real rt_turbulence(vec3 p, int octaves);

/* Colour of palette `id` at t (t taken modulo 1 would be the caller's choice; t is clamped to
 * [0, 1]). */
vec3 rt_palette(int id, real t);

/* Reduce every coordinate modulo RT_NOISE_PERIOD. */
vec3 rt_noise_wrap(vec3 p);

#endif
