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
from .vtkBrumeEvaluation import *  # noqa: F401,F403

# Render windows on X when DISPLAY names a display, else on EGL (no X
# server needed); BRUME_RENDER_WINDOW=x|egl|osmesa|auto chooses.
if not vtkBrumeRenderWindowSelection.Install():  # noqa: F405
    import warnings

    warnings.warn("brume: " + vtkBrumeRenderWindowSelection.GetLastError())  # noqa: F405

__version__ = "0.1.0"
