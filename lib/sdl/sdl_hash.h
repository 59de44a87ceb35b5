/* Internal: the hash of macro names (lib/sdl/sdl_macros.c's open-addressing
 * index). FNV-1a mixes each byte only into the low bits it touches, so names
 * chosen to agree in their low bits would share one probe run and make a
 * file of many defs load in quadratic time; MurmurHash3's final avalanche
 * step makes every bit of the result depend on every bit of the state.
 * A header of its own so the test can look at the index it spreads. */
#ifndef HITRAY_LIB_SDL_HASH_H
#define HITRAY_LIB_SDL_HASH_H

#include <stddef.h>
#include <stdint.h>

static inline size_t sdl_hash_name(const char *name)
{
    uint64_t h = 1469598103934665603u;
    for (; *name; name++) h = (h ^ (unsigned char)*name) * 1099511628211u;
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdu;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53u;
    h ^= h >> 33;
    return (size_t)h;
}

#endif
