/* hitray built-in shapes: the metadata every built-in module gives in its
 * hr_module_info (a plugin writes its own). The version is the project's,
 * spelled from common.h's numbers so it cannot drift from them. */
#ifndef HITRAY_SHAPES_SHAPE_BUILTIN_H
#define HITRAY_SHAPES_SHAPE_BUILTIN_H

#include <hitray/shape_module.h>

#define SHAPE_BUILTIN_TEXT_(x) #x
#define SHAPE_BUILTIN_TEXT(x) SHAPE_BUILTIN_TEXT_(x)
#define SHAPE_BUILTIN_VERSION                                                  \
    SHAPE_BUILTIN_TEXT(HR_VERSION_MAJOR)                                       \
    "." SHAPE_BUILTIN_TEXT(HR_VERSION_MINOR) "." SHAPE_BUILTIN_TEXT(HR_VERSION_PATCH)

/* The designated initializers of version, author and url (the built-ins
 * name no url: they come with hitray itself). */
#define SHAPE_BUILTIN_METADATA                                                 \
    .version = SHAPE_BUILTIN_VERSION, .author = "the hitray authors", .url = NULL

#endif
