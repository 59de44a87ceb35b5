/* A test module that claims a future shape ABI version: it must be refused
 * with a message naming its path and both versions. */
#include <hitray/shape_module.h>

static const hr_module_info info = {sizeof info, HR_SHAPE_ABI_VERSION + 98, "wrong_abi",
                                    "test: wrong ABI", NULL, 0, NULL, NULL, NULL};

HR_DEFINE_SHAPE_MODULE(host_version, host)
{
    (void)host_version;
    (void)host;
    return &info;
}
