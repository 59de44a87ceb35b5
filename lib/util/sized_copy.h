/* The struct_size rule for versioned structs (common.h), in one place.
 *
 * A caller's struct may be older (shorter) or newer (longer) than the
 * library's. Reading one in, only the bytes both sides know are copied over
 * the library's defaults, and the copy then says it is full size. Handing
 * one out, only the bytes both sides know are written, and struct_size tells
 * the caller how many that was. */
#ifndef HITRAY_LIB_UTIL_SIZED_COPY_H
#define HITRAY_LIB_UTIL_SIZED_COPY_H

#include <stdint.h>
#include <string.h>

static inline uint32_t hri_sized_common(uint32_t given, size_t full)
{
    return given < full ? given : (uint32_t)full;
}

/* Read the caller's *src over the defaulted full-size *dst. */
#define HR_SIZED_COPY_IN(dst, src)                                             \
    do {                                                                       \
        memcpy((dst), (src), hri_sized_common((src)->struct_size, sizeof *(dst))); \
        (dst)->struct_size = (uint32_t)sizeof *(dst);                          \
    } while (0)

/* Give the caller's *out as much of the full-size *full as it has room for. */
#define HR_SIZED_COPY_OUT(out, full)                                           \
    do {                                                                       \
        uint32_t sized_common_ = hri_sized_common((out)->struct_size, sizeof *(full)); \
        memcpy((out), (full), sized_common_);                                  \
        (out)->struct_size = sized_common_;                                    \
    } while (0)

#endif
