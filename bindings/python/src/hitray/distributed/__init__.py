"""hitray.distributed: renders and animations on a Dask cluster
(``dask.distributed``), bit for bit the images of one machine.

    import hitray, hitray.distributed
    scene, camera = hitray.load_sdl("scenes/demo.sdl")
    image = hitray.distributed.render(scene, camera, (1920, 1080), spp=16,
                                      client="tcp://scheduler:8786")
    hitray.distributed.render_frames(lambda i: (scene, orbit(i)), "frame_%04d.png", count=240)

A frame is cut into bands, each a window of the image (hr_render_options'
window) whose pixels are the full render's bits, so the image does not
depend on how it is cut, which worker rendered what, or workers lost on the
way (their bands are handed on). A band is rendered on all of a worker's
threads and sized by the workers' measured speed, so they finish together;
an animation sends whole frames while there are more frames than workers. The scene travels to every worker once, with
the files it references inside it. Needs the optional extra:
``pip install 'hitray[distributed]'``. The command line is
``python -m hitray.distributed`` (docs/distributed.md).
"""

from __future__ import annotations

from ._client import SchedulerUnreachable
from ._pack import MAX_SHIPPED_BYTES, ScenePack, ShippingError
from ._render import render, render_frames, windows
from ._report import Report, WorkerReport

__all__ = ["render", "render_frames", "windows", "Report", "WorkerReport", "ScenePack", "SchedulerUnreachable",
           "ShippingError", "MAX_SHIPPED_BYTES"]
