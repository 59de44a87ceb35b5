/* hitray built-in shapes: the prototype of the module entry point.
 *
 * HR_DEFINE_SHAPE_MODULE defines the exported function without declaring it
 * first, which -Wmissing-prototypes reports; declaring it here, with the same
 * name, signature and visibility, keeps every module warning-free. Every
 * module that uses HR_DEFINE_SHAPE_MODULE includes it. */
#ifndef HITRAY_SHAPE_ENTRY_H
#define HITRAY_SHAPE_ENTRY_H

#include <hitray/shape_module.h>

HR_EXPORT_ATTR const hr_module_info *HR_SHAPE_MODULE_ENTRY(uint32_t host_version,
                                                           const hr_host *host);

#endif
