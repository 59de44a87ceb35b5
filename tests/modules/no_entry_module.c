/* A test "module" without the entry point: refused, naming its path. */
#include <hitray/shape_module.h>

HR_EXPORT_ATTR int not_a_shape_module(void);
HR_EXPORT_ATTR int not_a_shape_module(void) { return 42; }
