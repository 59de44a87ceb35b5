/* Internal: one thread's last error on one context. */
#ifndef HITRAY_LIB_CORE_ERROR_SLOT_H
#define HITRAY_LIB_CORE_ERROR_SLOT_H

#include <hitray/common.h>

#include "util/errors.h"

typedef struct hr_error_slot {
    hr_status status;
    int32_t line, column;
    char file[512];
    char message[HR_ERROR_MESSAGE_SIZE];
} hr_error_slot;

#endif
