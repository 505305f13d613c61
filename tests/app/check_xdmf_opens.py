"""ParaView opens the app's output: the volume mesh and the contact surface have the expected numbers of cells
and carry their arrays. usage: pvbatch check_xdmf_opens.py <output-dir>"""
import os
import sys

from paraview import servermanager
from paraview.simple import Xdmf3ReaderS

directory = sys.argv[1]
volume = Xdmf3ReaderS(FileName=[os.path.abspath(os.path.join(directory, 'mesh.xmf'))])
volume.UpdatePipeline()
contact = Xdmf3ReaderS(FileName=[os.path.abspath(os.path.join(directory, 'mesh_contact.xmf'))])
contact.UpdatePipeline()
summary = dict(line.strip().split(',') for line in open(os.path.join(directory, 'mesh_summary.csv')))
cells = volume.GetDataInformation().GetNumberOfCells()
faces = contact.GetDataInformation().GetNumberOfCells()
part_range = volume.GetCellDataInformation().GetArray('part').GetRange()
assert cells == int(summary['elements_total']), (cells, summary['elements_total'])
assert faces == int(summary['contact_elements']), (faces, summary['contact_elements'])
assert part_range == (0.0, 3.0), part_range
surface = servermanager.Fetch(contact)   # the points list is the volume's; check the points the faces use
heights = [surface.GetPoint(surface.GetCell(c).GetPointId(i))[2] for c in range(faces) for i in range(4)]
assert max(abs(z) for z in heights) < 1e-9, max(abs(z) for z in heights)   # the contact surface is at Z = 0
print('ParaView read', cells, 'hexahedra and', faces, 'contact faces')

states_file = os.path.join(directory, 'mesh_states.xmf')
if os.path.exists(states_file):   # the deformed states: a time series with displacement and I1 on the volume mesh
    states = Xdmf3ReaderS(FileName=[os.path.abspath(states_file)])
    states.UpdatePipelineInformation()
    times = list(states.TimestepValues)
    assert len(times) >= 2, times
    states.UpdatePipeline(times[-1])
    information = states.GetDataInformation()
    assert information.GetNumberOfCells() == cells, information.GetNumberOfCells()
    assert states.GetCellDataInformation().GetArray('I1') is not None
    largest = states.GetPointDataInformation().GetArray('displacement').GetRange(-1)[1]
    assert largest > 1.0, largest   # the last state is deformed
    print('ParaView read', len(times), 'states; the last one moved a node by', round(largest, 1), 'nm')
