/* Which passes a refinement makes (view.h). */
#include "view.h"

int view_pass_plan(int32_t finest_block, int32_t spp, view_pass out[VIEW_MAX_PASSES])
{
    int n = 0;
    if (finest_block < 1) finest_block = 1;
    if (spp < 1) spp = 1;
    /* Each block pass costs a quarter of the next, so all of them together
     * add a third to the block-1 pass: the price of a picture at once. */
    for (int32_t block = VIEW_FIRST_BLOCK; block >= 1; block /= 2) {
        if (block > finest_block || (block == finest_block && spp > 1))
            out[n++] = (view_pass){block, 1};
    }
    out[n++] = (view_pass){finest_block, spp};
    return n;
}
