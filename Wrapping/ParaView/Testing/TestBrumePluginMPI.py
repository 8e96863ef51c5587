# pvbatch, one process or under mpirun: the plugin's pipeline on the default
# scene; prints a digest of every texture array that process 0 holds. Under
# mpirun each process traces its piece of the particles and the
# reconstruction sums the histograms across processes: the digest must be
# that of one process (ctest compares them). With "fixed" after the plugin,
# the reconstruction's FixedView is on: the view-dependent fog bins toward
# the eye and keeps no hits, to the same bits.
import hashlib
import sys

from paraview import servermanager as sm
from paraview.simple import *
from vtkmodules.util.numpy_support import vtk_to_numpy

LoadPlugin(sys.argv[1], ns=globals())
scene = BrumeDefaultScene()
tracer = BrumeLightTracer(Input=scene, NumberOfParticles=50000)
fixed = len(sys.argv) > 2 and sys.argv[2] == "fixed"
textures = BrumeRadianceReconstruction(Scene=scene, Hits=tracer, FixedView=int(fixed))
textures.UpdatePipeline()
# The filter's own PrintSelf (its class is not wrapped in this Python).
assert ("FixedView: %d" % fixed) in str(textures.GetClientSideObject())
data = sm.Fetch(textures, 0)  # the textures are process 0's output
digest = hashlib.sha256()
count = 0
for i in range(data.GetNumberOfPartitionedDataSets()):
    texture = data.GetPartitionedDataSet(i).GetPartition(0)
    for attributes in (texture.GetPointData(), texture.GetCellData()):
        for k in range(attributes.GetNumberOfArrays()):
            array = attributes.GetArray(k)
            digest.update(array.GetName().encode())
            digest.update(vtk_to_numpy(array).tobytes())
            count += 1
processes = sm.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
print("processes %d, texture arrays %d, fixed view %d" % (processes, count, fixed))
print("textures sha256 %s" % digest.hexdigest())
