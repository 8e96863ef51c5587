"""Brume: globally illuminated participating media as VTK modules.

The three phases of Jimenez & Pueyo (2003) as VTK algorithms:

>>> import brume
>>> scene = brume.vtkBrumeDefaultSceneSource()
>>> tracer = brume.vtkBrumeLightTracer()
>>> tracer.SetInputConnection(scene.GetOutputPort())
>>> reconstruction = brume.vtkBrumeRadianceReconstruction()
>>> reconstruction.SetInputConnection(0, scene.GetOutputPort())
>>> reconstruction.SetInputConnection(1, tracer.GetOutputPort())

then vtkBrumeSceneActors adds the textured surfaces and the slice volumes to
a vtkRenderer. Importing brume also registers the OpenGL implementation of
vtkBrumeSliceVolumeMapper with VTK's object factory. vtkBrumeImageError,
vtkBrumeErrorChart and vtkBrumeStabilitySweep measure images against the
reference path tracer on any scene.
"""

# ParaView's (or VTK's) own modules first: ours depend on them.
import vtkmodules.vtkCommonExecutionModel  # noqa: F401
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingVolumeOpenGL2  # noqa: F401

from .vtkBrumeDataModel import *  # noqa: F401,F403
from .vtkBrumeTracing import *  # noqa: F401,F403
from .vtkBrumeReconstruction import *  # noqa: F401,F403
from .vtkBrumeRendering import *  # noqa: F401,F403
from .vtkBrumeRenderingOpenGL2 import *  # noqa: F401,F403
from .vtkBrumeIO import *  # noqa: F401,F403
from .vtkBrumePipeline import *  # noqa: F401,F403
from .vtkBrumeEvaluation import *  # noqa: F401,F403

# Render windows on X when DISPLAY names a display, else on EGL (no X
# server needed); BRUME_RENDER_WINDOW=x|egl|osmesa|auto chooses.
if not vtkBrumeRenderWindowSelection.Install():  # noqa: F405
    import warnings

    warnings.warn("brume: " + vtkBrumeRenderWindowSelection.GetLastError())  # noqa: F405

# VTK's default vtkSMPTools backend here is Sequential, which would run every
# phase on one core: unless the user chose one (VTK_SMP_BACKEND_IN_USE, or
# vtkSMPTools.SetBackend after this import), Brume's filters use the
# STDThread backend on every core (VTK_SMP_MAX_THREADS caps the count), as
# the brume program does. Results do not depend on the number of threads.
def _use_all_cores():
    import os

    from vtkmodules.vtkCommonCore import vtkSMPTools

    if os.environ.get("VTK_SMP_BACKEND_IN_USE") or vtkSMPTools.GetBackend() != "Sequential":
        return
    if vtkSMPTools.SetBackend("STDThread"):
        maximum = os.environ.get("VTK_SMP_MAX_THREADS", "")
        vtkSMPTools.Initialize(int(maximum) if maximum.isdigit() else 0)


_use_all_cores()

__version__ = "0.1.0"
