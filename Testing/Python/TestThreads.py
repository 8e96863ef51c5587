"""`import brume` runs Brume's filters on every core: VTK's Sequential default
backend becomes STDThread, unless the user chose a backend.

usage: python3 TestThreads.py EXPECTED_BACKEND
(run with and without VTK_SMP_BACKEND_IN_USE=Sequential)
"""
import sys

from vtkmodules.vtkCommonCore import vtkSMPTools

expected = sys.argv[1]
before = vtkSMPTools.GetBackend()
import brume  # noqa: E402,F401

after = vtkSMPTools.GetBackend()
print("vtkSMPTools backend: %s before import brume, %s after (%d threads)"
      % (before, after, vtkSMPTools.GetEstimatedNumberOfThreads()))
sys.exit(0 if after == expected else 1)
