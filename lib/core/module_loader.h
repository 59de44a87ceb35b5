/* Internal: finding, loading and checking shape modules. */
#ifndef HITRAY_LIB_CORE_MODULE_LOADER_H
#define HITRAY_LIB_CORE_MODULE_LOADER_H

#include "core/context_internal.h"

/* dlclose every module and free the tables. */
void hri_modules_unload_all(hr_context *ctx);

#endif
